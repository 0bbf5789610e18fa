// Material that moves off a segment (segment alignment, Eq. 4 with p = p0)
// reads the volume without the segment's values: the region texture the
// operator's shader samples (bake/feature_region.hpp) against its CPU twin
// (operators/moved_value.hpp), and a lifted scalp that shows no skull.
#include "bake/feature_bake.hpp"
#include "bake/feature_region.hpp"
#include "bake/volume_upload.hpp"
#include "gpu_fixture.hpp"
#include "job/render_job.hpp"
#include "operators/moved_value.hpp"
#include "render/gpu_volume.hpp"
#include "scene/scene.hpp"
#include "volume/phantom.hpp"

#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace cutaway::test {
namespace {

using nlohmann::json;

class MovedOffSegment : public GpuTest {};

// The region holds every voxel a trilinear sample in the box reads, two more
// on each side, and nothing beyond the grid.
TEST(FeatureRegion, CoversTheBoxsSamplesWithinTheGrid) {
    const glm::ivec3 dims(40, 30, 20);
    const glm::dvec3 spacing(1.0, 2.0, 0.5), gridLo(-20.0, -30.0, -5.0);
    // Voxel centres at gridLo + (i + 0.5) spacing: x 3.5 .. 7.2 mm -> voxel coordinates
    // 23 .. 26.7, read from voxel 23 to 27; y -30 .. -29 -> -0.5 .. 0: voxel 0 (clamped);
    // z 9.9 .. 30 -> 29.3 .. 69.5: beyond the last voxel, 19.
    const bake::VoxelRegion r =
        bake::regionCovering(dims, spacing, gridLo, {3.5, -30.0, 9.9}, {7.2, -29.0, 30.0});
    EXPECT_EQ(r.lo, glm::ivec3(21, 0, 19));
    EXPECT_EQ(r.lo + r.size - 1, glm::ivec3(29, 2, 19));
    // A box wholly outside the grid still gives one voxel.
    const bake::VoxelRegion out =
        bake::regionCovering(dims, spacing, gridLo, {100.0, 100.0, 100.0}, {110.0, 110.0, 110.0});
    EXPECT_EQ(out.size, glm::ivec3(1));
    EXPECT_EQ(out.lo, dims - 1);
}

// The texture over a region that does not start at the grid's corner: r is
// the segment mask as baked, g the moved value of the CPU twin, at every texel.
TEST_F(MovedOffSegment, RegionTextureMatchesItsCpuTwin) {
    const Phantom phantom = makePhantom("head", glm::ivec3(40));
    const Volume& scan = phantom.values;
    bake::GradientBaker gradients(ctx());
    const bake::ValueWindow window{0.0, 255.0};
    const render::GpuVolume volume =
        render::prepareVolume(ctx(), gradients, std::make_shared<Volume>(scan), window);
    std::vector<std::uint8_t> skull(scan.voxelCount());
    for (std::size_t i = 0; i < skull.size(); ++i)
        skull[i] = scan.value(i) >= 180.0;
    const bake::FeatureBaker baker(ctx());
    const gpu::Image mask = baker.segmentMask(skull, scan.dims, glm::dvec3(1.0), 2.0);
    const bake::VoxelRegion region{{3, 5, 7}, {30, 33, 29}};
    const gpu::Image texture = bake::FeatureRegionBaker(ctx()).bake(volume.values, mask, region);

    const auto maskBytes = gpu::downloadImage(ctx(), mask, bake::kFeatureLayout, 2);
    const auto regionBytes =
        gpu::downloadImage(ctx(), texture, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 4);
    const auto* m = reinterpret_cast<const std::uint16_t*>(maskBytes.data());
    const auto* rg = reinterpret_cast<const std::uint16_t*>(regionBytes.data());
    const std::vector<std::uint16_t> normalized = bake::normalizeVolume(scan, window);
    const auto valueAt = [&](int x, int y, int z) {
        return normalized[scan.index(x, y, z)] / 65535.0f;
    };
    const auto maskAt = [&](int x, int y, int z) {
        return glm::unpackHalf1x16(m[scan.index(x, y, z)]);
    };
    int refilled = 0;
    std::size_t t = 0;
    for (int z = 0; z < region.size.z; ++z)
        for (int y = 0; y < region.size.y; ++y)
            for (int x = 0; x < region.size.x; ++x, ++t) {
                const glm::ivec3 v = region.lo + glm::ivec3(x, y, z);
                ASSERT_EQ(rg[2 * t], m[scan.index(v.x, v.y, v.z)]) << "M at " << t;
                const float expected = operators::movedValueAt(scan.dims, v, valueAt, maskAt);
                const float got = glm::unpackHalf1x16(rg[2 * t + 1]);
                // Half precision: 2^-11 relative, and the sum's order.
                ASSERT_NEAR(got, expected, 1e-3f) << "moved value at " << t;
                refilled += std::abs(expected - valueAt(v.x, v.y, v.z)) > 0.05f;
            }
    EXPECT_GT(refilled, 500) << "the skull's outer and inner faces lie in the region";
}

// The head phantom from above, only the skull's values visible, and a
// scalp flap aligned to the skull (its values as the segment): the flap
// must show nothing. Before moved points read the region's values, their
// trilinear samples leaned on skull voxels wherever the flap had lain on
// them, and those samples showed as bone in the lifted flap.
TEST_F(MovedOffSegment, LiftedFlapShowsNoSkull) {
    const json skullOnly = json::parse(R"([{"value": 0, "color": [1, 1, 1], "alpha": 0},
        {"value": 188, "color": [1, 1, 1], "alpha": 0},
        {"value": 196, "color": [1, 1, 0.9], "alpha": 0.9},
        {"value": 255, "color": [1, 1, 0.9], "alpha": 0.9}])");
    const auto moved = [&](const std::string& method, const json& alignment) {
        const json document = {
            {"version", 1},
            {"volume", {{"phantom", "head"}, {"size", {64, 64, 64}}}},
            {"transfer", {{"points", skullOnly}}},
            {"camera", {{"orbit", {{"azimuth", 20}, {"elevation", 50}, {"distance", 260}}}}},
            {"render", {{"size", {96, 96}}, {"classification", "post"}, {"method", method}}},
            {"operators",
             json::array({{
                 {"type", "peeler"},
                 {"placement", {{"translate", {0, 0, 16}}, {"scale", {50, 50, 30}}}},
                 {"alignment", alignment},
                 {"params", {{"hinge", -10}, {"thickness", 24}, {"radius", 4}, {"angle", 130}}},
             }})},
        };
        Scene scene = parseScene(document, "/nonexistent", "test");
        scene.output.operatorId = true;
        const Image image = job::renderImage(ctx(), scene);
        int n = 0; // pixels whose first visible sample moved with the operator
        for (const float id : image.operatorIds)
            n += id == 0.0f;
        return n;
    };
    for (const std::string method : {"slicing", "raycast"}) {
        SCOPED_TRACE(method);
        EXPECT_GT(moved(method, {{"mode", "axis"}}), 200)
            << "control: without alignment the flap carries the skull up";
        EXPECT_EQ(moved(method, {{"mode", "segment"}, {"range", {180, 255}}, {"band", 2}}), 0);
    }
}

} // namespace
} // namespace cutaway::test
