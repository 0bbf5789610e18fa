#include "operators/deformed_volume.hpp"

#include "core/error.hpp"
#include "operators/moved_value.hpp"
#include "operators/operator_geometry.hpp"
#include "shared/feature.h"
#include "shared/feature_bake.h"
#include "shared/operators.h"
#include "volume/io_util.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>

namespace cutaway::operators {
namespace {

// A world point (mm, origin at the volume's centre) in the volume's grid:
// its continuous voxel coordinate (voxel centres at whole numbers) and
// whether it lies in the volume's box (the shader's inVolume).
struct GridPoint {
    glm::dvec3 voxel;
    bool inside = false;
    /// The segment mask of the segment-aligned operator this point moved
    /// with: its trilinear sample reads movedValueAt (moved_value.hpp).
    const std::vector<float>* movedOffSegment = nullptr;
};

GridPoint locate(const PlacedVolume& in, glm::dvec3 world) {
    const glm::dvec3 t = (world - in.worldLo) / in.volume.extent();
    return {t * glm::dvec3(in.volume.dims) - 0.5,
            glm::all(glm::greaterThanEqual(t, glm::dvec3(0.0))) &&
                glm::all(glm::lessThanEqual(t, glm::dvec3(1.0)))};
}

// Trilinear interpolation of at(x, y, z) at a voxel coordinate, clamped at the
// edge voxels like the GPU sampler.
template <class At>
double trilinear(glm::ivec3 dims, glm::dvec3 voxel, At&& at) {
    const glm::ivec3 i0 = glm::ivec3(glm::floor(voxel));
    const glm::dvec3 f = voxel - glm::dvec3(i0);
    double value = 0.0;
    for (int c = 0; c < 8; ++c) {
        const glm::ivec3 o(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        const glm::ivec3 q = glm::clamp(i0 + o, glm::ivec3(0), dims - 1);
        const double w = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
        if (w != 0.0) value += w * at(q.x, q.y, q.z);
    }
    return value;
}

// The voxel nearest to a voxel coordinate, clamped to the grid (the shader's
// texelFetch at floor(tc * dims)).
glm::ivec3 nearestVoxel(glm::ivec3 dims, glm::dvec3 voxel) {
    return glm::clamp(glm::ivec3(glm::floor(voxel + 0.5)), glm::ivec3(0), dims - 1);
}

// An operator placed in the world, with the feature field its alignment reads.
struct Placed {
    const OperatorSpec* spec;
    WorldBox box;
    glm::dmat4 worldToLocal;
    FeatureField field;             // on the input's grid; null for axis alignment
    bool keepSegmentVoxels = false; // Resampling::keepSegmentVoxels
};

// The feature mask M at a point of the input's grid (maskAt in the shader's
// operator_sample.h): 0 for axis alignment. With `keepVoxels` every voxel of
// a segment counts as feature.
float maskAt(const Placed& op, const Volume& grid, glm::dvec3 voxel, bool keepVoxels) {
    if (!op.field) return 0.0f;
    const std::vector<float>& field = *op.field;
    const float f = static_cast<float>(trilinear(
        grid.dims, voxel, [&](int x, int y, int z) { return field[grid.index(x, y, z)]; }));
    const Alignment& a = op.spec->alignment;
    if (a.mode == AlignmentMode::Surface)
        return shader::surfaceMask(f, static_cast<float>(a.depth), static_cast<float>(a.band));
    if (!keepVoxels) return f;
    const glm::ivec3 nearest = nearestVoxel(grid.dims, voxel);
    return shader::segmentMask(f, field[grid.index(nearest.x, nearest.y, nearest.z)] >= 0.5f);
}

} // namespace

PlacedVolume centred(Volume volume) {
    const glm::dvec3 lo = -0.5 * volume.extent();
    return PlacedVolume{std::move(volume), lo};
}

namespace {

// resampleDeformed over operators [first, first + count): `fieldFor` sees
// references into the caller's own list.
PlacedVolume resample(const PlacedVolume& in, const OperatorSpec* first, std::size_t count,
                      float emptyValue, const FeatureFieldMaker& fieldFor, const Resampling& how);

} // namespace

PlacedVolume resampleSequentially(const PlacedVolume& in,
                                  const std::vector<OperatorSpec>& operators, float emptyValue,
                                  const FeatureFieldMaker& fieldFor, const Resampling& how) {
    if (operators.empty()) return in;
    // Only the last step takes the finer grid: the steps before it keep the
    // scan's, as the render's own resampling does.
    const auto step = [&](std::size_t i) {
        Resampling h = how;
        if (i + 1 < operators.size()) h.oversample = 1;
        return h;
    };
    PlacedVolume current = resample(in, &operators[0], 1, emptyValue, fieldFor, step(0));
    for (std::size_t i = 1; i < operators.size(); ++i)
        current = resample(current, &operators[i], 1, emptyValue, fieldFor, step(i));
    return current;
}

PlacedVolume resampleDeformed(const PlacedVolume& in, const std::vector<OperatorSpec>& operators,
                              float emptyValue, const FeatureFieldMaker& fieldFor,
                              const Resampling& how) {
    return resample(in, operators.data(), operators.size(), emptyValue, fieldFor, how);
}

namespace {

// The output grid of a resampling of `in` that covers [lo, hi] (world mm):
// whole voxels of the input grid, so untouched voxels land on themselves
// (oversampled, each splits into oversample^3 of the same box), zeroed, with
// the input's space and directions; worldLo its box's low corner.
PlacedVolume outputGrid(const PlacedVolume& in, glm::dvec3 lo, glm::dvec3 hi, Sampling sampling,
                        int oversample) {
    const Volume& volume = in.volume;
    const glm::dvec3 loVox = glm::floor((lo - in.worldLo) / volume.spacing + 1e-9);
    const glm::dvec3 hiVox = glm::ceil((hi - in.worldLo) / volume.spacing - 1e-9);
    const glm::dvec3 s = volume.spacing / double(oversample);
    const bool nearest = sampling == Sampling::Nearest;
    const glm::dvec3 dims = (hiVox - loVox) * double(oversample);
    if (dims.x * dims.y * dims.z > double(detail::kMaxVoxels))
        throw InputError("--oversample " + std::to_string(oversample) + ": the grid would be " +
                         std::to_string(std::int64_t(dims.x)) + " x " +
                         std::to_string(std::int64_t(dims.y)) + " x " +
                         std::to_string(std::int64_t(dims.z)) +
                         " voxels, past the limit of 2^31; take a smaller factor");
    Volume out = Volume::allocate(glm::ivec3(dims), nearest ? volume.type : VoxelType::F32, s);
    // The grid grew along the index axes, which run along the scan's
    // directions in its space: untouched voxels keep their physical places.
    // The origin is the centre of voxel (0, 0, 0): half a fine voxel past the
    // grid's corner, which lies half an input voxel before the input's centre.
    out.origin =
        volume.origin + volume.direction * (loVox * volume.spacing + 0.5 * (s - volume.spacing));
    out.direction = volume.direction;
    out.space = volume.space;
    if (nearest) {
        out.slope = volume.slope;
        out.inter = volume.inter;
    }
    return PlacedVolume{std::move(out), in.worldLo + loVox * volume.spacing};
}

PlacedVolume resample(const PlacedVolume& in, const OperatorSpec* first, std::size_t count,
                      float emptyValue, const FeatureFieldMaker& fieldFor, const Resampling& how) {
    const Sampling sampling = how.sampling;
    const int oversample = how.oversample;
    if (oversample < 1) throw std::invalid_argument("resampleDeformed: oversample below 1");
    const Volume& volume = in.volume;
    std::vector<Placed> placed;
    glm::dvec3 lo = in.worldLo, hi = in.worldLo + volume.extent();
    const WorldBox volumeBox{glm::dmat4(1.0), {lo, hi}};
    for (const OperatorSpec& op : std::span(first, count)) {
        const WorldBox box{op.localToWorld, materialBounds(op.params)};
        FeatureField field;
        if (fieldFor && op.alignment.mode != AlignmentMode::Axis) {
            field = fieldFor(volume, op);
            if (!field || field->size() != volume.voxelCount())
                throw std::logic_error("resampleDeformed: a feature field off the volume's grid");
        }
        placed.push_back({&op, box, glm::inverse(op.localToWorld), std::move(field),
                          how.keepSegmentVoxels || sampling == Sampling::Nearest});
        // Material moves out of the operator's own box V_T: one that misses
        // the volume moves none, and does not grow the grid.
        if (!intersects(WorldBox{op.localToWorld, {}}, volumeBox)) continue;
        lo = glm::min(lo, box.lo());
        hi = glm::max(hi, box.hi());
    }
    PlacedVolume grid = outputGrid(in, lo, hi, sampling, oversample);
    Volume& out = grid.volume;
    lo = grid.worldLo;
    const glm::dvec3 s = out.spacing;
    const bool nearest = sampling == Sampling::Nearest;
    const std::size_t bytes = voxelSize(out.type);
    // Writes output voxel i from the input at p (nothing: empty).
    const auto write = [&](std::size_t i, const GridPoint& p) {
        std::byte* dst = out.data.data() + i * bytes;
        if (nearest) {
            if (!p.inside) return; // allocate() zeroed it
            const glm::ivec3 v = nearestVoxel(volume.dims, p.voxel);
            std::memcpy(dst, volume.data.data() + volume.index(v.x, v.y, v.z) * bytes, bytes);
            return;
        }
        const auto valueAt = [&](int vx, int vy, int vz) { return volume.value(vx, vy, vz); };
        const auto movedAt = [&](int vx, int vy, int vz) {
            const std::vector<float>& mask = *p.movedOffSegment;
            if (!shader::maskInside(mask[volume.index(vx, vy, vz)]))
                return volume.value(vx, vy, vz);
            return double(
                movedValueAt(volume.dims, {vx, vy, vz}, valueAt,
                             [&](int x, int y, int z) { return mask[volume.index(x, y, z)]; }));
        };
        float value = emptyValue;
        if (p.inside)
            value =
                static_cast<float>(p.movedOffSegment ? trilinear(volume.dims, p.voxel, movedAt)
                                                     : trilinear(volume.dims, p.voxel, valueAt));
        std::memcpy(dst, &value, sizeof value);
    };

    for (int z = 0; z < out.dims.z; ++z)
        for (int y = 0; y < out.dims.y; ++y)
            for (int x = 0; x < out.dims.x; ++x) {
                const glm::dvec3 pPrime = lo + (glm::dvec3(x, y, z) + 0.5) * s;
                GridPoint p = locate(in, pPrime); // where the value comes from
                for (const Placed& op : placed) {
                    const glm::dvec3 q(op.worldToLocal * glm::dvec4(pPrime, 1.0));
                    if (glm::any(glm::lessThan(q, op.box.local.lo)) ||
                        glm::any(glm::greaterThan(q, op.box.local.hi)))
                        continue;
                    // Eq. 3 and 4, as the shader's resolve() does them.
                    const glm::vec4 b = shader::operatorBackward(glm::vec3(q), op.spec->params);
                    const GridPoint p0 = locate(
                        in, glm::dvec3(op.spec->localToWorld * glm::dvec4(glm::vec3(b), 1.0)));
                    const bool p0Valid = b.w > 0.0f && p0.inside;
                    const int which = shader::featureCase(
                        p0Valid,
                        p0Valid ? maskAt(op, volume, p0.voxel, op.keepSegmentVoxels) : 0.0f,
                        p.inside, p.inside ? maskAt(op, volume, p.voxel, true) : 0.0f);
                    if (which == CW_CASE_TRANSFORMED) {
                        p = p0;
                        if (op.spec->alignment.mode == AlignmentMode::Segment)
                            p.movedOffSegment = op.field.get();
                    }
                    if (which == CW_CASE_EMPTY) p.inside = false;
                    break; // deformed boxes do not overlap
                }
                write(out.index(x, y, z), p);
            }
    return grid;
}

} // namespace
} // namespace cutaway::operators
