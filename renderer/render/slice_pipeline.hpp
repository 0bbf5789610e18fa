#pragma once
// The graphics pipelines of the slicing pass: world-space triangles in, one
// RGBA float colour out with front-to-back premultiplied blending. Slices
// neither test nor write depth (the attachment is there for the mesh pass).
//
// The stencil composites several operators (paper section 5.1): on slice k
// (reference ref(k), set dynamically) an operator's polygon writes ref(k); the
// background polygon is drawn only where the stencil is not ref(k), so no
// region is drawn twice and no slice needs its own clear. An operator's whole
// box is marked by a stencil-only polygon, and its shader runs only on the
// parts of the box where something can show (render/operator_regions.hpp).
#include "gpu/context.hpp"
#include "gpu/handle.hpp"

#include <initializer_list>
#include <vulkan/vulkan.h>

namespace cutaway::render {

enum class SliceProxy {
    Background,     ///< slice.frag; stencil test != ref, no write
    Operator,       ///< slice_operator.frag; stencil always passes, writes ref
    OperatorStencil ///< no fragment shader, no colour: writes ref over an operator's whole box
};

/// The operator-id target: RGBA16F, see shaders/glsl/slice_common.h.
constexpr VkFormat kOperatorIdFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

/// What a frame fixes in the slicing fragment shaders, given to them as
/// specialization constants (shaders/glsl/slice_common.h) so that each
/// pipeline runs only the code its frame needs. `withOperatorId`: a second
/// colour attachment receives the id of the proxy whose sample was the first
/// visible one in each pixel.
struct SliceVariant {
    SliceProxy proxy = SliceProxy::Background;
    bool withOperatorId = false;
    bool preintegrated = false;
    bool byLabel = false;
    bool shading = true;
    int lights = 0;    ///< directional lights, 0..CW_MAX_LIGHTS
    int alignment = 0; ///< operator proxies: CW_ALIGN_*
    /// The volume's values read with imageLoad and filtered in the shader
    /// instead of sampled (sample_common.h's volumeAt; SliceRenderer
    /// decides): 0 sampled, 1 from the R8 binding, 2 from the R16 one.
    int storageFetch = 0;
    /// The gradients in the bricked layout, loaded and filtered in the shader
    /// (sample_common.h's gradientAt; GpuVolume::gradientLayout decides).
    bool brickedGradients = false;
    /// The shading's shininess when it is a whole number, else 0: the
    /// specular power by repeated squaring (sample_common.h's specularPower).
    int wholeShininess = 0;
    /// The ray caster's lanes that step over transparent samples stop for a
    /// pass of shading as soon as one lane waits (ray_march.h's
    /// CW_YIELD_LANES: its shaders with subgroup ballots; SliceRenderer
    /// decides). Slicing ignores it.
    bool yieldLanes = false;
    /// The ray caster's census (SliceRenderer::setCensus): counts of samples
    /// per pixel instead of colour.
    bool census = false;
    auto operator<=>(const SliceVariant&) const = default;
};

/// The specialization constants of `variant` (constant_id 0..5 of
/// shaders/glsl/sample_common.h), for the slicing and ray-casting pipelines,
/// up to three `more` (constant_id 6, 7, 8: the ray caster's operators; 0
/// where not given), the census (constant_id 9, ray_march.h), the bricked
/// gradients (constant_id 10, sample_common.h) and the whole-number shininess
/// (constant_id 11). A shader that does not declare an id ignores its entry.
class SliceConstants {
public:
    explicit SliceConstants(const SliceVariant& variant, std::initializer_list<uint32_t> more = {});
    SliceConstants(const SliceConstants&) = delete;
    SliceConstants& operator=(const SliceConstants&) = delete;
    const VkSpecializationInfo* info() const { return &m_info; }

private:
    static constexpr uint32_t kFixed = 6;               ///< constant_id 0..5, from the variant
    static constexpr uint32_t kMore = 3;                ///< constant_id 6..8, from `more`
    static constexpr uint32_t kCensus = kFixed + kMore; ///< constant_id 9
    static constexpr uint32_t kMost = kCensus + 3;      ///< and 10, 11: see above
    uint32_t m_values[kMost];
    VkSpecializationMapEntry m_entries[kMost];
    VkSpecializationInfo m_info;
};

gpu::PipelineHandle createSlicePipeline(const gpu::Context& ctx, VkPipelineLayout layout,
                                        const SliceVariant& variant);

} // namespace cutaway::render
