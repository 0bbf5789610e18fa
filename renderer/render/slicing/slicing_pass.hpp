#pragma once
// Texture-based view-aligned slicing into a float target (paper section 5).
//
// Per frame: slice polygons are clipped on the CPU against each proxy (the
// operators' deformed boxes, then the volume's occupied bricks) and drawn
// front to back; each fragment samples the volume, classifies, corrects
// opacity, shades and is composited with premultiplied "under" blending
// (dst += (1 - dst.a) * src). The stencil keeps the volume's polygons out of
// the operators' boxes (section 5.1; slice_pipeline.hpp). Every
// kSlicesPerChunk slices the saturation pass marks the opaque pixels, which
// the slices behind then skip (early ray termination). Opaque meshes are
// drawn first and depth-test the slices (mesh_pass.hpp).
#include "gpu/handle.hpp"
#include "gpu/pipeline.hpp"
#include "gpu/resources.hpp"
#include "render/render_pass.hpp"
#include "render/slicing/saturation_pass.hpp"
#include "render/slicing/slice_pipeline.hpp"
#include "render/slicing/slicer.hpp"

#include <array>
#include <map>
#include <utility>
#include <vector>

namespace cutaway::render {

class SlicingPass final : public RenderPass {
public:
    /// `operatorLayout`: an operator's set (OperatorStack::setLayout), set 1.
    SlicingPass(const PassResources& shared, VkDescriptorSetLayout operatorLayout);
    Image render(const Frame& frame, FrameStats& stats) override;

private:
    /// What each proxy of the frame is: operator `op`'s stencil box or one of
    /// its regions, or (op < 0) a box of the volume's occupied bricks.
    struct ProxyRole {
        int op = -1;
        bool stencil = false;
    };
    /// The frame's proxies (m_roles says what each is): each operator's
    /// deformed box, then its regions, then the volume's occupied bricks.
    std::vector<Proxy> proxies(const Frame& frame);
    /// Its colour and depth-stencil targets, and the AOV targets `variant`
    /// asks for (aovTargetCount).
    void ensureTargets(glm::uvec2 size, const ShaderVariant& variant);
    void ensureVertexCapacity(std::size_t bytes);
    /// The pipeline of `proxy`'s polygons for `variant`, made on first use.
    VkPipeline pipelineFor(ShaderVariant variant, SliceProxy proxy);
    /// The meshes, the chunks of slices and the copies to the readbacks.
    void record(VkCommandBuffer cmd, const Frame& frame, const SliceSet& slices,
                VkDescriptorSet frameSet, VkDescriptorSet saturationSet);
    /// Draws slices [begin, end) inside a rendering pass.
    void recordSlices(VkCommandBuffer cmd, const SliceSet& slices, VkDescriptorSet frameSet,
                      const ShaderVariant& variant, std::size_t begin, std::size_t end);
    /// Clears the stencil (before its references cycle back to a value).
    void clearStencil(VkCommandBuffer cmd) const;
    /// The volume's image and AOVs from the readbacks.
    Image readBack(const Frame& frame) const;

    PassResources m_shared;
    gpu::PipelineLayoutHandle m_layout; ///< set 0 the frame's, set 1 an operator's
    std::map<std::pair<ShaderVariant, SliceProxy>, gpu::PipelineHandle> m_pipelines;
    SaturationPass m_saturation;
    std::vector<ProxyRole> m_roles;
    gpu::Buffer m_vertices;
    glm::uvec2 m_targetSize{0, 0};
    gpu::Image m_color;
    gpu::Image m_depthStencil; ///< the meshes' depth, then the saturation's marks
    gpu::Buffer m_readback;
    /// The id target, then the two matte targets: only while frames ask for them.
    std::array<gpu::Image, 3> m_aovs;
    std::array<gpu::Buffer, 3> m_aovReadbacks;
};

} // namespace cutaway::render
