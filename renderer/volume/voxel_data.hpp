#pragma once
// Private helpers of the readers whose headers say where the voxel data
// starts (NRRD, MetaImage): exactly the declared bytes, raw or compressed
// (gzip or zlib), no more and no fewer. Every error names `ctx`.
#include <cstddef>
#include <cstdint>
#include <istream>
#include <string>
#include <vector>

namespace cutaway::detail {

/// Where voxel data is read: `stream` at the data's start (after its
/// header), `fileSize` bytes in all, `ctx` naming it in messages.
struct VoxelSource {
    std::istream* stream = nullptr;
    std::string ctx;
    std::uint64_t fileSize = 0;
};

/// The `bytes` of raw data, `byteSkip` after the stream's position (-1:
/// the file's last bytes).
std::vector<std::byte> readRawVoxels(const VoxelSource& d, std::int64_t byteSkip,
                                     std::size_t bytes);

/// The `bytes` of gzip or zlib data, `byteSkip` counting decompressed bytes.
std::vector<std::byte> readCompressedVoxels(const VoxelSource& d, std::int64_t byteSkip,
                                            std::size_t bytes);

} // namespace cutaway::detail
