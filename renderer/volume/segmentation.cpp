#include "volume/segmentation.hpp"

namespace cutaway {

std::vector<std::uint8_t> objectMask(const Volume& volume, double threshold) {
    const glm::ivec3 n = volume.dims;
    const std::size_t count = volume.voxelCount();
    // 0: below the threshold, not yet reached; 1: object; 2: background (reached).
    std::vector<std::uint8_t> state(count);
    for (std::size_t i = 0; i < count; ++i)
        state[i] = volume.value(i) > threshold ? 1 : 0;
    std::vector<std::size_t> stack;
    const auto seed = [&](std::size_t i) {
        if (state[i] == 0) {
            state[i] = 2;
            stack.push_back(i);
        }
    };
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x)
                if (x == 0 || y == 0 || z == 0 || x == n.x - 1 || y == n.y - 1 || z == n.z - 1)
                    seed(volume.index(x, y, z));
    const std::size_t sx = 1, sy = std::size_t(n.x), sz = std::size_t(n.x) * std::size_t(n.y);
    while (!stack.empty()) {
        const std::size_t i = stack.back();
        stack.pop_back();
        const int x = int(i % sy), y = int((i / sy) % std::size_t(n.y)), z = int(i / sz);
        if (x > 0) seed(i - sx);
        if (x + 1 < n.x) seed(i + sx);
        if (y > 0) seed(i - sy);
        if (y + 1 < n.y) seed(i + sy);
        if (z > 0) seed(i - sz);
        if (z + 1 < n.z) seed(i + sz);
    }
    for (std::uint8_t& s : state)
        s = s == 2 ? 0 : 1;
    return state;
}

} // namespace cutaway
