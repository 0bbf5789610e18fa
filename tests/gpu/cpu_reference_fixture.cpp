#include "bake/volume_upload.hpp"
#include "cpu_reference.hpp"
#include "job/render_job.hpp"
#include "render/camera.hpp"
#include "render/classify/preintegration.hpp"
#include "render/classify/transfer_table.hpp"
#include "shared/frame.h"
#include "shared/gradient.h"
#include "shared/shading.h"

#include <algorithm>
#include <cmath>

namespace cutaway::test {
namespace {

// The volume as the GPU sees it: normalized texels, a baked gradient quantized
// to SNORM8, both read with trilinear filtering and clamp-to-edge.
struct CpuVolume {
    glm::ivec3 dims;
    std::vector<float> values;
    std::vector<glm::vec4> gradients;

    template <typename T>
    T trilinear(const std::vector<T>& data, glm::dvec3 tc) const {
        const glm::dvec3 p = tc * glm::dvec3(dims) - 0.5;
        const glm::ivec3 i0 = glm::ivec3(glm::floor(p));
        const glm::dvec3 f = p - glm::dvec3(i0);
        T sum{};
        for (int c = 0; c < 8; ++c) {
            const glm::ivec3 o((c & 1), (c >> 1) & 1, (c >> 2) & 1);
            const glm::ivec3 q = glm::clamp(i0 + o, glm::ivec3(0), dims - 1);
            const double w = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
            sum += data[static_cast<std::size_t>(q.x + dims.x * (q.y + dims.y * q.z))] *
                   static_cast<float>(w);
        }
        return sum;
    }
};

CpuVolume cpuVolume(const Volume& volume, bake::ValueWindow window) {
    CpuVolume v;
    v.dims = volume.dims;
    for (uint16_t t : bake::normalizeVolume(volume, window))
        v.values.push_back(t / 65535.0f);
    for (const glm::vec4& g : cpuGradients(volume, window))
        v.gradients.push_back(glm::round(g * 127.0f) / 127.0f); // SNORM8, as stored
    return v;
}

glm::vec4 lookup1D(const std::vector<glm::vec4>& table, float u) {
    const float n = static_cast<float>(table.size());
    const float x = std::clamp(u * n - 0.5f, 0.0f, n - 1.0f);
    const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(x), table.size() - 2);
    return glm::mix(table[i], table[i + 1], x - float(i));
}

glm::vec4 lookup2D(const std::vector<glm::vec4>& table, int n, glm::vec2 uv) {
    const glm::vec2 p = glm::clamp(uv * float(n) - 0.5f, glm::vec2(0.0f), glm::vec2(float(n - 1)));
    const glm::ivec2 i = glm::min(glm::ivec2(p), glm::ivec2(n - 2));
    const glm::vec2 f = p - glm::vec2(i);
    auto t = [&](int x, int y) { return table[static_cast<std::size_t>(y * n + x)]; };
    return glm::mix(glm::mix(t(i.x, i.y), t(i.x + 1, i.y), f.x),
                    glm::mix(t(i.x, i.y + 1), t(i.x + 1, i.y + 1), f.x), f.y);
}

// What every slab of a reference render reads.
struct SlabContext {
    const CpuVolume& cv;
    glm::dvec3 half; // the volume's box is [-half, half]
    bool preintegrated;
    int refine; // /render/refine's sub-slabs, 1 when post-classified
    const std::vector<glm::vec4>& table1D;
    const std::vector<glm::vec4>& table2D;
    double stepRatio; // post-classification's opacity correction: mm per reference step
    const shader::FrameUniforms& u;

    glm::dvec3 tcOf(glm::dvec3 q) const { return (q + half) / (2.0 * half); }
    float value(glm::dvec3 q) const { return cv.trilinear(cv.values, tcOf(q)); }

    // The premultiplied colour of a slab from value `front` to `back`,
    // `ratio` times the table's opacity correction long.
    glm::vec4 classify(float front, float back, float ratio) const {
        if (!preintegrated) {
            const float n = float(render::kTransferTableSize);
            const glm::vec4 c = lookup1D(table1D, front * (n - 1) / n + 0.5f / n);
            if (c.w <= 0.0f) return glm::vec4(0.0f);
            const float alpha = shader::correctOpacity(c.w, float(stepRatio) * ratio);
            return glm::vec4(glm::vec3(c) * alpha, alpha);
        }
        const int n = render::kPreintegrationSize;
        const float s = (n - 1.0f) / n, o = 0.5f / n;
        const glm::vec4 slab = lookup2D(table2D, n, glm::vec2(front, back) * s + o);
        if (slab.w <= 0.0f) return glm::vec4(0.0f);
        const float alpha = shader::correctOpacity(slab.w, ratio);
        return glm::vec4(glm::vec3(slab) * (alpha / slab.w), alpha);
    }

    glm::dvec4 shade(glm::vec4 c, glm::dvec3 at, const shader::Viewer& viewer) const {
        const shader::Lighting light =
            shader::lightSample(cv.trilinear(cv.gradients, tcOf(at)), viewer, u);
        return glm::dvec4(glm::vec3(c) * light.diffuse + light.specular * c.w, c.w);
    }
};

// The shaded slab from world point p to p + step, as the shaders' backgroundSlab
// takes it: classified whole, and when something shows and it is
// pre-integrated, again in `refine` sub-slabs, each lit at its middle and
// composited front to back.
glm::dvec4 slabColor(const SlabContext& ctx, glm::dvec3 p, glm::dvec3 step,
                     const shader::Viewer& viewer, float obliquity) {
    const float front = ctx.value(p);
    const float back = ctx.preintegrated ? ctx.value(p + step) : front;
    const glm::vec4 c = ctx.classify(front, back, obliquity);
    if (c.w <= 0.0f) return glm::dvec4(0.0);
    if (!ctx.preintegrated) return ctx.shade(c, p, viewer);
    const int n = ctx.refine;
    glm::dvec4 sum(0.0);
    float a = front;
    for (int j = 1; j <= n; ++j) {
        const float b = j == n ? back : ctx.value(p + step * (double(j) / n));
        const glm::vec4 part = n == 1 ? c : ctx.classify(a, b, obliquity / float(n));
        if (part.w > 0.0f)
            sum += (1.0 - sum.w) * ctx.shade(part, p + step * ((j - 0.5) / n), viewer);
        a = b;
    }
    return sum;
}

} // namespace

std::vector<glm::vec4> cpuGradients(const Volume& volume, bake::ValueWindow window) {
    const glm::ivec3 dims = volume.dims;
    const std::vector<uint16_t> norm = bake::normalizeVolume(volume, window);
    shader::GradientParams params{};
    params.dims = dims;
    params.magnitudeScale =
        static_cast<float>(2.0 * std::min({volume.spacing.x, volume.spacing.y, volume.spacing.z}));
    params.halfInvSpacing = glm::vec3(0.5 / volume.spacing);
    auto at = [&](int x, int y, int z) {
        x = std::clamp(x, 0, dims.x - 1), y = std::clamp(y, 0, dims.y - 1),
        z = std::clamp(z, 0, dims.z - 1);
        return norm[volume.index(x, y, z)] / 65535.0f;
    };
    std::vector<glm::vec4> out;
    out.reserve(volume.voxelCount());
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                glm::vec3 d(0.0f);
                for (int a = -1; a <= 1; ++a)
                    for (int b = -1; b <= 1; ++b) {
                        const float w = shader::gradientWeight(a, b);
                        d.x += w * (at(x + 1, y + a, z + b) - at(x - 1, y + a, z + b));
                        d.y += w * (at(x + a, y + 1, z + b) - at(x + a, y - 1, z + b));
                        d.z += w * (at(x + a, y + b, z + 1) - at(x + a, y + b, z - 1));
                    }
                out.push_back(shader::encodeGradient(d, params));
            }
    return out;
}

Image renderCpuReference(const Scene& scene, const Volume& volume) {
    const bake::ValueWindow window = job::sceneWindow(scene, volume);
    const CpuVolume cv = cpuVolume(volume, window);
    const glm::dvec3 half = 0.5 * volume.extent();
    const render::Box box{-half, half};
    const int w = scene.render.width, h = scene.render.height;
    const render::CameraMatrices cam = render::computeCamera(scene.camera, box, w, h);
    const double minSpacing = std::min({volume.spacing.x, volume.spacing.y, volume.spacing.z});
    const double sliceMm = scene.render.sliceSpacing * minSpacing;
    const double unitMm = opacityUnit(scene, minSpacing);
    const bool preintegrated = scene.render.classification == Classification::Preintegrated;
    const std::vector<glm::vec4> table1D = render::tabulateTransfer(scene.transfer, window);
    const std::vector<glm::vec4> table2D =
        preintegrated ? render::preintegrate(table1D, unitMm, sliceMm) : std::vector<glm::vec4>{};

    // The same uniforms the GPU gets, for the shared lighting function.
    shader::FrameUniforms u{};
    u.eye = glm::vec4(glm::vec3(cam.eye), cam.perspective ? 1.0f : 0.0f);
    u.viewDir = glm::vec4(glm::vec3(cam.forward), float(sliceMm));
    u.material = glm::vec4(scene.lights.ambient, scene.render.shading.diffuse,
                           scene.render.shading.specular, scene.render.shading.shininess);
    u.headlight = glm::vec4(glm::vec3(scene.lights.headlight), 0.0f);
    for (std::size_t i = 0; i < scene.lights.directional.size(); ++i) {
        const auto& l = scene.lights.directional[i];
        u.lightDir[i] = glm::vec4(glm::vec3(-glm::normalize(l.direction)), 0.0f);
        u.lightColor[i] = glm::vec4(l.color * l.intensity, 0.0f);
    }
    u.flags = glm::vec4(float(scene.lights.directional.size()),
                        scene.render.shading.enabled ? 1.0f : 0.0f, 0.0f, 0.0f);

    const glm::dvec3 f = cam.forward;
    const glm::dmat4 clipToWorld = glm::inverse(cam.viewProj);
    double sMin = 1e300, sMax = -1e300;
    for (int i = 0; i < 8; ++i) {
        glm::dvec3 c((i & 1) ? half.x : -half.x, (i & 2) ? half.y : -half.y,
                     (i & 4) ? half.z : -half.z);
        sMin = std::min(sMin, glm::dot(f, c));
        sMax = std::max(sMax, glm::dot(f, c));
    }
    if (cam.perspective) sMin = std::max(sMin, glm::dot(f, cam.eye) + cam.nearPlane);

    const int refine = preintegrated ? scene.render.refine : 1;
    const SlabContext ctx{cv, half, preintegrated, refine, table1D, table2D, sliceMm / unitMm, u};
    Image img(w, h);
    for (int py = 0; py < h; ++py)
        for (int px = 0; px < w; ++px) {
            const double nx = (px + 0.5) / w * 2 - 1, ny = (py + 0.5) / h * 2 - 1;
            glm::dvec4 a = clipToWorld * glm::dvec4(nx, ny, 0, 1),
                       b = clipToWorld * glm::dvec4(nx, ny, 1, 1);
            const glm::dvec3 origin = glm::dvec3(a) / a.w;
            const glm::dvec3 dir = glm::normalize(glm::dvec3(b) / b.w - origin);
            glm::dvec4 acc(0.0);
            for (double k = std::ceil(sMin / sliceMm - 0.5); (k + 0.5) * sliceMm <= sMax; k += 1) {
                const double t = ((k + 0.5) * sliceMm - glm::dot(f, origin)) / glm::dot(f, dir);
                const glm::dvec3 p = origin + t * dir;
                if (glm::any(glm::lessThan(p, -half)) || glm::any(glm::greaterThan(p, half)))
                    continue;
                const glm::vec3 toEye =
                    cam.perspective ? glm::vec3(glm::normalize(cam.eye - p)) : -glm::vec3(f);
                const float obliquity = 1.0f / std::max(glm::dot(-toEye, glm::vec3(f)), 1e-3f);
                const shader::Viewer viewer = shader::viewerOf(toEye, u);
                const double stepMm = sliceMm * obliquity;
                const glm::dvec4 shaded =
                    slabColor(ctx, p, glm::dvec3(toEye) * -stepMm, viewer, obliquity);
                acc += (1.0 - acc.w) * shaded;
            }
            const glm::vec4 bg = scene.render.background;
            const glm::dvec4 bgp(glm::dvec3(bg) * double(bg.w), bg.w);
            acc += (1.0 - acc.w) * bgp;
            for (int c = 0; c < 4; ++c)
                img.pixel(px, py)[c] = float(acc[c]);
        }
    return img;
}

} // namespace cutaway::test
