#pragma once
// Runs a scene: loads its volume (a file or a phantom), prepares it on the
// device once, renders frames and writes them (EXR, optional PNG preview).
// The CLI is a thin layer over this; tests drive it directly.
#include "bake/gradient_bake.hpp"
#include "bake/volume_upload.hpp"
#include "gpu/context.hpp"
#include "io/image.hpp"
#include "job/output_pattern.hpp"
#include "job/scene_data.hpp"
#include "job/value_checks.hpp"
#include "operators/deformed_volume.hpp"
#include "render/gpu_volume.hpp"
#include "render/volume_renderer.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <array>
#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace cutaway::job {

/// What the command line can change for a run.
struct RenderOverrides {
    std::optional<std::string> outputPattern; ///< replaces /output/pattern (relative to cwd)
    std::optional<glm::ivec2> size;           ///< replaces /render/size
    bool png = false;                         ///< also write PNG previews
};

/// Applies overrides to a parsed scene (validated by the caller).
void applyOverrides(Scene& scene, const RenderOverrides& overrides);

/// Turns scenes into images, keeping the device-side state between calls: the
/// pipelines, and the uploaded volume with its baked gradients for as long as
/// frameVolumeKey stays the same.
class FrameRenderer {
public:
    explicit FrameRenderer(const gpu::Context& ctx);
    Image render(const Scene& scene);
    /// See VolumeRenderer::setCensus.
    void setCensus(bool on) { m_renderer.setCensus(on); }
    int uploads() const { return m_uploads; } ///< volumes loaded, uploaded and baked so far
    /// What the renders since the last call derived, one line each (e.g. the
    /// Otsu threshold of surface alignment and its bake time).
    std::vector<std::string> takeNotes() { return m_renderer.takeNotes(); }
    /// What the last frame derived, without times: the feature fields it
    /// read, the same lines for every frame that reads the same fields.
    std::vector<std::string> fieldsInUse() const { return m_renderer.fieldsInUse(); }
    /// What in the scenes since the last call is likely a mistake, once per
    /// run: an operator whose box does not reach the volume moves nothing.
    std::vector<std::string> takeWarnings() { return std::exchange(m_warnings, {}); }

private:
    void warnOfOperatorsOutside(const Scene& scene);
    /// The bounds of what the operators of `given`'s animation move over all
    /// its frames, with the volume's box (/camera/fit "sequence"), cached.
    std::array<glm::dvec3, 2> sequenceBounds(const Scene& given);

    const gpu::Context& m_ctx;
    bake::GradientBaker m_baker;
    render::VolumeRenderer m_renderer;
    std::unique_ptr<render::GpuVolume> m_volume;
    std::optional<FrameVolumeKey> m_volumeKey;
    Volume m_geometry;
    ValueChecks m_values;         ///< of every frame, made again when its functions change
    nlohmann::json m_sequenceKey; ///< the first frame's document sequenceBounds were made for
    std::optional<std::array<glm::dvec3, 2>>
        m_sequenceBounds; ///< the scan's as loaded: places LPS and RAS (job/volume_frame.hpp)
    int m_uploads = 0;
    std::vector<std::string> m_warnings;
    std::set<std::size_t> m_warnedOutside;         ///< operator indices already warned of
    std::vector<FrameVolumeKey> m_warnedNonFinite; ///< volumes already warned of
    std::set<std::string> m_warnedOnce; ///< absent-label and value warnings already given
};

/// Renders one frame to an image without writing anything (tests, benchmark).
Image renderImage(const gpu::Context& ctx, const Scene& scene);

} // namespace cutaway::job
