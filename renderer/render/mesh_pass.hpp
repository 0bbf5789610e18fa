#pragma once
// Opaque meshes drawn with the volume: the scene's glTF models (/meshes, paper
// Fig. 10) and the operators' box glyphs (/operators/N/glyph, Fig. 8).
//
// In two steps that keep the volume's front-to-back "under" compositing exact:
//   1. the meshes are drawn opaque, with depth, into their own colour target
//      and the depth buffer the slices then use (a render pass of their own);
//   2. the slices are depth-tested against that depth, so the volume behind a
//      mesh is never composited, and the volume's image is composited over
//      the meshes' image like over an opaque background (VolumeRenderer).
// Drawing the meshes' colour into the volume's target after the slices would
// need a second pass with an EQUAL depth test, and so depths invariant across
// two pipelines, which SPIR-V tools only half support.
#include "gpu/context.hpp"
#include "gpu/handle.hpp"
#include "gpu/resources.hpp"
#include "mesh/mesh.hpp"
#include "render/camera.hpp"
#include "scene/scene.hpp"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cutaway::render {

/// The rigid frame of an operator's placement: its box centre and unit box
/// axes, without the box's scale (what /meshes/N/attach places a mesh in).
glm::dmat4 operatorFrame(const glm::dmat4& localToWorld);

class MeshPass {
public:
    MeshPass(const gpu::Context& ctx, VkDescriptorSetLayout frameLayout);

    /// Places the scene's meshes and glyphs for this frame, reading each glTF
    /// file once (InputError names a bad one). `volumeDiagonal` (mm) sizes the
    /// default glyph width. Returns the world bounds of what will be drawn.
    std::optional<Box> prepare(const Scene& scene, double volumeDiagonal);

    bool empty() const { return m_draws.empty(); }
    /// Step 1, a render pass of its own: clears `color` (the colour target's
    /// format), `distance` (kMeshDistanceFormat) and `depthStencil`, draws
    /// every mesh, and makes the depth visible to the volume pass that loads
    /// it. The images must be in their attachment layouts.
    void recordPass(VkCommandBuffer cmd, VkDescriptorSet frameSet, const gpu::Image& color,
                    const gpu::Image& distance, const gpu::Image& depthStencil);

private:
    struct GpuMesh {
        gpu::Buffer vertices; ///< interleaved position, normal, colour (40 bytes)
        gpu::Buffer indices;  ///< uint32
        uint32_t indexCount = 0;
        glm::vec3 lo{0.0f}, hi{0.0f}; ///< bounds in model units
    };
    struct Draw {
        const GpuMesh* mesh = nullptr;
        glm::dmat4 modelToWorld{1.0};
        std::optional<glm::vec3> color;
    };
    void upload(GpuMesh& gpuMesh, const mesh::TriangleMesh& mesh, bool reuse);
    void record(VkCommandBuffer cmd, VkDescriptorSet frameSet);

    const gpu::Context& m_ctx;
    gpu::PipelineLayoutHandle m_layout;
    gpu::PipelineHandle m_pipeline;          ///< made on first use
    std::map<std::string, GpuMesh> m_models; ///< glTF files by path, loaded once
    GpuMesh m_glyphs;                        ///< this frame's glyphs, in world space
    std::vector<Draw> m_draws;
};

} // namespace cutaway::render
