#pragma once
// A way of taking the volume integral of a frame: slicing (the paper's
// method, slicing/slicing_pass.hpp) or ray casting (raycast/raycast_pass.hpp).
// The front (VolumeRenderer) chooses one per frame, as pbrt-v4 chooses its
// integrator, after it has prepared what every pass reads (frame.hpp); a
// pass owns its targets and pipelines. Another pass (a light or shadow pass
// run before these) is a class beside them that the front calls, and what it
// makes, an input of the frame.
#include "gpu/context.hpp"
#include "io/image.hpp"
#include "render/frame.hpp"
#include "render/gpu_operators.hpp"
#include "render/mesh_pass.hpp"
#include "render/skipping/empty_space.hpp"

#include <cstddef>

namespace cutaway::render {

/// Numbers about the last frame, for logs and the benchmark.
struct FrameStats {
    int slices = 0;
    std::size_t vertices = 0;
    int operatorBakes = 0; ///< operator maps baked since the renderer was made
};

/// What the front owns and every pass uses.
struct PassResources {
    const gpu::Context& ctx;
    VkSampler linear;
    VkSampler nearest;
    /// Set 0 of slicing and of the meshes: the frame's inputs (frame.hpp).
    VkDescriptorSetLayout frameLayout;
    /// Whether the layouts hold the storage paths' bindings: the shaders'
    /// flavour must match (ShaderVariant::storageImages).
    bool storageImages;
    OperatorStack& operators;
    EmptySpace& emptySpace;
    MeshPass& meshes;
};

class RenderPass {
public:
    virtual ~RenderPass() = default;
    /// Renders `frame`: the meshes first where it has them (into
    /// Frame::meshColor, with the pass's own depth), then the volume and its
    /// operators over nothing, read back as linear premultiplied RGBA (row 0
    /// at the top) with the operator ids where the variant asks. The front
    /// composites the meshes and the background.
    virtual Image render(const Frame& frame, FrameStats& stats) = 0;
};

} // namespace cutaway::render
