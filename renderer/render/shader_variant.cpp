#include "render/shader_variant.hpp"

#include "shared/bindings.h"

#include <cassert>

namespace cutaway::render {

static_assert(CW_SPEC_COUNT == 16, "ShaderConstants::kCount");

ShaderConstants::ShaderConstants(const ShaderVariant& v, std::initializer_list<uint32_t> more)
    : m_values{} {
    assert(more.size() <= 3);
    // Booleans are 32-bit VkBool32.
    m_values[CW_SPEC_PREINTEGRATED] = v.preintegrated;
    m_values[CW_SPEC_BY_LABEL] = v.byLabel;
    m_values[CW_SPEC_SHADING] = v.shading;
    m_values[CW_SPEC_LIGHT_COUNT] = static_cast<uint32_t>(v.lights);
    m_values[CW_SPEC_ALIGNMENT] = static_cast<uint32_t>(v.alignment);
    m_values[CW_SPEC_STORAGE_FETCH] = static_cast<uint32_t>(v.storageFetch);
    const uint32_t slots[3] = {CW_SPEC_OPERATOR_COUNT, CW_SPEC_ALIGNMENT1, CW_SPEC_ALIGNMENT2};
    uint32_t at = 0;
    for (uint32_t value : more)
        m_values[slots[at++]] = value;
    m_values[CW_SPEC_CENSUS] = v.census;
    m_values[CW_SPEC_BRICKED_GRADIENTS] = v.brickedGradients;
    m_values[CW_SPEC_WHOLE_SHININESS] = static_cast<uint32_t>(v.wholeShininess);
    m_values[CW_SPEC_CUBIC] = v.cubic;
    m_values[CW_SPEC_REFINE] = static_cast<uint32_t>(v.refine);
    m_values[CW_SPEC_LABEL_AOVS] = v.labelAovs;
    m_values[CW_SPEC_MATTES] = v.mattes;
    for (uint32_t i = 0; i < kCount; ++i)
        m_entries[i] = {i, i * 4u, 4u};
    m_info = {kCount, m_entries, kCount * 4u, m_values};
}

} // namespace cutaway::render
