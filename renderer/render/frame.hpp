#pragma once
// One frame as the renderer's front (VolumeRenderer) prepares it for a pass
// (render_pass.hpp): the camera and slabs, the shader variant, and the
// inputs that every pass reads in its set 0.
#include "gpu/context.hpp"
#include "gpu/resources.hpp"
#include "render/camera.hpp"
#include "render/gpu_operators.hpp"
#include "render/gpu_volume.hpp"
#include "render/shader_variant.hpp"
#include "scene/scene.hpp"
#include "shared/frame.h"

#include <array>
#include <optional>
#include <vector>
#include <vulkan/vulkan.h>

namespace cutaway::render {

/// What every pass reads in its set 0: shaders/shared/bindings.h's
/// CW_BIND_FRAME to CW_BIND_CLASSES, and, where the shaders are built with
/// the storage paths, CW_BIND_VALUES_R8 to CW_BIND_GRADIENT_IMAGE.
struct FrameInputs {
    VkBuffer uniforms = VK_NULL_HANDLE; ///< shader::FrameUniforms
    const gpu::Image* values = nullptr;
    const gpu::Image* gradients = nullptr;
    const gpu::Image* transfer = nullptr;
    const gpu::Image* classes = nullptr;
    VkSampler linear = VK_NULL_HANDLE, nearest = VK_NULL_HANDLE;
    bool storageImages = false;
    /// The views for CW_BIND_VALUES_R8, _R16 and CW_BIND_GRADIENT_IMAGE
    /// (bake::ValueStorageBindings), with storageImages.
    std::array<VkImageView, 3> storage{};
};

/// The layout bindings of FrameInputs, visible to `stages` (the uniforms to
/// `uniformStages`).
std::vector<VkDescriptorSetLayoutBinding>
frameInputBindings(VkShaderStageFlags stages, VkShaderStageFlags uniformStages, bool storageImages);
/// Writes `inputs` into their bindings of `set`.
void writeFrameInputs(const gpu::Context& ctx, VkDescriptorSet set, const FrameInputs& inputs);

/// A frame's camera and slabs.
struct FrameGeometry {
    CameraMatrices camera;
    /// The volume and the deformed boxes of the operators that reach it (a
    /// flap may leave the volume's box).
    Box bounds;
    double sliceMm = 0.0; ///< between two slicing planes
    /// How far along a ray a slab reaches: the slice spacing, longer by the
    /// obliquity of the frame's most oblique ray.
    double reachMm = 0.0;
    int marginVoxels = 0; ///< slabMargin of that reach, for empty space
};

/// The box the slicing planes span: `volumeBox` and each of `boxes` (the
/// operators' deformed boxes) that meets it (a flap may leave the volume's box).
Box slicedBounds(const Box& volumeBox, const std::vector<operators::WorldBox>& boxes);

/// What frameGeometry refuses before anything is drawn, from the scene and
/// the volume as read (centred, as a render places it): more slicing planes
/// than are drawn (checkPlaneCount). `validate` calls it, so that it refuses
/// what `render` does.
void checkSlicingPlanes(const Scene& scene, const Volume& volume);

/// The camera frames the volume alone, so that an operator moving through a
/// sequence does not move the camera; its depth range covers the operators'
/// boxes and `meshBounds` too.
FrameGeometry frameGeometry(const Scene& scene, const GpuVolume& volume,
                            const OperatorStack& operators, const std::optional<Box>& meshBounds);

/// The frame's uniforms (shaders/shared/frame.h).
shader::FrameUniforms frameUniforms(const Scene& scene, const GpuVolume& volume,
                                    const CameraMatrices& cam, double sliceMm);

/// The shininess as ShaderVariant::wholeShininess takes it: the exponent
/// when it is a whole number and a highlight is drawn, else 0 (pow).
int wholeShininess(const Shading& shading);

/// What a pass renders; the front prepared the rest.
/// The meshes' targets (render/mesh_pass.hpp) and their readbacks: their
/// colour (the colour target's format) and each pixel's distance from the eye
/// (R32F, shared/frame.h's viewDepth; where the colour's alpha is 0 no mesh is).
struct MeshTargets {
    gpu::Image color, distance;
    gpu::Buffer colorReadback, distanceReadback;
};

struct Frame {
    const Scene& scene;
    const GpuVolume& volume;
    const FrameGeometry& geometry;
    glm::uvec2 size;
    ShaderVariant variant;
    FrameInputs inputs;
    /// The meshes' targets, null without meshes: the pass draws the meshes
    /// first, with its own depth target, and copies both targets out.
    const MeshTargets* meshes = nullptr;
};

} // namespace cutaway::render
