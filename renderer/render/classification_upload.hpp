#pragma once
// A scene's classification on the device: the transfer functions' tables (one
// layer per function) and each voxel's layer, read by the slicing shaders and
// the ray caster.
#include "gpu/context.hpp"
#include "gpu/resources.hpp"
#include "render/gpu_volume.hpp"
#include "scene/scene.hpp"

namespace cutaway::render {

/// The classification tables, one layer per transfer function (/transfer,
/// then /transfer/labels; classifyingTransfers): the 1D function
/// (post-classification) or its pre-integrated 2D table for slabs `sliceMm`
/// thick, RGBA16F.
gpu::Image uploadTransfer(const gpu::Context& ctx, const Scene& scene, const GpuVolume& volume,
                          double sliceMm);

/// Each voxel's classification layer (R8_UINT), or a single 0 without labels.
gpu::Image uploadClasses(const gpu::Context& ctx, const Scene& scene, const GpuVolume& volume);

} // namespace cutaway::render
