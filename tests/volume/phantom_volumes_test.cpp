// The built-in phantoms: labels, ordering of tissue values, exact mirror
// symmetry (the renderer's symmetry test depends on it), physical shape
// independent of the grid, and clear errors.
#include "volume/phantom.hpp"
#include "volume_test_util.hpp"

#include <map>
#include <set>

namespace cutaway::test {
namespace {

std::map<int, double> meanValueByLabel(const Phantom& p) {
    std::map<int, double> sum;
    std::map<int, std::size_t> count;
    for (std::size_t i = 0; i < p.values.voxelCount(); ++i) {
        const int label = static_cast<int>(p.labels.raw(i));
        sum[label] += p.values.value(i);
        ++count[label];
    }
    for (auto& [label, s] : sum)
        s /= static_cast<double>(count[label]);
    return sum;
}

} // namespace

TEST(PhantomVolumes, NamesAndLabels) {
    EXPECT_EQ(phantomNames(), (std::vector<std::string>{"head", "orange"}));
    for (const std::string name : {"head", "orange"}) {
        SCOPED_TRACE(name);
        Phantom p = makePhantom(name, {48, 40, 36});
        EXPECT_EQ(p.values.type, VoxelType::U8);
        EXPECT_EQ(p.labels.type, VoxelType::U8);
        EXPECT_EQ(p.labels.dims, p.values.dims);
        std::set<int> labels;
        for (std::size_t i = 0; i < p.labels.voxelCount(); ++i)
            labels.insert(static_cast<int>(p.labels.raw(i)));
        EXPECT_EQ(labels, (std::set<int>{0, 1, 2, 3}));
        ASSERT_EQ(p.labelNames.size(), 4u);
        EXPECT_EQ(p.labelNames[0], "background");
        EXPECT_EQ(p.labels.raw(0), 0.0) << "a corner is background";
        EXPECT_EQ(p.values.raw(0), 0.0) << "background is air";
    }
}

TEST(PhantomVolumes, TissuesHaveTheirValueOrder) {
    const auto head = meanValueByLabel(makePhantom("head", {64, 64, 64}));
    const Phantom h = makePhantom("head", {8, 8, 8});
    EXPECT_EQ(h.labelNames[1], "skin");
    EXPECT_EQ(h.labelNames[2], "skull");
    EXPECT_EQ(h.labelNames[3], "brain");
    EXPECT_GT(head.at(2), head.at(3)); // bone brighter than brain
    EXPECT_GT(head.at(3), head.at(1)); // brain brighter than skin (as the demo TF assumes)
    EXPECT_GT(head.at(1), head.at(0)); // skin brighter than air

    const auto orange = meanValueByLabel(makePhantom("orange", {64, 64, 64}));
    const Phantom o = makePhantom("orange", {8, 8, 8});
    EXPECT_EQ(o.labelNames[1], "rind");
    EXPECT_EQ(o.labelNames[2], "pith");
    EXPECT_EQ(o.labelNames[3], "segments");
    EXPECT_GT(orange.at(3), orange.at(1));
    EXPECT_GT(orange.at(1), orange.at(2));
    EXPECT_GT(orange.at(2), orange.at(0));
}

TEST(PhantomVolumes, ExactlyMirrorSymmetricInX) {
    for (const std::string name : {"head", "orange"}) {
        for (glm::ivec3 dims : {glm::ivec3(40, 36, 30), glm::ivec3(41, 33, 29)}) {
            SCOPED_TRACE(name + " " + std::to_string(dims.x));
            const Phantom p = makePhantom(name, dims, {1.0, 1.2, 0.9});
            for (int z = 0; z < dims.z; ++z)
                for (int y = 0; y < dims.y; ++y)
                    for (int x = 0; x < dims.x / 2; ++x) {
                        const int m = dims.x - 1 - x;
                        ASSERT_EQ(p.values.value(x, y, z), p.values.value(m, y, z))
                            << x << "," << y << "," << z;
                        ASSERT_EQ(p.labels.value(x, y, z), p.labels.value(m, y, z));
                    }
        }
    }
}

// Shapes are defined in physical space: the same phantom on a coarser,
// anisotropic grid labels the same physical points the same way.
TEST(PhantomVolumes, ShapeFollowsPhysicalSpaceNotTheGrid) {
    const Phantom fine = makePhantom("head", {64, 64, 64}, {1.0, 1.0, 1.0});
    const Phantom coarse = makePhantom("head", {64, 64, 32}, {1.0, 1.0, 2.0});
    std::size_t agree = 0, total = 0;
    for (int z = 0; z < 32; ++z)
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                // Coarse voxel centre z = 2k + 1 mm lies between fine voxels 2k and 2k+1.
                const double c = coarse.labels.value(x, y, z);
                agree +=
                    c == fine.labels.value(x, y, 2 * z) || c == fine.labels.value(x, y, 2 * z + 1);
                ++total;
            }
    EXPECT_GT(static_cast<double>(agree) / static_cast<double>(total), 0.97);
}

// Each phantom is a continuous object of its box: the grid only samples it.
// On a grid three times finer over the same box, voxel 3i + 1's centre is
// the coarse voxel i's, so the two must hold the same value there (up to the
// rounding of a value that falls on a half when the centre's position is
// computed two ways). Control: the finer grid's next voxel, a third of a
// coarse voxel away, differs at the edges, as would an edge ramp that
// followed the grid (1.5 voxels wide on one grid, half a coarse voxel on
// the other).
TEST(PhantomVolumes, TheSameObjectAtThreeTimesTheResolution) {
    for (const std::string name : {"head", "orange"}) {
        SCOPED_TRACE(name);
        const glm::ivec3 n(30, 28, 32);
        const glm::dvec3 s(1.5, 1.5, 1.25);
        const Phantom coarse = makePhantom(name, n, s);
        const Phantom fine = makePhantom(name, 3 * n, s / 3.0);
        std::size_t total = 0, apart = 0, apartNext = 0;
        double worst = 0.0;
        for (int z = 0; z < n.z; ++z)
            for (int y = 0; y < n.y; ++y)
                for (int x = 0; x < n.x; ++x) {
                    const double c = coarse.values.value(x, y, z);
                    const double f = fine.values.value(3 * x + 1, 3 * y + 1, 3 * z + 1);
                    const double next = fine.values.value(3 * x + 2, 3 * y + 1, 3 * z + 1);
                    worst = std::max(worst, std::abs(c - f));
                    apart += c != f;
                    apartNext += std::abs(c - next) > 1.0;
                    ++total;
                }
        EXPECT_LE(worst, 1.0);
        EXPECT_LT(double(apart) / double(total), 1e-3);
        std::printf("%s: %zu of %zu apart, %zu for the next voxel\n", name.c_str(), apart, total,
                    apartNext);
        EXPECT_GT(double(apartNext) / double(total), 0.02) << "control: the next voxel";
    }
}

TEST(PhantomVolumes, BadRequestsAreInputErrors) {
    EXPECT_NE(inputError([] {
                  makePhantom("pear", {32, 32, 32});
              }).find("pear"),
              std::string::npos);
    EXPECT_FALSE(inputError([] { makePhantom("head", {4, 32, 32}); }).empty());
    EXPECT_FALSE(inputError([] { makePhantom("head", {32, 2000, 32}); }).empty());
}

} // namespace cutaway::test
