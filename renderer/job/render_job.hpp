#pragma once
// Runs a scene: loads its volume (a file or a phantom), prepares it on the
// device once, renders frames and writes them (EXR, optional PNG preview).
// The CLI is a thin layer over this; tests drive it directly.
#include "bake/gradient_bake.hpp"
#include "bake/volume_upload.hpp"
#include "gpu/context.hpp"
#include "io/image.hpp"
#include "operators/deformed_volume.hpp"
#include "render/gpu_volume.hpp"
#include "render/volume_renderer.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace cutaway::job {

/// The scene's volume: read from its file (or made as its phantom), with the
/// spacing override applied. Its NaN and infinite voxels (a float file's)
/// are left out of its value range and the automatic window, and take the
/// value of empty space (emptyValue), so they render as empty; `nonFinite`,
/// if given, receives how many there were. Throws InputError naming the file
/// on failure.
Volume loadSceneVolume(const Scene& scene, std::size_t* nonFinite = nullptr);

/// The warning for a volume with `count` non-finite voxels of `voxels`.
std::string nonFiniteWarning(const Scene& scene, std::size_t count, std::size_t voxels);

/// The scene's label volume (/labels), or null without one: read from its
/// file or made with the phantom, checked against the scan's grid (same dims,
/// spacing equal to within 0.1 %; /volume/spacing applies to both), with
/// integer ids >= 0. Throws InputError naming the file on a mismatch. When
/// /labels names the scan's own file (a label volume rendered as itself), the
/// scan is checked and returned: the file is read and held once.
std::shared_ptr<const Volume> loadSceneLabels(const Scene& scene,
                                              const std::shared_ptr<const Volume>& scan);

/// The value window: the scene's, else the volume's value range (a flat
/// volume gets a window of width 1 so normalization stays defined).
bake::ValueWindow sceneWindow(const Scene& scene, const Volume& volume);

/// What empty space (cuts, openings, the space a flap lifts into) holds when
/// the CPU resamples the scan (sequential composition, `cutaway export`): the
/// lower of the scan's smallest value and the window's bottom. Transparent
/// under any transfer function that is transparent for air, and background
/// to an aligned operator's threshold or value range made from the result.
float emptyValue(const Scene& scene, const Volume& scan);

/// Whether the frame resamples the scan on the CPU: sequential composition
/// with more than one operator (all but the last are baked into the volume).
bool sequential(const Scene& scene);

/// The volume a frame renders and its value window: the scan itself, or under
/// sequential composition the scan deformed by every operator but the last
/// (resampled on the CPU). The window is always the scan's.
struct FrameVolume {
    std::shared_ptr<const Volume> scan;
    glm::dvec3 worldLo{0.0}; ///< where the scan's corner lies in the world
    bake::ValueWindow window;
    std::shared_ptr<const Volume> labels; ///< on the scan's grid (maybe the scan), or null
    std::size_t nonFinite = 0; ///< NaN and infinite voxels the scan's file held (now empty)
};
FrameVolume frameVolume(const Scene& scene);

/// Identifies the volume frameVolume would make, so a sequence uploads it
/// again only when it changes: the /volume section, plus under sequential
/// composition every operator but the last.
std::string frameVolumeKey(const Scene& scene);

/// The operators rendered live through their baked maps: all of them, or
/// under sequential composition only the last.
std::vector<OperatorSpec> liveOperators(const Scene& scene);

/// Expands "####" (any run of #) or "%0Nd" / "%Nd" / "%d" in `pattern` with
/// `frame`, padded to the run's length or N with zeros (spaces for "%Nd").
/// "%%" is one '%', as in printf; a pattern without a placeholder is
/// otherwise used as is.
std::string expandPattern(const std::string& pattern, int frame);

/// How many frame-number placeholders `pattern` holds (runs of #, %d forms);
/// a run of several frames needs exactly one.
int framePlaceholders(const std::string& pattern);

/// The PNG preview path that goes with an EXR path (same name, .png).
std::filesystem::path previewPath(const std::filesystem::path& exrPath);

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

    const gpu::Context& m_ctx;
    bake::GradientBaker m_baker;
    render::VolumeRenderer m_renderer;
    std::unique_ptr<render::GpuVolume> m_volume;
    std::string m_volumeKey;
    int m_uploads = 0;
    std::vector<std::string> m_warnings;
    std::set<std::size_t> m_warnedOutside;   ///< operator indices already warned of
    std::set<std::string> m_warnedNonFinite; ///< volumes (frameVolumeKey) already warned of
};

/// Renders one frame to an image without writing anything (tests, benchmark).
Image renderImage(const gpu::Context& ctx, const Scene& scene);

} // namespace cutaway::job
