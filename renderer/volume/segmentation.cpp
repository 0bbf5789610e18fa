#include "volume/segmentation.hpp"

#include <algorithm>

namespace cutaway {

std::vector<std::uint8_t> objectMask(const Volume& volume, double threshold) {
    const glm::ivec3 n = volume.dims;
    const std::size_t count = volume.voxelCount();
    // 0: below the threshold, not yet reached; 1: object; 2: background (reached).
    std::vector<std::uint8_t> state(count);
    for (std::size_t i = 0; i < count; ++i)
        state[i] = volume.value(i) > threshold ? 1 : 0;
    // A scanline fill: a popped seed grows into its whole run along x, and
    // only the starts of unreached runs in the four neighbouring rows are
    // pushed, so most voxels are visited by the scans, not the stack.
    struct Seed {
        int x, y, z;
    };
    std::vector<Seed> stack;
    const std::size_t sy = std::size_t(n.x), sz = std::size_t(n.x) * std::size_t(n.y);
    const auto row = [&](int y, int z) { return state.data() + sy * y + sz * z; };
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x)
                if (x == 0 || y == 0 || z == 0 || x == n.x - 1 || y == n.y - 1 || z == n.z - 1)
                    if (row(y, z)[x] == 0) stack.push_back({x, y, z});
    const auto pushRuns = [&](int y, int z, int xl, int xr) {
        if (y < 0 || z < 0 || y >= n.y || z >= n.z) return;
        const std::uint8_t* r = row(y, z);
        for (int x = xl; x <= xr; ++x)
            if (r[x] == 0 && (x == xl || r[x - 1] != 0)) stack.push_back({x, y, z});
    };
    while (!stack.empty()) {
        const Seed s = stack.back();
        stack.pop_back();
        std::uint8_t* r = row(s.y, s.z);
        if (r[s.x] != 0) continue;
        int xl = s.x, xr = s.x;
        while (xl > 0 && r[xl - 1] == 0)
            --xl;
        while (xr + 1 < n.x && r[xr + 1] == 0)
            ++xr;
        std::fill(r + xl, r + xr + 1, std::uint8_t(2));
        pushRuns(s.y - 1, s.z, xl, xr);
        pushRuns(s.y + 1, s.z, xl, xr);
        pushRuns(s.y, s.z - 1, xl, xr);
        pushRuns(s.y, s.z + 1, xl, xr);
    }
    for (std::uint8_t& s : state)
        s = s == 2 ? 0 : 1;
    return state;
}

} // namespace cutaway
