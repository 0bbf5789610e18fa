#include "volume/io_util.hpp"

#include "core/error.hpp"
#include "volume/read_budget.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>

namespace cutaway::detail {

namespace {

std::string prefix(std::string_view context) {
    return std::string(context) + ": ";
}

} // namespace

std::size_t checkedByteCount(const std::int64_t sizes[3], VoxelType type,
                             std::string_view context) {
    static constexpr const char* kAxis[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
        if (sizes[a] < 1) {
            throw InputError(prefix(context) + "size along " + kAxis[a] + " is " +
                             std::to_string(sizes[a]) + " (sizes must each be >= 1)");
        }
        if (sizes[a] > std::numeric_limits<int>::max()) {
            throw InputError(prefix(context) + "size along " + kAxis[a] + " is " +
                             std::to_string(sizes[a]) + ": volume too large");
        }
    }
    // Each factor is < 2^31, so checking after every multiplication cannot overflow.
    std::uint64_t voxels = 1;
    for (int a = 0; a < 3; ++a) {
        voxels *= static_cast<std::uint64_t>(sizes[a]);
        if (voxels > kMaxVoxels) {
            throw InputError(prefix(context) + "volume too large: " + std::to_string(sizes[0]) +
                             "x" + std::to_string(sizes[1]) + "x" + std::to_string(sizes[2]) +
                             " exceeds the limit of 2^31 voxels");
        }
    }
    const std::uint64_t bytes = voxels * voxelSize(type);
    if (bytes > kMaxBytes) {
        throw InputError(prefix(context) + "volume too large: " + std::to_string(bytes) +
                         " bytes of voxel data exceeds the limit of 8 GiB");
    }
    if (bytes > readBudget()) {
        throw InputError(prefix(context) + "its " + std::to_string(sizes[0]) + "x" +
                         std::to_string(sizes[1]) + "x" + std::to_string(sizes[2]) + " " +
                         std::string(voxelTypeName(type)) + " voxels need " +
                         std::to_string(bytes >> 20) + " MiB, more than the " +
                         std::to_string(readBudget() >> 20) +
                         " MiB reading may take (--read-budget; by default half the machine's "
                         "memory)");
    }
    return static_cast<std::size_t>(bytes);
}

void checkSpacing(double spacing, int axis, std::string_view context) {
    static constexpr const char* kAxis[3] = {"x", "y", "z"};
    if (!std::isfinite(spacing) || spacing <= 0.0) {
        throw InputError(prefix(context) + "spacing along " + kAxis[axis] + " is " +
                         formatDouble(spacing) + " (spacing must be finite and > 0)");
    }
    if (spacing < kMinSpacing || spacing > kMaxSpacing) {
        throw InputError(prefix(context) + "spacing along " + kAxis[axis] + " is " +
                         formatDouble(spacing) +
                         " mm, outside the 1e-9 to 1e9 mm cutaway "
                         "renders (a nanometre is 1e-6 mm)");
    }
}

MemoryBuffer::MemoryBuffer(std::span<const std::byte> bytes) {
    // The get area is only read from: std::streambuf just wants non-const pointers.
    char* begin = const_cast<char*>(reinterpret_cast<const char*>(bytes.data()));
    setg(begin, begin, begin + bytes.size());
}

MemoryBuffer::pos_type MemoryBuffer::seekoff(off_type offset, std::ios_base::seekdir dir,
                                             std::ios_base::openmode which) {
    const off_type size = egptr() - eback();
    off_type base = 0;
    if (dir == std::ios_base::cur)
        base = gptr() - eback();
    else if (dir == std::ios_base::end)
        base = size;
    if ((which & std::ios_base::in) == 0 || offset < -base || offset > size - base) {
        return pos_type(off_type(-1));
    }
    setg(eback(), eback() + (base + offset), egptr());
    return pos_type(base + offset);
}

MemoryBuffer::pos_type MemoryBuffer::seekpos(pos_type position, std::ios_base::openmode which) {
    return seekoff(off_type(position), std::ios_base::beg, which);
}

std::size_t readSome(std::istream& in, std::byte* dst, std::size_t size) {
    // Reads in chunks so a size beyond std::streamsize is still fine.
    std::size_t done = 0;
    constexpr std::size_t kChunk = std::size_t{1} << 30;
    while (done < size && in) {
        const std::size_t want = std::min(kChunk, size - done);
        in.read(reinterpret_cast<char*>(dst + done), static_cast<std::streamsize>(want));
        const auto got = static_cast<std::size_t>(in.gcount());
        done += got;
        if (got < want) break;
    }
    return done;
}

bool parseInt(std::string_view text, std::int64_t& value) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    if (text.empty()) return false;
    const auto* end = text.data() + text.size();
    const auto result = std::from_chars(text.data(), end, value);
    return result.ec == std::errc() && result.ptr == end;
}

bool parseDouble(std::string_view text, double& value) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    if (text.empty()) return false;
    const auto* end = text.data() + text.size();
    const auto result = std::from_chars(text.data(), end, value);
    return result.ec == std::errc() && result.ptr == end;
}

std::string formatDouble(double value) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string toLower(std::string_view text) {
    std::string out(text);
    for (char& c : out)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

std::string_view trim(std::string_view text) {
    const auto isSpace = [](char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; };
    while (!text.empty() && isSpace(text.front()))
        text.remove_prefix(1);
    while (!text.empty() && isSpace(text.back()))
        text.remove_suffix(1);
    return text;
}

} // namespace cutaway::detail
