#pragma once
// What a frame fixes in the shaders of either pass, given to them as
// specialization constants (shaders/shared/bindings.h, CW_SPEC_*) so that each
// pipeline runs only the code its frame needs: on lavapipe a branch on a
// uniform still costs both sides. Each pass keeps its pipelines by variant.
#include <cstdint>
#include <initializer_list>
#include <vulkan/vulkan.h>

namespace cutaway::render {

struct ShaderVariant {
    /// The shaders' storage flavour (CW_STORAGE_PATHS): they declare the
    /// CPU-device bindings (gpu::DeviceTuning::storageImages). Fixed per
    /// renderer, not per frame.
    bool storageImages = false;
    /// A second colour attachment (slicing) receives what each pixel's first
    /// visible sample was: its proxy's id, its distance from the eye and its
    /// label (/output/aovs); the ray caster always writes its id image, and
    /// copies it out only with this.
    bool withAovs = false;
    /// The first visible sample's label in the id target (CW_SPEC_LABEL_AOVS).
    bool labelAovs = false;
    /// The mattes (/output/mattes): slicing's attachments 2 and 3
    /// (CW_WRITE_MATTES), the ray caster's matte image (CW_SPEC_MATTES).
    bool mattes = false;
    bool preintegrated = false;
    bool byLabel = false;
    bool shading = true;
    int lights = 0;    ///< directional lights, 0..CW_MAX_LIGHTS
    int alignment = 0; ///< operator shaders: CW_ALIGN_* (the ray caster's slot 0)
    /// The volume's values read with imageLoad and filtered in the shader
    /// instead of sampled (sample_common.h's volumeAt): 0 sampled, 1 from
    /// the R8 binding, 2 from the R16 one. Only with storageImages.
    int storageFetch = 0;
    /// The gradients in the bricked layout, loaded and filtered in the
    /// shader (sample_common.h's gradientAt). Only with storageImages.
    bool brickedGradients = false;
    /// The shading's shininess when it is a whole number, else 0: the
    /// specular power by repeated squaring (sample_common.h's specularPower).
    int wholeShininess = 0;
    /// /render/filter "cubic": the values and gradients reconstructed by
    /// the tricubic Catmull-Rom filter (shared/cubic_filter.h) instead of
    /// trilinearly.
    bool cubic = false;
    /// /render/refine: the sub-slabs a pre-integrated slab that shows is
    /// taken in (sample_common.h's backgroundSlab); 1 none.
    int refine = 1;
    /// The ray caster's lanes that step over transparent samples stop for a
    /// pass of shading as soon as one lane waits (ray_march.h's
    /// CW_YIELD_LANES, the "lanes" flavour). Slicing ignores it.
    bool yieldLanes = false;
    /// The ray caster's census (VolumeRenderer::setCensus): counts of
    /// samples per pixel instead of colour. Slicing ignores it.
    bool census = false;
    auto operator<=>(const ShaderVariant&) const = default;
};

/// The specialization constants of `variant` (every CW_SPEC_* id), with the
/// ray caster's operator count and slots 1 and 2's alignments from `more`
/// (CW_SPEC_OPERATOR_COUNT, ALIGNMENT1, ALIGNMENT2; 0 where not given). A
/// shader that does not declare an id ignores its entry.
class ShaderConstants {
public:
    explicit ShaderConstants(const ShaderVariant& variant,
                             std::initializer_list<uint32_t> more = {});
    ShaderConstants(const ShaderConstants&) = delete;
    ShaderConstants& operator=(const ShaderConstants&) = delete;
    const VkSpecializationInfo* info() const { return &m_info; }

private:
    static constexpr uint32_t kCount = 16; ///< CW_SPEC_COUNT
    uint32_t m_values[kCount];
    VkSpecializationMapEntry m_entries[kCount];
    VkSpecializationInfo m_info;
};

} // namespace cutaway::render
