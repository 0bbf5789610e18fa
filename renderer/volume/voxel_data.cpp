#include "volume/voxel_data.hpp"

#include "core/error.hpp"
#include "volume/gzip.hpp"
#include "volume/io_util.hpp"

namespace cutaway::detail {

/// The `bytes` of raw data, `byteSkip` after the stream's position (-1:
/// the file's last bytes).
std::vector<std::byte> readRawVoxels(const VoxelSource& d, std::int64_t byteSkip,
                                     std::size_t bytes) {
    auto start = static_cast<std::uint64_t>(d.stream->tellg());
    if (byteSkip == -1) {
        // Data at the end of the file, whatever comes before it.
        start = d.fileSize < bytes ? d.fileSize + 1 : d.fileSize - bytes;
    } else {
        start += static_cast<std::uint64_t>(byteSkip);
    }
    const std::uint64_t available = start <= d.fileSize ? d.fileSize - start : 0;
    if (start > d.fileSize || available < bytes) {
        throw InputError(d.ctx + ": data truncated: expected " + std::to_string(bytes) +
                         " bytes after the header, found " + std::to_string(available));
    }
    d.stream->seekg(static_cast<std::streamoff>(start));
    std::vector<std::byte> data(bytes);
    if (readSome(*d.stream, data.data(), bytes) != bytes) {
        throw InputError(d.ctx + ": read error in the voxel data");
    }
    return data;
}

/// The `bytes` of gzip data, its byte skip counting decompressed bytes; no
/// more and no fewer.
std::vector<std::byte> readCompressedVoxels(const VoxelSource& d, std::int64_t byteSkip,
                                            std::size_t bytes) {
    GzipReader reader(*d.stream, d.ctx);
    if (reader.skip(static_cast<std::uint64_t>(byteSkip)) < static_cast<std::uint64_t>(byteSkip)) {
        throw InputError(d.ctx + ": data truncated: byte skip " + std::to_string(byteSkip) +
                         " goes past the end of the decompressed data");
    }
    std::vector<std::byte> data = readUpTo(reader, bytes);
    if (data.size() < bytes) {
        throw InputError(d.ctx + ": data truncated: expected " + std::to_string(bytes) +
                         " bytes after decompression, found " + std::to_string(data.size()));
    }
    std::byte extra{};
    if (reader.read(&extra, 1) != 0) {
        throw InputError(d.ctx + ": decompressed data exceeds the declared size (" +
                         std::to_string(bytes) + " bytes)");
    }
    return data;
}

} // namespace cutaway::detail
