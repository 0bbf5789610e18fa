#pragma once
// Private helper: byte-order conversion for voxel buffers. Volumes are kept in
// host byte order; files say which order they use.
#include <algorithm>
#include <bit>
#include <cstddef>

namespace cutaway::detail {

/// True when data stored in the given order must be swapped to host order.
inline bool needsSwap(bool fileIsBigEndian) {
    return fileIsBigEndian != (std::endian::native == std::endian::big);
}

/// Reverses the bytes of each `width`-byte element in place (width 1: no-op).
inline void swapBytes(std::byte* data, std::size_t count, std::size_t width) {
    if (width <= 1) return;
    for (std::size_t i = 0; i < count; ++i) {
        std::reverse(data + i * width, data + (i + 1) * width);
    }
}

} // namespace cutaway::detail
