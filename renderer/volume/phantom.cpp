// Procedural phantoms. Shapes live in a normalised frame q = p / R, where p is
// the voxel centre in millimetres relative to the box centre and R a fixed
// fraction of the physical extent per axis, so the phantom fills the box
// whatever the voxel spacing. Each phantom is a continuous object of its box
// alone: its edges are smoothstep ramps of a fixed share of the box (the
// head's 3/128: 3 mm in a 128 mm box, wide enough that the demo's 160^3 grid
// resolves them; the orange's 1.5/128, which keeps its thin membranes), and
// the grid only samples it, so a phantom at twice the resolution over the
// same box is the same object.
//
// Mirror symmetry about x = extent.x / 2 is exact: each row is evaluated for
// the voxels with x <= centre only, at |x|, and copied to the mirrored voxel.
#include "volume/phantom.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cutaway {

namespace {

/// 0 outside, 1 inside, a smoothstep ramp of width `w` centred on the surface;
/// `inside` is a signed distance in the same units, positive inside.
inline double cover(double inside, double w) {
    const double t = std::clamp(inside / w + 0.5, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

inline double mix(double a, double b, double t) {
    return a + (b - a) * t;
}

inline double length3(double x, double y, double z) {
    return std::sqrt(x * x + y * y + z * z);
}

inline std::uint8_t toByte(double v) {
    return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
}

struct Sample {
    double value = 0.0;
    std::uint8_t label = 0;
};

/// Evaluates f(qx >= 0, qy, qz, ramp width, out) on half of every row and
/// mirrors it. `share` is R per axis as a share of the box, `ramp` the width
/// of an edge's ramp as a share of the box's side.
template <typename F>
void fillMirrored(Phantom& p, glm::dvec3 share, double ramp, F&& f) {
    const glm::ivec3 n = p.values.dims;
    const glm::dvec3 s = p.values.spacing;
    const glm::dvec3 radius = share * p.values.extent();
    // In q the ramp is `ramp` of the box along the axis whose R is its smallest share.
    const double w = ramp / std::min({share.x, share.y, share.z});
    auto* values = reinterpret_cast<std::uint8_t*>(p.values.data.data());
    auto* labels = reinterpret_cast<std::uint8_t*>(p.labels.data.data());
    const int half = (n.x + 1) / 2;
    std::vector<double> qx(static_cast<std::size_t>(half));
    for (int i = 0; i < half; ++i) {
        // |i + 0.5 - n/2| is exact in double, so mirrored voxels see the same input.
        qx[static_cast<std::size_t>(i)] = std::fabs(i + 0.5 - n.x * 0.5) * s.x / radius.x;
    }
    for (int k = 0; k < n.z; ++k) {
        const double qz = (k + 0.5 - n.z * 0.5) * s.z / radius.z;
        for (int j = 0; j < n.y; ++j) {
            const double qy = (j + 0.5 - n.y * 0.5) * s.y / radius.y;
            const std::size_t row = p.values.index(0, j, k);
            for (int i = 0; i < half; ++i) {
                Sample out;
                f(qx[static_cast<std::size_t>(i)], qy, qz, w, out);
                const std::uint8_t v = toByte(out.value);
                values[row + static_cast<std::size_t>(i)] = v;
                values[row + static_cast<std::size_t>(n.x - 1 - i)] = v;
                labels[row + static_cast<std::size_t>(i)] = out.label;
                labels[row + static_cast<std::size_t>(n.x - 1 - i)] = out.label;
            }
        }
    }
}

/// Signed distance (approximate, q units) inside an axis-aligned ellipsoid.
inline double ellipsoid(double x, double y, double z, glm::dvec3 c, glm::dvec3 a) {
    const double r = length3((x - c.x) / a.x, (y - c.y) / a.y, (z - c.z) / a.z);
    return (1.0 - r) * std::min({a.x, a.y, a.z});
}

// --- head ---------------------------------------------------------------------
// Face towards -y, top towards +z. Brain, skull and CSF gap are nested
// ellipsoids around the brain centre; the head ellipsoid adds the soft tissue
// of face and jaw below the skull.
constexpr glm::dvec3 kBrainCentre{0.0, 0.02, 0.12};
constexpr glm::dvec3 kBrainAxes{0.80, 0.84, 0.74};
constexpr double kSkullInner = 1.05; // skull surfaces as multiples of kBrainAxes
constexpr double kSkullOuter = 1.13;

/// Depth of the sulci at brain-frame direction u (unit), 0 on a gyrus to 1 in
/// the middle of a groove. Even in u.x: mirror-symmetric.
inline double sulcusDepth(double ux, double uy, double uz) {
    const double x2 = ux * ux;
    const double phase = 6.5 * uz + 2.2 * std::sin(5.3 * uy + 1.7 * std::cos(4.1 * ux)) +
                         1.4 * std::sin(7.1 * uy * uz + 2.9 * x2);
    const double s = std::fabs(std::sin(phase));
    const double t = std::min(s / 0.35, 1.0);
    const double groove = 1.0 - t * t * (3.0 - 2.0 * t);
    // The longitudinal fissure between the hemispheres, above the temporal lobes.
    const double f =
        std::max(0.0, 1.0 - std::fabs(ux) / 0.06) * std::clamp((uz + 0.3) / 0.4, 0.0, 1.0);
    return std::max(groove, 2.0 * f * f * (3.0 - 2.0 * f));
}

void head(double x, double y, double z, double w, Sample& out) {
    // Skin: the head ellipsoid (q unit sphere), nose and ears.
    const double r = length3(x, y, z);
    double skin = cover(1.0 - r, w);
    double softValue = mix(74.0, 88.0, std::clamp((r - 0.955) / 0.03, 0.0, 1.0));
    if (y < -0.7 + 2.0 * w && z < 2.0 * w) {
        const double nose = cover(ellipsoid(x, y, z, {0.0, -0.93, -0.25}, {0.09, 0.16, 0.20}), w);
        skin = std::max(skin, nose);
    }
    if (x > 0.9 - 2.0 * w && std::fabs(z + 0.05) < 0.22 + 2.0 * w) {
        const double ear = cover(ellipsoid(x, y, z, {0.97, 0.05, -0.05}, {0.07, 0.14, 0.22}), w);
        if (ear > skin) softValue = 86.0;
        skin = std::max(skin, ear);
    }
    double value = softValue * skin;
    if (skin <= 0.0) {
        out = {};
        return;
    }
    // Skull and brain in the brain frame: rb = 1 on the smooth brain hull.
    const double bx = (x - kBrainCentre.x) / kBrainAxes.x;
    const double by = (y - kBrainCentre.y) / kBrainAxes.y;
    const double bz = (z - kBrainCentre.z) / kBrainAxes.z;
    const double rb = length3(bx, by, bz);
    const double scale = 0.78; // q units per brain-frame unit, for the ramps
    const double skullOut = cover((kSkullOuter - rb) * scale, w);
    const double skullIn = cover((kSkullInner - rb) * scale, w);
    // Bone: dense outer and inner tables, a lighter diploe between them.
    const double t = std::clamp((rb - kSkullInner) / (kSkullOuter - kSkullInner), 0.0, 1.0);
    value = mix(value, 246.0 - 24.0 * 4.0 * t * (1.0 - t), skullOut);
    value = mix(value, 45.0, skullIn); // CSF between skull and brain

    // Eyes in the orbits: they replace bone, so the skull has sockets.
    double eye = 0.0;
    if (y < -0.66 + 2.0 * w) {
        const double d = length3(x - 0.36, y + 0.78, z + 0.20);
        eye = cover(0.12 - d, w);
        value = mix(value, 95.0, eye);
    }

    double brain = 0.0;
    if (rb < 1.0 + 2.0 * w / scale) {
        double depth = 0.0;
        if (rb > 0.72 && rb > 1e-9) depth = sulcusDepth(bx / rb, by / rb, bz / rb);
        brain = cover((1.0 - 0.07 * depth - rb) * scale, w);
        const double white = cover((0.90 - 0.05 * depth - rb) * scale, w);
        double brainValue = mix(108.0, 132.0, white);
        // Lateral ventricles: two CSF-filled lobes either side of the midline.
        const double vent = cover(ellipsoid(x, y, z, {0.13, 0.04, 0.14}, {0.07, 0.26, 0.10}), w);
        brainValue = mix(brainValue, 50.0, vent);
        value = mix(value, brainValue, brain);
    }
    out.value = value;
    if (brain >= 0.5)
        out.label = 3;
    else if (skullOut >= 0.5 && skullIn < 0.5 && eye < 0.5)
        out.label = 2;
    else if (skin >= 0.5)
        out.label = 1;
    else
        out.label = 0;
}

// --- orange -------------------------------------------------------------------
constexpr double kFlatten = 0.92;    // polar semi-axis / equatorial
constexpr double kPithStart = 0.935; // rind / white pith boundary (radius in q)
constexpr double kSegmentsEnd = 0.885;
constexpr double kCoreRadius = 0.085;
constexpr double kMembrane = 0.011; // half thickness of a radial membrane
constexpr int kSegments = 10;

void orange(double x, double y, double z, double w, Sample& out) {
    const double zf = z / kFlatten;
    const double r = length3(x, y, zf);
    if (r > 1.05 + 2.0 * w) {
        out = {};
        return;
    }
    // Peel: low bumps plus a lattice of oil-gland dimples, on the outer surface only.
    double surface = 1.0;
    if (r > 0.95 && r > 1e-9) {
        const double ux = x / r, uy = y / r, uz = zf / r;
        const double dimple =
            0.5 + 0.5 * std::cos(58.0 * ux) * std::cos(58.0 * uy) * std::cos(58.0 * uz);
        const double bumps = std::cos(7.0 * ux) * std::cos(6.0 * uy + 1.0) * std::cos(5.0 * uz);
        surface += 0.008 * bumps - 0.012 * dimple * dimple * dimple;
    }
    const double rind = cover(surface - r, w);
    double value = rind * mix(152.0, 168.0, std::clamp((r - kPithStart) / 0.05, 0.0, 1.0));
    const double pith = cover(kPithStart - r, w);
    value = mix(value, 90.0, pith);

    double segment = 0.0;
    if (r < kSegmentsEnd + 2.0 * w) {
        const double rxy = std::hypot(x, y);
        // Wedges around z with membranes at phi = 90 deg + k * 36 deg: the set
        // is mapped onto itself by x -> -x, so the pattern is mirror-symmetric.
        const double phi = std::atan2(y, x); // x >= 0 here: phi in [-90, 90] deg
        const double wedge = (std::numbers::pi / 2 - phi) / (2.0 * std::numbers::pi / kSegments);
        const double f = std::fabs(wedge - std::round(wedge)); // 0 on a membrane, 0.5 mid-wedge
        const double tangential = rxy * std::sin(f * 2.0 * std::numbers::pi / kSegments);
        segment = std::min({cover(kSegmentsEnd - r, w), cover(rxy - kCoreRadius, w),
                            cover(tangential - kMembrane, w)});
        if (segment > 0.0) {
            // Juice sacs: long cells radiating from the core, darker walls between.
            const double across = std::cos(f * 4.0 * std::numbers::pi * 2.0);
            const double along = std::cos(r * 26.0 + 3.0 * f);
            const double height = std::cos(zf * 34.0 + 2.0 * rxy);
            const double sac = (across * along + height) * 0.5; // in [-1, 1]
            value = mix(value, 200.0 + 12.0 * sac, segment);
        }
    }
    out.value = value;
    if (segment >= 0.5)
        out.label = 3;
    else if (pith >= 0.5)
        out.label = 2;
    else if (rind >= 0.5)
        out.label = 1;
    else
        out.label = 0;
}

} // namespace

std::vector<std::string> phantomNames() {
    return {"head", "orange"};
}

Phantom makePhantom(std::string_view name, glm::ivec3 dims, glm::dvec3 spacing) {
    const std::string ctx = "phantom '" + std::string(name) + "'";
    if (name != "head" && name != "orange") {
        throw InputError("unknown phantom '" + std::string(name) + "' (expected head or orange)");
    }
    for (int a = 0; a < 3; ++a) {
        if (dims[a] < 8 || dims[a] > 1024) {
            throw InputError(ctx + ": size " + std::to_string(dims.x) + "x" +
                             std::to_string(dims.y) + "x" + std::to_string(dims.z) +
                             " is out of range (each in [8, 1024])");
        }
        if (!std::isfinite(spacing[a]) || spacing[a] <= 0.0) {
            throw InputError(ctx + ": spacing must be finite and > 0");
        }
    }
    Phantom p;
    p.values = Volume::allocate(dims, VoxelType::U8, spacing);
    p.labels = Volume::allocate(dims, VoxelType::U8, spacing);
    if (name == "head") {
        // Head breadth : length : height ~ 0.83 : 0.92 : 1, with room for nose and ears.
        fillMirrored(p, glm::dvec3(0.38, 0.42, 0.45), 3.0 / 128.0, head);
        p.labelNames = {"background", "skin", "skull", "brain"};
    } else {
        fillMirrored(p, glm::dvec3(0.46), 1.5 / 128.0, orange);
        p.labelNames = {"background", "rind", "pith", "segments"};
    }
    return p;
}

} // namespace cutaway
