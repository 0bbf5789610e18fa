// objectMask (surface alignment's background segmentation): the background is
// the air connected to the border through 6-neighbours; enclosed cavities
// belong to the object. Checked against a plain breadth-first fill on random
// volumes (the fast fill scans runs; the reference visits voxel by voxel) and
// on shapes whose answer is known.
#include "volume/segmentation.hpp"

#include <gtest/gtest.h>
#include <queue>
#include <random>

namespace cutaway {
namespace {

std::vector<std::uint8_t> referenceMask(const Volume& v, double threshold) {
    const glm::ivec3 n = v.dims;
    std::vector<std::uint8_t> background(v.voxelCount(), 0);
    std::queue<glm::ivec3> open;
    const auto reach = [&](glm::ivec3 p) {
        if (glm::any(glm::lessThan(p, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(p, n)))
            return;
        const std::size_t i = v.index(p.x, p.y, p.z);
        if (background[i] || v.value(i) > threshold) return;
        background[i] = 1;
        open.push(p);
    };
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x)
                if (x == 0 || y == 0 || z == 0 || x == n.x - 1 || y == n.y - 1 || z == n.z - 1)
                    reach({x, y, z});
    while (!open.empty()) {
        const glm::ivec3 p = open.front();
        open.pop();
        for (int a = 0; a < 3; ++a)
            for (int s : {-1, 1}) {
                glm::ivec3 q = p;
                q[a] += s;
                reach(q);
            }
    }
    std::vector<std::uint8_t> object(background.size());
    for (std::size_t i = 0; i < object.size(); ++i)
        object[i] = background[i] ? 0 : 1;
    return object;
}

TEST(ObjectMask, MatchesABreadthFirstFillOnRandomVolumes) {
    std::mt19937 rng(7);
    for (const double density : {0.2, 0.35, 0.5, 0.65}) {
        for (const glm::ivec3 dims : {glm::ivec3(17, 9, 13), glm::ivec3(1, 12, 12),
                                      glm::ivec3(24, 1, 5), glm::ivec3(31, 29, 7)}) {
            Volume v = Volume::allocate(dims, VoxelType::U8);
            std::bernoulli_distribution solid(density);
            auto* data = reinterpret_cast<std::uint8_t*>(v.data.data());
            for (std::size_t i = 0; i < v.voxelCount(); ++i)
                data[i] = solid(rng) ? 200 : 10;
            EXPECT_EQ(objectMask(v, 100.0), referenceMask(v, 100.0))
                << "density " << density << ", dims " << dims.x << "x" << dims.y << "x" << dims.z;
        }
    }
}

TEST(ObjectMask, AnEnclosedCavityBelongsToTheObjectAndAWindowOpensIt) {
    const glm::ivec3 n(20, 20, 20);
    Volume v = Volume::allocate(n, VoxelType::U8);
    auto* data = reinterpret_cast<std::uint8_t*>(v.data.data());
    // A closed box shell from 4 to 15, hollow inside.
    for (int z = 4; z <= 15; ++z)
        for (int y = 4; y <= 15; ++y)
            for (int x = 4; x <= 15; ++x) {
                const bool wall = x == 4 || x == 15 || y == 4 || y == 15 || z == 4 || z == 15;
                data[v.index(x, y, z)] = wall ? 200 : 0;
            }
    std::vector<std::uint8_t> mask = objectMask(v, 100.0);
    EXPECT_EQ(mask[v.index(10, 10, 10)], 1) << "the cavity is inside the object";
    EXPECT_EQ(mask[v.index(1, 1, 1)], 0) << "the air outside is background";
    data[v.index(15, 10, 10)] = 0; // a one-voxel window in a wall
    mask = objectMask(v, 100.0);
    EXPECT_EQ(mask[v.index(10, 10, 10)], 0) << "through the window the cavity is outside";
    EXPECT_EQ(mask[v.index(4, 4, 4)], 1) << "the walls stay object";
}

} // namespace
} // namespace cutaway
