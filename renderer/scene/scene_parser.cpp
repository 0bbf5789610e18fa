// parseScene and loadScene: the top level of a scene document, and the
// /render and /output sections. The other sections are parsed in
// scene_volume.cpp and scene_camera.cpp.
#include "core/error.hpp"
#include "io/input_file.hpp"
#include "io/json_limits.hpp"
#include "scene/animation.hpp"
#include "scene/json_reader.hpp"
#include "scene/scene.hpp"
#include "scene/scene_sections.hpp"
#include "shared/operator_frame.h"

#include <algorithm>
#include <string>
#include <system_error>

namespace cutaway {

namespace scene_detail {

/// /render: the image and how the volume is sampled.
///
///  * size           [integer, integer], pixels, each in [1, 16384], default [512, 512]
///                   Width and height of the image.
///  * slice_spacing  number, voxels (of the smallest spacing), in [0.05, 16], default 1
///                   Distance between the slices that sample the volume.
///  * background     [number x3] or [number x4], linear RGB(A), each in [0, 1],
///                   or the string "transparent" (= [0, 0, 0, 0]); default [0, 0, 0]
///                   Three numbers mean alpha 1.
///  * classification "preintegrated" or "post", default "preintegrated"
///                   How the slab between two slices is classified: from a table of
///                   its front and back values (no rings on thin features), or from
///                   the transfer function at its front sample only.
///  * operator_composition "separate" or "sequential", default "separate": see
///                   Composition in scene.hpp
///  * method         "slicing" or "raycast", default "slicing": see RenderMethod in
///                   scene.hpp
///  * termination_opacity number, in [0.5, 1], default 1 - 1/255
///                   A pixel takes no more samples once its opacity reaches this
///                   (early ray termination); what lies behind could change a
///                   channel by at most 1 minus it. 1: every sample that can show.
///  * jitter         boolean, default false: each pixel's samples shifted along its
///                   ray by its own fraction of the slice spacing, so the slices'
///                   rings become fine noise (the same offsets in both methods)
///  * samples        integer, in [1, 64], default 1: passes with evenly spread
///                   offsets, averaged (each costs a frame's rendering)
///  * seed           integer, in [0, 2147483647], default the frame number: what
///                   varies the offsets from frame to frame
///  * filter         "linear" or "cubic", default "linear": how values and
///                   gradients are reconstructed between voxels (see Filter)
///  * refine         integer, in [1, 8], default 4 (1 under quality "draft"): the
///                   sub-slabs each pre-integrated slab that shows is taken in,
///                   resolved, classified and lit on its own
///  * quality        "final" or "draft", default "final": draft takes each slab
///                   whole (refine 1), for speed while a scene is being made
///  * cut_antialias  number, in [0, 4], default 1: the footprint, in pixels, over which
///                   a cut's coverage is taken, so a slanted cut has a smooth edge; 0 lets
///                   each pixel's ray decide alone
///  * shading        object, default {}: Blinn-Phong material of every sample
///    * enabled      boolean, default true: false shows the transfer function's colours unlit
///    * diffuse      number, in [0, 1], default 0.8
///    * specular     number, in [0, 1], default 0.3
///    * shininess    number, Blinn-Phong exponent, in [1, 512], default 32
void parseRender(JsonReader& reader, RenderSettings& render) {
    if (const auto size = reader.integers("size", 2, 2, 1, 16384)) {
        render.width = int((*size)[0]);
        render.height = int((*size)[1]);
    }
    render.sliceSpacing = reader.number("slice_spacing", render.sliceSpacing, 0.05, 16.0);

    if (const nlohmann::json* background = reader.find("background")) {
        const std::string pointer = reader.pointerOf("background");
        const char* what = "an array of 3 or 4 numbers in [0, 1], or \"transparent\"";
        if (background->is_array() && (background->size() == 3 || background->size() == 4)) {
            const auto rgba = reader.asNumbers(*background, pointer, 3, 4, Range::closed(0, 1));
            if (rgba) {
                render.background = glm::vec4(glm::dvec4((*rgba)[0], (*rgba)[1], (*rgba)[2],
                                                         rgba->size() == 4 ? (*rgba)[3] : 1.0));
            }
        } else if (background->is_string() && background->get<std::string>() == "transparent") {
            render.background = glm::vec4(0.0f);
        } else {
            reader.expected(pointer, what, *background);
        }
    }

    const std::string classification = reader.string(
        "classification", render.classification == Classification::Post ? "post" : "preintegrated",
        {"preintegrated", "post"});
    render.classification =
        classification == "post" ? Classification::Post : Classification::Preintegrated;

    const std::string composition =
        reader.string("operator_composition", "separate", {"separate", "sequential"});
    render.composition =
        composition == "sequential" ? Composition::Sequential : Composition::Separate;

    const std::string method = reader.string("method", "slicing", {"slicing", "raycast"});
    render.method = method == "raycast" ? RenderMethod::Raycast : RenderMethod::Slicing;
    render.terminationOpacity =
        reader.number("termination_opacity", render.terminationOpacity, 0.5, 1.0);
    render.jitter = reader.boolean("jitter", render.jitter);
    render.samples = int(reader.integer("samples", render.samples, 1, 64));
    if (reader.find("seed")) render.seed = int(reader.integer("seed", 0, 0, 2147483647));
    render.filter = reader.string("filter", render.filter == Filter::Cubic ? "cubic" : "linear",
                                  {"linear", "cubic"}) == "cubic"
                        ? Filter::Cubic
                        : Filter::Linear;
    // The quality only sets refine's default: a refine given wins.
    if (reader.find("quality"))
        render.refine = reader.string("quality", "final", {"final", "draft"}) == "draft"
                            ? kDraftRefine
                            : kDefaultRefine;
    render.refine = int(reader.integer("refine", render.refine, 1, 8));
    render.cutAntialias = reader.number("cut_antialias", render.cutAntialias, 0.0, 4.0);

    reader.object("shading", [&](JsonReader& shading) {
        Shading& s = render.shading;
        s.enabled = shading.boolean("enabled", s.enabled);
        s.diffuse = float(shading.number("diffuse", s.diffuse, 0.0, 1.0));
        s.specular = float(shading.number("specular", s.specular, 0.0, 1.0));
        s.shininess = float(shading.number("shininess", s.shininess, 1.0, 512.0));
    });
}

/// /output/aovs: the names of the channels beside the colour.
void parseAovs(JsonReader& reader, OutputSettings& output,
               const std::optional<LabelSource>& labels) {
    const nlohmann::json* list = reader.find("aovs");
    if (!list) return;
    const std::string pointer = reader.pointerOf("aovs");
    if (!list->is_array() || list->size() > 3) {
        reader.expected(pointer, "an array of \"Z\", \"label\" and \"operator_id\"", *list);
        return;
    }
    std::vector<std::string> seen;
    for (std::size_t i = 0; i < list->size(); ++i) {
        const nlohmann::json& item = (*list)[i];
        const std::string at = pointer + "/" + std::to_string(i);
        const std::string name = item.is_string() ? item.get<std::string>() : std::string();
        if (name != "Z" && name != "label" && name != "operator_id") {
            reader.expected(at, "\"Z\", \"label\" or \"operator_id\"", item);
            continue;
        }
        if (std::find(seen.begin(), seen.end(), name) != seen.end()) {
            reader.diagnostics().error(at, "\"" + name + "\" is listed twice");
            continue;
        }
        seen.push_back(name);
        if (name == "Z") output.depth = true;
        if (name == "operator_id") output.operatorId = true;
        if (name != "label") continue;
        if (!labels)
            reader.diagnostics().error(at, "\"label\" needs a /labels section (a label volume)");
        output.labelId = true;
    }
}

/// /output/mattes: one label name or id per matte.
void parseMattes(JsonReader& reader, OutputSettings& output,
                 const std::optional<LabelSource>& labels) {
    const nlohmann::json* list = reader.find("mattes");
    if (!list) return;
    const std::string pointer = reader.pointerOf("mattes");
    if (!list->is_array() || list->empty() || list->size() > kMaxMattes) {
        reader.expected(pointer,
                        "an array of 1 to " + std::to_string(kMaxMattes) + " label names or ids",
                        *list);
        return;
    }
    if (!labels) {
        reader.diagnostics().error(pointer, "mattes need a /labels section (a label volume)");
        return;
    }
    for (std::size_t i = 0; i < list->size(); ++i) {
        const nlohmann::json& item = (*list)[i];
        const std::string at = pointer + "/" + std::to_string(i);
        Matte matte;
        if (item.is_string()) {
            const auto found = labels->names.find(item.get<std::string>());
            if (found == labels->names.end()) {
                reader.diagnostics().error(at, "unknown label name " + describeValue(item) +
                                                   " (a matte takes one label: no patterns)");
                continue;
            }
            matte = {"matte." + item.get<std::string>(), found->second};
        } else if (const auto id = reader.asInteger(item, at, 0, 2147483647)) {
            matte = {"matte." + std::to_string(*id), *id};
        } else {
            continue;
        }
        const auto same = [&](const Matte& m) { return m.id == matte.id; };
        if (std::any_of(output.mattes.begin(), output.mattes.end(), same)) {
            reader.diagnostics().error(at, "label " + std::to_string(matte.id) +
                                               " already has a matte");
            continue;
        }
        output.mattes.push_back(std::move(matte));
    }
}

/// /output: where and how frames are written.
///
///  * pattern     string, path, non-empty, default "cutaway_####.exr"
///                The EXR file of each frame; a run of '#' is replaced by the
///                zero-padded frame number. Relative paths are relative to the
///                scene file's folder.
///  * pixel_type  string, "half" or "float", default "half": EXR channel type
///  * compression string, "none", "rle", "zips", "zip" or "piz", default "zip":
///                the EXR's compression, all lossless
///  * png         boolean, default false: also write an 8-bit sRGB PNG preview
///  * aovs        array of "Z", "label", "operator_id", default []: float channels
///                beside the colour (docs/compositing.md): the planar depth of the
///                first visible sample (a mesh's where it is nearer, infinity where
///                nothing shows), that sample's label id (0 where none), the
///                operator (0-based) it came from (-1 the untouched volume, -2 none)
///  * operator_id boolean, default false: the same as "operator_id" in aovs
///  * mattes      array of label names or ids, at most 6, default []: a channel
///                "matte.<entry>" per entry, the share of each pixel's colour that
///                samples of that label give
void parseOutput(JsonReader& reader, OutputSettings& output,
                 const std::optional<LabelSource>& labels) {
    output.pattern = reader.string("pattern", output.pattern);
    output.pixelType = reader.string("pixel_type", "half", {"half", "float"}) == "float"
                           ? PixelType::Float
                           : PixelType::Half;
    const std::string compression =
        reader.string("compression", "zip", {"none", "rle", "zips", "zip", "piz"});
    output.compression = compression == "none"   ? Compression::None
                         : compression == "rle"  ? Compression::Rle
                         : compression == "zips" ? Compression::Zips
                         : compression == "piz"  ? Compression::Piz
                                                 : Compression::Zip;
    output.png = reader.boolean("png", output.png);
    output.operatorId = reader.boolean("operator_id", output.operatorId);
    parseAovs(reader, output, labels);
    parseMattes(reader, output, labels);
}

} // namespace scene_detail

/// The top level of a scene document.
///
///  * version    integer, required, must be 1: the version of this format
///  * volume     object, required: the scalar field (scene_volume.cpp)
///  * transfer   object, default: a grey ramp (scene_volume.cpp)
///  * camera     object, default: an orbit that fits the volume (scene_camera.cpp)
///  * lights     object, default: ambient 0.2 and a headlight 0.8 (scene_camera.cpp)
///  * render     object, default: 512 x 512, black background, shaded
///  * output     object, default: "cutaway_####.exr" next to the scene, half floats
///  * animation  object, default: one frame, no tracks (scene_animation.cpp)
///  * operators  array, default []: manipulation operators (scene_operators.cpp)
///  * labels     object, default none: a label volume (scene_labels.cpp)
///  * meshes     array, default []: opaque glTF models drawn with the volume (scene_meshes.cpp)
Scene parseScene(const nlohmann::json& document, const std::filesystem::path& baseDir,
                 const std::string& source) {
    using namespace scene_detail;
    Diagnostics diagnostics(source);
    if (!document.is_object()) {
        diagnostics.error("", "expected an object (a scene), got " + describeValue(document));
        diagnostics.throwIfAny();
    }

    Scene scene;
    scene.baseDir = baseDir;
    JsonReader root(document, diagnostics);
    if (const nlohmann::json* version = root.find("version")) {
        // 1.0 is 1 too (JSON Schema counts a number with a zero fraction an integer).
        if (!(version->is_number() && version->get<double>() == 1.0)) {
            root.error("version",
                       "unsupported version: expected 1, got " + describeValue(*version));
        }
    } else {
        root.error("version", "missing; add \"version\": 1 at the top level of the scene");
    }

    root.object(
        "volume", [&](JsonReader& reader) { parseVolume(reader, scene.volume, baseDir); }, true);
    root.object("labels", [&](JsonReader& reader) {
        parseLabels(reader, scene.labels.emplace(), scene.volume, baseDir);
    });
    scene.transfer = defaultTransfer();
    root.object("transfer", [&](JsonReader& reader) {
        parseTransfer(reader, scene.transfer);
        parseLabelTransfers(reader, scene.labelTransfers, scene.labels);
        scene.unitDistance = reader.number("unit_distance", Range::openClosed(0.0, 1e6));
    });
    root.object("camera", [&](JsonReader& reader) { parseCamera(reader, scene.camera); });
    root.object("lights", [&](JsonReader& reader) { parseLights(reader, scene.lights); });
    root.object("render", [&](JsonReader& reader) { parseRender(reader, scene.render); });
    root.object("output",
                [&](JsonReader& reader) { parseOutput(reader, scene.output, scene.labels); });
    root.object("animation", [&](JsonReader& reader) { parseAnimation(reader, scene.animation); });
    scene.frame = scene.animation.firstFrame;
    parseOperators(root, scene.operators, scene.labels);
    parseMeshes(root, scene.meshes, scene.operators.size(), baseDir);
    // Sequential composition resamples the scan but not its labels or masks.
    if (scene.render.composition == Composition::Sequential && scene.operators.size() > 1) {
        for (std::size_t i = 0; i < scene.operators.size(); ++i) {
            const Alignment& a = scene.operators[i].alignment;
            const std::string at = "/operators/" + std::to_string(i) + "/alignment";
            if (i + 1 < scene.operators.size() && a.mode != AlignmentMode::Axis)
                diagnostics.error(at + "/mode",
                                  "under \"operator_composition\": \"sequential\" only the "
                                  "last operator may be surface- or segment-aligned");
            else if (!a.labels.empty())
                diagnostics.error(at + "/labels",
                                  "under \"operator_composition\": \"sequential\" the scan is "
                                  "resampled and its labels no longer match: use \"range\"");
        }
        if (scene.output.labelAovs())
            diagnostics.error(scene.output.labelId ? "/output/aovs" : "/output/mattes",
                              "label channels need \"operator_composition\": \"separate\" when "
                              "there are several operators (the scan is resampled, its labels "
                              "are not)");
        if (!scene.labelTransfers.empty())
            diagnostics.error("/transfer/labels",
                              "classification by label needs \"operator_composition\": "
                              "\"separate\" when there are several operators");
    }
    // The ray caster takes a few live operators (under sequential composition
    // only the last is).
    if (scene.render.method == RenderMethod::Raycast) {
        const bool sequential = scene.render.composition == Composition::Sequential;
        const std::size_t live =
            sequential ? std::min<std::size_t>(scene.operators.size(), 1) : scene.operators.size();
        if (live > CW_RAY_MAX_OPERATORS)
            diagnostics.error("/render/method", "\"raycast\" renders scenes with at most " +
                                                    std::to_string(CW_RAY_MAX_OPERATORS) +
                                                    " operators; use \"slicing\"");
    }
    // Relative output patterns (the default too) resolve against the scene's folder.
    const std::filesystem::path pattern(scene.output.pattern);
    if (pattern.is_relative() && !baseDir.empty())
        scene.output.pattern = (baseDir / pattern).lexically_normal().string();

    root.finish();
    diagnostics.throwIfAny();

    scene.document = document;
    return scene;
}

Scene loadScene(const std::filesystem::path& file, const std::vector<SceneSetting>& settings) {
    const std::string source = file.string();
    const std::string text = InputFile(file, "scene").readAll(kMaxSceneBytes);
    nlohmann::json document = parseJsonText(text, source);
    applySettings(document, settings);
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(file, ec);
    const std::filesystem::path baseDir = (ec ? file : absolute).lexically_normal().parent_path();
    Scene scene =
        parseScene(document, baseDir, settings.empty() ? source : source + " (with --set)");
    scene.file = file;
    return scene;
}

} // namespace cutaway
