// Bake times of what a volume and its operators need before the first frame:
// upload, gradients, the distance field and segment mask of feature alignment
// (paper sections 4.2, 4.3), and one operator map. Prints a table; asserts
// nothing. Usage: cutaway_bench_bake [SIZE] [REPEATS]   (default 256 3)
#include "bake/feature_bake.hpp"
#include "bake/gradient_bake.hpp"
#include "bake/operator_bake.hpp"
#include "bake/volume_upload.hpp"
#include "gpu/context.hpp"
#include "operators/operator_geometry.hpp"
#include "render/label_classes.hpp"
#include "volume/otsu.hpp"
#include "volume/phantom.hpp"
#include "volume/segmentation.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

using namespace cutaway;

namespace {

struct Row {
    std::string what;
    std::vector<double> ms;
};

Row time(const std::string& what, int repeats, const std::function<void()>& body) {
    Row row{what, {}};
    for (int i = 0; i < repeats; ++i) {
        const auto start = std::chrono::steady_clock::now();
        body();
        row.ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count());
    }
    std::sort(row.ms.begin(), row.ms.end());
    return row;
}

} // namespace

int main(int argc, char** argv) {
    const int size = argc > 1 ? std::atoi(argv[1]) : 256;
    const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
    if (size < 8 || size > 1024) {
        std::fprintf(stderr, "usage: cutaway_bench_bake [SIZE in 8..1024] [REPEATS]\n");
        return 2;
    }
    gpu::Context ctx(gpu::ContextOptions{});
    const Phantom phantom = makePhantom("head", glm::ivec3(size));
    const Volume& scan = phantom.values;
    const bake::ValueWindow window{0.0, 255.0};
    bake::GradientBaker gradients(ctx);
    bake::FeatureBaker features(ctx);
    bake::OperatorBaker operators(ctx);
    gpu::Image values = bake::uploadVolume(ctx, scan, window);

    double threshold = 0.0;
    std::vector<std::uint8_t> object, indicator;
    Volume objectVolume = Volume::allocate(scan.dims, VoxelType::U8, scan.spacing);
    std::vector<Row> rows;
    rows.push_back(time("upload (R16, normalized)", repeats,
                        [&] { values = bake::uploadVolume(ctx, scan, window); }));
    rows.push_back(time("gradients (GPU)", repeats, [&] { gradients.bake(values, scan.spacing); }));
    rows.push_back(time("Otsu threshold (CPU)", repeats, [&] { threshold = otsuThreshold(scan); }));
    rows.push_back(time("background segmentation (CPU flood fill)", repeats,
                        [&] { object = objectMask(scan, threshold); }));
    std::copy(object.begin(), object.end(),
              reinterpret_cast<std::uint8_t*>(objectVolume.data.data()));
    gpu::Image objectTexture = bake::uploadVolume(ctx, objectVolume, {0.0, 1.0});
    rows.push_back(time("distance field (GPU exact EDT)", repeats,
                        [&] { features.distanceField(objectTexture, scan.spacing, 0.5f); }));
    rows.push_back(time("segment indicator (CPU, labels)", repeats,
                        [&] { indicator = render::labelIndicator(phantom.labels, {2}); }));
    for (const double band : {0.0, 2.0, 4.0}) {
        char name[64];
        std::snprintf(name, sizeof name, "segment mask (GPU, band %.0f mm)", band);
        rows.push_back(time(name, repeats, [&] {
            features.segmentMask(indicator, scan.dims, scan.spacing, band);
        }));
    }
    shader::OperatorParams peeler{};
    peeler.a = glm::vec4(-0.2f, 0.5f, 0.2f, 2.2f);
    peeler.b = glm::vec4(0.8f, 0.0f, 0.0f, 0.0f);
    peeler.kind = glm::vec4(float(CW_OP_PEELER), 0.0f, 0.0f, 0.0f);
    const operators::LocalBox box = operators::deformedBounds(peeler, glm::ivec3(64));
    rows.push_back(time("operator map 64^3 (GPU, peeler)", repeats, [&] {
        operators.bake(peeler, glm::vec3(box.lo), glm::vec3(box.hi), glm::ivec3(64));
    }));

    std::printf("bake times, head phantom %d^3, %s, %d run(s) each\n\n", size,
                ctx.deviceName().c_str(), repeats);
    std::printf("| %-42s | %9s | %9s | %9s |\n", "bake", "min ms", "median ms", "max ms");
    std::printf("|%s|%s|%s|%s|\n", std::string(44, '-').c_str(), std::string(11, '-').c_str(),
                std::string(11, '-').c_str(), std::string(11, '-').c_str());
    for (const Row& r : rows)
        std::printf("| %-42s | %9.1f | %9.1f | %9.1f |\n", r.what.c_str(), r.ms.front(),
                    r.ms[r.ms.size() / 2], r.ms.back());
    return 0;
}
