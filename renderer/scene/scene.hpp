#pragma once
// The scene model: what one frame needs, after parsing and validation.
//
// Units: lengths in millimetres of the scan's physical extent; angles in
// degrees; colours linear RGB in [0, 1]. World space is the volume's index
// axes scaled by its spacing, with the origin at the centre of the volume box
// (so a 256^3 scan at 1 mm spans [-128, 128]^3). Scene JSON keys are
// snake_case; see docs/scene-format.md for every key, range and default.
#include "shared/operators.h"
#include "volume/volume.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace cutaway {

/// /volume: where the scalar field comes from. Exactly one of file / phantom.
struct VolumeSource {
    std::filesystem::path file;   ///< resolved against the scene's folder; empty for a phantom
    std::optional<RawLayout> raw; ///< /volume/raw: layout of a headerless file
    std::string series;           ///< /volume/series: a DICOM series' number, UID or description
    std::string phantom;          ///< /volume/phantom: "head" or "orange"
    glm::ivec3 phantomSize{128};  ///< /volume/size (phantoms only), each in [8, 1024]
    std::optional<glm::dvec3> spacing;           ///< /volume/spacing: overrides the file's, mm, > 0
    std::optional<std::array<double, 2>> window; ///< /volume/window: [lo, hi] values, lo < hi
    bool operator==(const VolumeSource&) const = default;
};

/// One control point of a piecewise-linear transfer function. `value` is in the
/// volume's physical units (after slope/intercept). `alpha` is the opacity of a
/// sample one reference step thick (/transfer/unit_distance, by default the
/// smallest voxel spacing); rendering corrects it for the actual slice spacing.
struct TransferPoint {
    double value = 0.0;
    glm::vec3 color{1.0f};
    float alpha = 0.0f;
    bool operator==(const TransferPoint&) const = default;
};

/// /transfer: points sorted by strictly increasing value (at least 2).
/// Below the first point the first point's colour applies, above the last the last's.
struct TransferFunction {
    std::vector<TransferPoint> points;
    bool operator==(const TransferFunction&) const = default;
};

/// /transfer/labels/N: the transfer function of the samples whose label is
/// one of `ids` (classification by label, paper Fig. 6). Needs /labels.
struct LabelTransfer {
    std::vector<std::int64_t> ids; ///< label ids, names resolved through /labels/names
    TransferFunction transfer;
};

/// /labels: a label volume on the scan's grid (same dims; spacing equal to
/// within 0.1 %, checked on load), or the phantom's own labels.
struct LabelSource {
    std::filesystem::path file;                ///< resolved; empty with `phantom`
    bool phantom = false;                      ///< /labels/phantom: the phantom's labels
    std::map<std::string, std::int64_t> names; ///< /labels/names (a phantom's own are added)
    std::filesystem::path table;               ///< /labels/table, resolved; empty without
    std::map<std::int64_t, glm::vec3> colors;  ///< the table's colours (linear RGB)
};

enum class Projection { Perspective, Orthographic };

/// /camera/fit: what a distance or ortho height of 0 fits in view.
enum class CameraFit {
    Volume,   ///< the volume's box
    Deformed, ///< the volume's box and what the frame's operators move
    Sequence  ///< the same, over every frame of the animation: a steady view
};

/// The frame a placement's coordinates are in ("space"): the volume frame
/// (mm along the voxel grid's axes, the volume's centre at the origin), or the
/// scan's own physical coordinates, LPS (as `cutaway info` prints them) or RAS
/// (as 3D Slicer and MNI atlases show them). job/volume_frame.hpp turns
/// LPS and RAS into the volume frame once the scan's geometry is known.
enum class CoordinateSpace { Volume, LPS, RAS };

/// /camera: either an orbit around a target (default the volume centre) or a
/// look-at. Distance 0 means "fit the volume's bounding sphere in view".
struct Camera {
    Projection projection = Projection::Perspective;
    double fovDeg = 30.0;     ///< /camera/fov: vertical field of view, (0, 170)
    double orthoHeight = 0.0; ///< /camera/ortho_height: mm visible vertically; 0 = fit
    bool useOrbit = true;
    // orbit: eye = target + distance * (cos(el) sin(az), -cos(el) cos(az), sin(el)) in the
    // frame whose third axis is `up`; azimuth 0, elevation 0 looks along +y.
    double azimuthDeg = 0.0;
    double elevationDeg = 0.0; ///< (-90, 90)
    double distance = 0.0;     ///< mm from target; 0 = fit
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0, 0.0, 1.0};
    // look_at
    glm::dvec3 eye{0.0, -500.0, 0.0};
    /// /camera/orbit/space or /camera/look_at/space: the frame of `target`,
    /// `eye` and `up` (and of the orbit's directions).
    CoordinateSpace space = CoordinateSpace::Volume;
    bool targetGiven = false; ///< a target left out is the volume's centre in every space
    /// Turns directions (`up`, the orbit's) into the volume frame: identity
    /// until job/volume_frame.hpp places a camera given in LPS or RAS.
    glm::dmat3 directionsToVolume{1.0};
    CameraFit fit = CameraFit::Volume;
    /// /camera/margin: a fitted view frames the fit's box itself (its
    /// corners as seen), keeping this fraction of the frame's width and
    /// height free on each side; none: the box's bounding sphere, as before.
    std::optional<double> margin;
    double zoom = 1.0; ///< /camera/zoom: a factor on a fitted view
    /// With CameraFit::Sequence, the bounds (lo, hi in the volume frame) of
    /// what the operators move over the animation, set by the renderer of
    /// the sequence (job/render_job.cpp); none: the frame's own.
    std::optional<std::array<glm::dvec3, 2>> sequenceBounds;
};

struct DirectionalLight {
    glm::dvec3 direction{0.0, 0.0, -1.0}; ///< the direction the light travels, world space
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
};

/// /lights
struct Lights {
    float ambient = 0.2f;   ///< /lights/ambient, [0, 1]
    float headlight = 0.8f; ///< /lights/headlight: intensity of a white light at the eye, [0, 10]
    std::vector<DirectionalLight> directional; ///< /lights/directional, at most 4
};

/// /render/shading: Blinn-Phong material applied to every sample.
struct Shading {
    bool enabled = true;
    float diffuse = 0.8f;
    float specular = 0.3f;
    float shininess = 32.0f; ///< [1, 512]
};

/// /render/classification: how a slab between two slices is classified.
///   "preintegrated": from a table of the slab's front and back values
///                    (no slicing rings on thin or steep features; default)
///   "post":          the transfer function at the slab's front sample only
enum class Classification { Preintegrated, Post };

/// /render/operator_composition: how several operators combine.
///   "separate":   each acts on the original volume in its own box; deformed
///                 boxes must not overlap (section 5.1; default)
///   "sequential": in array order, each acts on the volume the previous ones
///                 left (the intermediate volume is resampled and uploaded),
///                 so boxes may overlap; costs a CPU resample when they change
enum class Composition { Separate, Sequential };

/// /render/method: how the volume integral is taken (docs/design/ray-caster.md;
/// speeds: docs/performance.md#settings-that-matter).
///   "slicing": view-aligned slices with the stencil pass (paper section 5; default)
///   "raycast": a compute pass marching each pixel's ray through the same
///              sample points; up to CW_RAY_MAX_OPERATORS (3) live operators
enum class RenderMethod { Slicing, Raycast };

/// /render/filter: how the values and the gradients that shade them are
/// reconstructed between voxels (shaders/shared/cubic_filter.h).
///   "linear": trilinear (default)
///   "cubic":  tricubic Catmull-Rom over the 4^3 voxels around a sample:
///             through the voxels' values, smooth (C1) where trilinear leaves
///             a terrace at every slice of a thick-slice scan; 1.2-1.7x a
///             whole render on lavapipe (docs/quality.md)
enum class Filter { Linear, Cubic };

/// /render
/// Early ray termination's default: a pixel takes no more samples once its
/// opacity reaches 1 - 1/255, so what it leaves behind could change any
/// channel by at most one step of an 8-bit image (VTK's GPU ray caster stops
/// at the same opacity). 1 takes every sample that can show.
inline constexpr double kDefaultTerminationOpacity = 1.0 - 1.0 / 255.0;

/// /render/refine's default, and under /render/quality "draft".
inline constexpr int kDefaultRefine = 4;
inline constexpr int kDraftRefine = 1;

/// /render/cut_antialias's default: a cut's coverage over one pixel.
inline constexpr double kDefaultCutAntialias = 1.0;

struct RenderSettings {
    int width = 512;           ///< /render/size[0], [1, 16384]
    int height = 512;          ///< /render/size[1]
    double sliceSpacing = 1.0; ///< /render/slice_spacing: in voxels (smallest spacing), [0.05, 16]
    glm::vec4 background{0, 0, 0, 1}; ///< /render/background: RGB(A) or "transparent" (0,0,0,0)
    Classification classification = Classification::Preintegrated;
    Composition composition = Composition::Separate;
    RenderMethod method = RenderMethod::Slicing;
    /// /render/termination_opacity, [0.5, 1]: see kDefaultTerminationOpacity
    double terminationOpacity = kDefaultTerminationOpacity;
    Shading shading;
    /// /render/jitter: each pixel's samples shifted along its ray by its own
    /// fraction of the slice spacing (shared/sampling.h), turning the slices'
    /// rings into fine noise.
    bool jitter = false;
    /// /render/samples, [1, 64]: passes with evenly spread offsets, averaged.
    int samples = 1;
    /// /render/seed, >= 0: what varies the offsets between frames; none: the
    /// frame number (Scene::frame).
    std::optional<int> seed;
    Filter filter = Filter::Linear;
    /// /render/refine, [1, 8]: the sub-slabs a pre-integrated slab that
    /// shows is taken in; 1 none. /render/quality "draft" makes 1 the default.
    int refine = kDefaultRefine;
    /// /render/cut_antialias, [0, 4] pixels: the width of the footprint
    /// over which a cut's coverage is taken (operator_sample.h, cutCoverage);
    /// 0: each pixel's ray alone decides, and a slanted cut's edge steps.
    double cutAntialias = kDefaultCutAntialias;
};

enum class PixelType { Half, Float };

/// /output/mattes/N: one label's coverage matte.
struct Matte {
    std::string channel; ///< "matte." and the entry as written (a name or an id)
    std::int64_t id = 0; ///< the label id
};

/// At most this many mattes (two colour targets of three channels each).
inline constexpr std::size_t kMaxMattes = 6;

/// /output/compression: OpenEXR's lossless compressions.
enum class Compression { None, Rle, Zips, Zip, Piz };

/// /output
struct OutputSettings {
    std::string pattern = "cutaway_####.exr"; ///< resolved against the scene's folder when relative
    PixelType pixelType = PixelType::Half;    ///< /output/pixel_type: "half" | "float"
    Compression compression = Compression::Zip; ///< /output/compression
    bool png = false;                           ///< /output/png: also write an sRGB PNG preview
    /// /output/aovs "operator_id" (or /output/operator_id, its alias): the
    /// EXR channel "operator_id" (see Image)
    bool operatorId = false;
    bool depth = false;   ///< /output/aovs "Z": the first visible sample's planar depth
    bool labelId = false; ///< /output/aovs "label": the first visible sample's label id
    /// /output/mattes: a coverage matte per label, the EXR channel "matte.<entry>"
    std::vector<Matte> mattes;
    /// Whether any AOV needs the label volume on the device (label, mattes).
    bool labelAovs() const { return labelId || !mattes.empty(); }
    /// Whether any channel beyond colour is asked for.
    bool anyAov() const { return operatorId || depth || labelAovs(); }
};

/// /animation/tracks/N/interpolation
enum class Interpolation {
    Linear, ///< straight lines between keys
    Smooth, ///< Catmull-Rom: a C1 Hermite spline through the keys, tangents from the neighbours
    Step    ///< holds each key's value until the next key
};

/// A key of a track: a frame number and a number or an array of numbers.
struct Keyframe {
    double frame = 0.0;
    std::vector<double> value; ///< one entry for a number
    bool isArray = false;      ///< written as an array (a vector), even of length 1
};

/// /animation/tracks/N: drives the value at a JSON pointer into the scene.
struct Track {
    std::string target; ///< JSON pointer, e.g. "/camera/orbit/azimuth"
    Interpolation interpolation = Interpolation::Linear;
    std::vector<Keyframe> keys; ///< strictly increasing frames, all values of one shape
};

/// The largest frame number a scene or the command line may name.
inline constexpr int kMaxFrame = 1000000;

/// /animation: the frames of a sequence and the tracks that change between them.
struct Animation {
    int firstFrame = 0; ///< /animation/frames[0]
    int lastFrame = 0;  ///< /animation/frames[1], inclusive
    double fps = 24.0;  ///< recorded in the EXR headers
    std::vector<Track> tracks;
};

enum class OperatorType { Peeler, Retractor, Pliers, Dilator };

/// /operators/N/alignment/mode (paper section 4)
///   Axis:    every point of the box is operatable (Eq. 6)
///   Surface: points deeper than `depth` below the object's surface are the
///            feature and stay (Eq. 3, 4 with M from the distance field, Eq. 9)
///   Segment: the points of some labels (or of a value range) are the
///            feature and stay (Eq. 3, 4 with M from the segment, Eq. 10)
enum class AlignmentMode { Axis, Surface, Segment };

/// /operators/N/alignment
struct Alignment {
    AlignmentMode mode = AlignmentMode::Axis;
    std::optional<double> threshold; ///< surface: object = value > threshold; none = Otsu
    double depth = 5.0;              ///< surface: tau of Eq. 9, mm below the surface, > 0
    double band = 2.0; ///< delta of Eq. 9 (surface) / smoothing width of M (segment), mm
    std::vector<std::int64_t> labels;           ///< segment: label ids of the feature
    std::optional<std::array<double, 2>> range; ///< segment: [lo, hi] values instead of labels
};

/// /operators/N/glyph: the operator's box drawn as an opaque outline (paper
/// Fig. 8), so a reader sees where a lens or a cut acts.
struct OperatorGlyph {
    bool enabled = false;
    glm::vec3 color{1.0f, 0.8f, 0.25f};
    double width = 0.0; ///< mm, thickness of the outline's bars; 0 = 1/300 of the volume's diagonal
};

/// /operators/N/cut_face: the flat colour illustrators give the faces an
/// operator cuts (the "capped" cross-section of anatomical drawings), mixed
/// over the data's colour in a layer under them. Peelers and retractors only.
struct CutFace {
    glm::vec3 color{1.0f}; ///< linear RGB
    double mix = 1.0;      ///< [0, 1]: 0 the data's colour, 1 the cut face's
    double depth = 1.0;    ///< mm: how deep under the cut the layer reaches
};

/// /operators/N: one manipulation operator (paper section 3; docs/operators.md).
/// Its box is the unit cube [-1, 1]^3 of its local frame, placed in the world
/// by `localToWorld` (Eq. 8: translate, rotate, scale, or a matrix); the
/// tissue surface is toward local +z. Parameters are given in millimetres and
/// degrees in the scene and stored here converted to local units.
struct OperatorSpec {
    OperatorType type = OperatorType::Retractor;
    glm::dmat4 localToWorld{1.0};
    shader::OperatorParams params{};
    glm::ivec3 resolution{64}; ///< /operators/N/resolution: texels of the baked map per axis
    double normalBand = 2.0;   ///< /operators/N/normal_band: D of Eq. 7, mm
    Alignment alignment;       ///< /operators/N/alignment
    std::string name;          ///< /operators/N/name, for messages; default "operator N (type)"
    OperatorGlyph glyph;       ///< /operators/N/glyph
    std::optional<CutFace> cutFace; ///< /operators/N/cut_face; none: the data's own colour
    int index = 0;                  ///< N, for messages that point into the scene
    /// /operators/N/placement/space: the frame `localToWorld` maps into.
    CoordinateSpace space = CoordinateSpace::Volume;
};

/// /meshes/N: an opaque glTF 2.0 model (.gltf or .glb) drawn with depth before
/// the volume, whose slices are depth-tested against it (paper Fig. 10).
struct MeshSpec {
    std::filesystem::path file; ///< resolved against the scene's folder
    /// Model units to mm of the parent frame: translate * rotate * scale * units.
    glm::dmat4 placement{1.0};
    std::optional<glm::vec3> color; ///< /meshes/N/color; none = the model's base colours
    /// /meshes/N/attach: index of the operator whose frame (box centre, box
    /// axes, no scale) is the parent, so the mesh moves with it; none = world.
    std::optional<int> attach;
    std::string name; ///< /meshes/N/name, for messages; default "mesh N"
    /// /meshes/N/placement/space: the frame `placement` maps into (not with `attach`).
    CoordinateSpace space = CoordinateSpace::Volume;
};

struct Scene {
    int version = 1;
    std::filesystem::path file;    ///< the scene file, empty when parsed from a string
    std::filesystem::path baseDir; ///< relative paths resolve against this
    VolumeSource volume;
    std::optional<LabelSource> labels;
    TransferFunction transfer;
    std::vector<LabelTransfer> labelTransfers; ///< /transfer/labels
    /// /transfer/unit_distance, mm, > 0: the thickness every transfer
    /// function's alpha is the opacity of; none: the volume's smallest spacing.
    std::optional<double> unitDistance;
    Camera camera;
    Lights lights;
    RenderSettings render;
    OutputSettings output;
    std::vector<OperatorSpec> operators;
    std::vector<MeshSpec> meshes;
    Animation animation;
    nlohmann::json document; ///< the validated JSON as given (for EXR headers)
    /// The frame this scene is of (sceneAtFrame; the first frame for a scene
    /// as parsed): the default seed of the sampling offsets.
    int frame = 0;
};

/// The thickness in mm that `scene`'s transfer functions' alphas refer to,
/// for a volume whose smallest voxel spacing is `smallestSpacing`.
inline double opacityUnit(const Scene& scene, double smallestSpacing) {
    return scene.unitDistance.value_or(smallestSpacing);
}

/// Parses and validates a scene document. Every problem found is reported at
/// once in one InputError whose message has one line per problem:
///   "SOURCE: /render/size/0: expected an integer in [1, 16384], got -5".
/// `source` names the document in messages (a file path, or "<string>").
/// Files named by the scene must exist (checked here).
Scene parseScene(const nlohmann::json& document, const std::filesystem::path& baseDir,
                 const std::string& source = "<string>");

/// One `--set /json/pointer=VALUE` from the command line. VALUE is read as
/// JSON (42, [1, 2, 3], true, "text") and, failing that, as a plain string.
struct SceneSetting {
    std::string pointer;
    nlohmann::json value;
};

/// Reads a JSON file (syntax errors name line and column), writes `settings`
/// into it (see applySettings in animation.hpp), and parses it. With settings,
/// messages name the source as "FILE (with --set)".
Scene loadScene(const std::filesystem::path& file, const std::vector<SceneSetting>& settings = {});

} // namespace cutaway
