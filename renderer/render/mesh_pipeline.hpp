#pragma once
// The graphics pipelines of the mesh pass (see mesh_pass.hpp).
#include "gpu/context.hpp"
#include "gpu/handle.hpp"

#include <glm/glm.hpp>

namespace cutaway::render {

/// One vertex as the mesh shaders read it.
struct MeshVertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec4 color;
};
static_assert(sizeof(MeshVertex) == 40);

/// The format of the meshes' distance target (mesh.frag's second output).
constexpr VkFormat kMeshDistanceFormat = VK_FORMAT_R32_SFLOAT;

/// Opaque triangles: depth LESS and written, colour and distance written
/// without blending, into an attachment of the colour target's format and one
/// of kMeshDistanceFormat. `layout`: frame set 0 and the MeshDraw push
/// constants.
gpu::PipelineHandle createMeshPipeline(const gpu::Context& ctx, VkPipelineLayout layout);

} // namespace cutaway::render
