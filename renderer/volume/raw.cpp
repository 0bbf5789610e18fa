// Headerless raw volumes: the caller supplies the layout.
#include "core/error.hpp"
#include "io/input_file.hpp"
#include "volume/byte_order.hpp"
#include "volume/io_util.hpp"
#include "volume/volume.hpp"

namespace cutaway {

Volume readRaw(const std::filesystem::path& path, const RawLayout& layout) {
    const std::string ctx = path.string();
    const std::int64_t sizes[3] = {layout.dims.x, layout.dims.y, layout.dims.z};
    const std::size_t bytes = detail::checkedByteCount(sizes, layout.type, ctx);
    for (int a = 0; a < 3; ++a)
        detail::checkSpacing(layout.spacing[a], a, ctx);
    InputFile file(path, "volume");
    const std::uint64_t fileSize = file.size();
    if (layout.offset > fileSize) {
        throw InputError(ctx + ": offset " + std::to_string(layout.offset) +
                         " is beyond the end of the file (" + std::to_string(fileSize) + " bytes)");
    }
    if (fileSize - layout.offset < bytes) {
        throw InputError(ctx + ": data truncated: expected " + std::to_string(bytes) +
                         " bytes after offset " + std::to_string(layout.offset) + ", found " +
                         std::to_string(fileSize - layout.offset));
    }
    std::istream& in = file.stream();
    in.seekg(static_cast<std::streamoff>(layout.offset));
    Volume volume;
    volume.dims = layout.dims;
    volume.spacing = layout.spacing;
    volume.type = layout.type;
    volume.data.resize(bytes);
    if (detail::readSome(in, volume.data.data(), bytes) != bytes) {
        throw InputError(ctx + ": read error in the voxel data");
    }
    if (detail::needsSwap(layout.bigEndian)) {
        detail::swapBytes(volume.data.data(), volume.voxelCount(), voxelSize(layout.type));
    }
    return volume;
}

} // namespace cutaway
