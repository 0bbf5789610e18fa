#pragma once
// Private helpers shared by the volume readers and the writer: limits on what a
// header may declare, file checks, and number parsing. Every error names the
// file (`context`) it is about.
#include "volume/volume.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <streambuf>
#include <string>
#include <string_view>

namespace cutaway::detail {

/// Largest grid a file may declare: 2^31 voxels and 8 GiB of voxel data, so a
/// hostile header cannot make us allocate absurd memory.
constexpr std::uint64_t kMaxVoxels = std::uint64_t{1} << 31;
constexpr std::uint64_t kMaxBytes = std::uint64_t{8} << 30;

/// Checks declared sizes (each >= 1, within the limits above and the read
/// budget, volume/read_budget.hpp) and returns the byte count of the voxel
/// data. Throws InputError naming `context`.
std::size_t checkedByteCount(const std::int64_t sizes[3], VoxelType type, std::string_view context);

/// Voxel spacings cutaway renders, in mm: from a picometre to a thousand
/// kilometres, far beyond electron microscopy (nanometres) and astronomy's
/// grids in any unit a file names as mm.
constexpr double kMinSpacing = 1e-9;
constexpr double kMaxSpacing = 1e9;

/// Spacing must be finite and within [kMinSpacing, kMaxSpacing]; `axis` is
/// 0, 1, 2 for x, y, z.
void checkSpacing(double spacing, int axis, std::string_view context);

/// A read-only, seekable stream buffer over bytes in memory (not copied: they
/// must outlive it), so the readers take `std::istream in(&buffer)` as they
/// take a file.
class MemoryBuffer : public std::streambuf {
public:
    explicit MemoryBuffer(std::span<const std::byte> bytes);

protected:
    pos_type seekoff(off_type offset, std::ios_base::seekdir dir,
                     std::ios_base::openmode which) override;
    pos_type seekpos(pos_type position, std::ios_base::openmode which) override;
};

/// Reads up to `size` bytes; returns how many were read (fewer only at the end).
std::size_t readSome(std::istream& in, std::byte* dst, std::size_t size);

/// Parses a whole token as a number; false when it is not one. Doubles accept
/// "nan", "inf" and a leading '+'.
bool parseInt(std::string_view text, std::int64_t& value);
bool parseDouble(std::string_view text, double& value);

/// Formats a double so that parsing it gives back the same value.
std::string formatDouble(double value);

std::string toLower(std::string_view text);

std::string_view trim(std::string_view text);

} // namespace cutaway::detail
