// The pre-integration table (render/classify/preintegration.hpp) on the CPU: the
// model's closed forms, its symmetry, and the same table on any number of
// threads. No device.
#include "render/classify/preintegration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <gtest/gtest.h>
#include <random>

namespace cutaway::test {
namespace {

/// A table of `size` entries: bands of random colour and opacity, some
/// transparent, with sharp edges (the hardest case for the sub-steps).
std::vector<glm::vec4> bandedTable(std::size_t size, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<glm::vec4> table(size);
    glm::vec4 entry(0.0f);
    for (std::size_t i = 0; i < size; ++i) {
        if (i % 37 == 0) {
            const float alpha = unit(rng) < 0.3f ? 0.0f : unit(rng);
            entry = glm::vec4(unit(rng), unit(rng), unit(rng), alpha);
        }
        table[i] = entry;
    }
    return table;
}

TEST(Preintegration, AConstantMediumFollowsBeerLambert) {
    // Opacity alpha per reference length r: over a segment of length L the
    // opacity is 1 - (1 - alpha)^(L / r), and the premultiplied colour is the
    // colour times that opacity, whatever the front and back values.
    const glm::vec3 colour(0.2f, 0.5f, 0.9f);
    for (const double alpha : {0.05, 0.4, 0.9}) {
        for (const double segment : {0.25, 1.0, 3.0}) {
            const std::vector<glm::vec4> table(64, glm::vec4(colour, float(alpha)));
            const std::vector<glm::vec4> out = render::preintegrate(table, 0.5, segment, 32);
            const double opacity = 1.0 - std::pow(1.0 - alpha, segment / 0.5);
            for (const glm::vec4& e : out) {
                ASSERT_NEAR(e.w, opacity, 1e-6) << alpha << " " << segment;
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(e[c], colour[c] * opacity, 1e-6) << alpha << " " << segment;
            }
        }
    }
}

TEST(Preintegration, MatchesAFineIntegrationOfEachSegment) {
    // The model of preintegration.hpp integrated with 2000 midpoint steps a
    // segment: the table's resampling to n entries, the extinction
    // -ln(1 - alpha) / reference, front-to-back compositing. The table takes
    // one step per entry crossed, so it agrees to the steps' error; an entry
    // left out (a clear range misjudged) would be off by its whole opacity.
    // A continuous function, clear below 0.3 and above 0.3 + pi/6 (where its
    // ramp comes back to 0): one midpoint a step is then accurate (0.0009 at
    // worst when this was written), and many segments lie in clear values.
    std::vector<glm::vec4> table(1024);
    for (std::size_t i = 0; i < table.size(); ++i) {
        const float x = float(i) / float(table.size() - 1);
        const float ramp = std::sin(6.0f * (x - 0.3f));
        const bool clear = x < 0.3f || x > 0.3f + 3.14159265f / 6.0f;
        table[i] = glm::vec4(x, 1.0f - x, 0.5f + 0.5f * std::sin(5.0f * x),
                             clear ? 0.0f : 0.6f * ramp * ramp);
    }
    const int n = 48;
    const double reference = 1.0, segment = 1.0;
    const std::vector<glm::vec4> out = render::preintegrate(table, reference, segment, n);
    auto entry = [&](double i) { // the n-entry table at a fractional index
        auto resampled = [&](int k) {
            const double x = double(table.size() - 1) * k / (n - 1);
            const auto i0 = std::size_t(x);
            const std::size_t i1 = std::min(i0 + 1, table.size() - 1);
            return glm::mix(table[i0], table[i1], float(x - double(i0)));
        };
        const int k0 = int(i);
        const int k1 = std::min(k0 + 1, n - 1);
        const double t = i - k0;
        const glm::vec4 a = resampled(k0), b = resampled(k1);
        auto tau = [&](const glm::vec4& e) {
            return -std::log1p(-std::min(double(e.w), 0.999999)) / reference;
        };
        return std::pair{glm::dvec3(glm::mix(glm::vec3(a), glm::vec3(b), float(t))),
                         tau(a) * (1 - t) + tau(b) * t};
    };
    double worst = 0.0;
    int shown = 0;
    for (int b = 0; b < n; b += 3)
        for (int f = 0; f < n; f += 2) {
            const int steps = 2000;
            double transmittance = 1.0;
            glm::dvec3 colour(0.0);
            for (int k = 0; k < steps; ++k) {
                const auto [c, tau] = entry(f + (b - f) * (k + 0.5) / steps);
                const double a = 1.0 - std::exp(-tau * segment / steps);
                colour += transmittance * a * c;
                transmittance *= 1.0 - a;
            }
            const glm::vec4 got = out[std::size_t(b) * n + f];
            worst = std::max({worst, std::abs(got.w - (1.0 - transmittance)),
                              std::abs(got.x - colour.x), std::abs(got.y - colour.y),
                              std::abs(got.z - colour.z)});
            shown += got.w > 0.01f;
        }
    EXPECT_LT(worst, 0.004);
    EXPECT_GT(shown, 100); // segments that cross some material
    std::printf("worst difference %.5f over %d segments that show\n", worst, shown);
}

TEST(Preintegration, OpacityDoesNotDependOnTheDirection) {
    // A segment from s_f to s_b crosses the same material as one from s_b to
    // s_f: the same opacity; the colour differs (what lies in front shows).
    const int n = 96;
    const std::vector<glm::vec4> out = render::preintegrate(bandedTable(1024, 7), 1.0, 1.5, n);
    int colourDiffers = 0;
    for (int b = 0; b < n; ++b)
        for (int f = 0; f < b; ++f) {
            const glm::vec4 forth = out[std::size_t(b) * n + f];
            const glm::vec4 back = out[std::size_t(f) * n + b];
            ASSERT_NEAR(forth.w, back.w, 1e-6) << f << " " << b;
            colourDiffers += std::abs(forth.x - back.x) > 1e-3f;
        }
    EXPECT_GT(colourDiffers, 0);
}

TEST(Preintegration, TheTableIsTheSameOnAnyNumberOfThreads) {
    const std::vector<glm::vec4> table = bandedTable(4096, 11);
    const int n = 200;
    const std::vector<glm::vec4> one = render::preintegrate(table, 0.7, 1.0, n, 1);
    for (const unsigned threads : {0u, 2u, 3u, 7u, 1000u}) {
        const std::vector<glm::vec4> many = render::preintegrate(table, 0.7, 1.0, n, threads);
        ASSERT_EQ(many.size(), one.size());
        EXPECT_EQ(std::memcmp(many.data(), one.data(), one.size() * sizeof(glm::vec4)), 0)
            << threads << " threads";
    }
}

} // namespace
} // namespace cutaway::test
