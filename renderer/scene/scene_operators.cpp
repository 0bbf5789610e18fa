#include "scene/scene_sections.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace cutaway::scene_detail {

glm::dmat4 translateRotate(glm::dvec3 translate, glm::dvec3 rotateDeg) {
    glm::dmat4 a = glm::translate(glm::dmat4(1.0), translate);
    a = glm::rotate(a, glm::radians(rotateDeg.z), glm::dvec3(0, 0, 1));
    a = glm::rotate(a, glm::radians(rotateDeg.y), glm::dvec3(0, 1, 0));
    return glm::rotate(a, glm::radians(rotateDeg.x), glm::dvec3(1, 0, 0));
}

namespace {

constexpr double kPi = 3.14159265358979323846;

/// /operators/N/placement (Eq. 8): the operator's unit box [-1, 1]^3 in the world.
///
///  * translate  [number x3], mm, world position of the box centre, default [0, 0, 0]
///  * rotate     [number x3], degrees about x, then y, then z (world axes), default [0, 0, 0]
///  * scale      [number x3], mm, each in (0, 1e5], required: the box's edge lengths
///  or instead of the three:
///  * matrix     [number x16], row-major 4x4 affine map from the unit box to the world
///               (last row 0 0 0 1, invertible)
///  * space      "volume" | "lps" | "ras", default "volume": the frame the box is
///               placed in (scene.hpp, CoordinateSpace); its axes and rotations
///               are that frame's axes
glm::dmat4 parsePlacement(JsonReader& r, glm::dvec3& halfSize) {
    if (const nlohmann::json* m = r.find("matrix")) {
        for (const char* key : {"translate", "rotate", "scale"})
            if (r.find(key)) r.error(key, "not allowed together with \"matrix\"");
        const auto v = r.asNumbers(*m, r.pointerOf("matrix"), 16, 16, Range::closed(-1e6, 1e6));
        if (!v) return glm::dmat4(1.0);
        glm::dmat4 a(1.0);
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col)
                a[col][row] = (*v)[std::size_t(row * 4 + col)];
        const bool affine = a[0][3] == 0 && a[1][3] == 0 && a[2][3] == 0 && a[3][3] == 1;
        const double det = glm::determinant(glm::dmat3(a));
        if (!affine || std::abs(det) < 1e-9)
            r.error("matrix", "expected an invertible affine matrix (last row 0 0 0 1)");
        for (int c = 0; c < 3; ++c)
            halfSize[c] = glm::length(glm::dvec3(a[c]));
        return a;
    }
    const glm::dvec3 t = r.vec3("translate", glm::dvec3(0.0), Range::closed(-1e6, 1e6));
    const glm::dvec3 deg = r.vec3("rotate", glm::dvec3(0.0), Range::closed(-36000, 36000));
    const glm::dvec3 size =
        r.vec3("scale", Range::openClosed(0.0, 1e5), true).value_or(glm::dvec3(2.0));
    halfSize = 0.5 * size;
    return glm::scale(translateRotate(t, deg), halfSize);
}

float f(double v) {
    return static_cast<float>(v);
}

/// /operators/N/params of a peeler (lengths in mm along the box's local axes):
///  * hinge      number, mm from the box centre along local x, in (-scale/2, scale/2), default 0
///  * thickness  number, mm, layer lifted, in (0, scale_z), default scale_z / 10 (a layer
///               as deep as the box would make the bottom face a cut)
///  * radius     number, mm, bend radius, in (0, 1e5], default scale_z / 10
///  * angle      number, degrees, fold angle, in [0, 180], default 120
///  * width      number, mm along local y, in (0, 1e5], default scale_y (the whole box)
void peeler(JsonReader& r, glm::dvec3 h, shader::OperatorParams& p) {
    const double hinge = r.number("hinge", 0.0, Range::open(-h.x, h.x));
    const double thickness = r.number("thickness", 0.2 * h.z, Range::open(0.0, 2.0 * h.z));
    const double radius = r.number("radius", 0.2 * h.z, Range::openClosed(0.0, 1e5));
    const double angle = r.number("angle", 120.0, Range::closed(0.0, 180.0));
    const double width = r.number("width", 2.0 * h.y, Range::openClosed(0.0, 1e5));
    // In the peeler's frame of equal units, the box's half z (operators.h).
    p.a = glm::vec4(f(hinge / h.z), f(thickness / h.z), f(radius / h.z), f(angle * kPi / 180.0));
    p.b = glm::vec4(f(0.5 * width / h.z), 0.0f, f(h.x / h.z), f(h.y / h.z));
    p.kind.x = CW_OP_PEELER;
}

/// retractor:
///  * length   number, mm along local y, in (0, scale_y], default 0.6 scale_y
///  * depth    number, mm from the surface (local +z face) down, in (0, scale_z], default scale_z /
///  2
///  * opening  number, mm, full width of the opening at the surface, in [0, 0.9 scale_x],
///             default 0.3 scale_x
void retractor(JsonReader& r, glm::dvec3 h, shader::OperatorParams& p) {
    const double length = r.number("length", 1.2 * h.y, Range::openClosed(0.0, 2.0 * h.y));
    const double depth = r.number("depth", h.z, Range::openClosed(0.0, 2.0 * h.z));
    const double opening = r.number("opening", 0.6 * h.x, Range::closed(0.0, 1.8 * h.x));
    p.a = glm::vec4(f(0.5 * length / h.y), f(depth / h.z), f(0.5 * opening / h.x), 0.0f);
    p.kind.x = CW_OP_RETRACTOR;
}

/// pliers (a sphere of influence in the box's local frame):
///  * grasp         [number x3], mm from the box centre, default [0, 0, 0]
///  * radius        number, mm (in units of the smallest half edge), in (0, 1e5],
///                  default half the smallest edge; the sphere must fit in the box
///  * displacement  [number x3], mm, default [0, 0, 0]; |d| * 1.72 / radius < 1 so the
///                  map stays invertible
void pliers(JsonReader& r, glm::dvec3 h, shader::OperatorParams& p) {
    const double hMin = std::min({h.x, h.y, h.z});
    const glm::dvec3 grasp = r.vec3("grasp", glm::dvec3(0.0), Range::closed(-1e5, 1e5)) / h;
    const double radius = r.number("radius", 0.5 * hMin, Range::openClosed(0.0, 1e5)) / hMin;
    const glm::dvec3 d = r.vec3("displacement", glm::dvec3(0.0), Range::closed(-1e5, 1e5)) / h;
    for (int a = 0; a < 3; ++a)
        if (std::abs(grasp[a]) + radius > 1.0 + 1e-9) {
            r.error("radius", "expected the sphere of influence (grasp +- radius) to fit in the "
                              "operator's box, so its faces stay fixed");
            break;
        }
    const double contraction = glm::length(d) * 1.7173 / radius;
    if (contraction >= 0.95)
        r.error("displacement",
                "expected |displacement| * 1.72 / radius < 0.95 so the backward map converges "
                "(got " +
                    describeValue(contraction) +
                    "): use a larger radius or a smaller displacement");
    p.a = glm::vec4(glm::vec3(grasp), f(radius));
    p.b = glm::vec4(glm::vec3(d), 0.0f);
    p.kind.x = CW_OP_PLIERS;
}

/// dilator (a volumetric magic lens):
///  * radius         number, mm (in units of the smallest half edge), inner region
///                   magnified uniformly, in (0, 1e5), default a fifth of the smallest edge
///  * magnification  number, in [0.1, 10], default 2; radius * magnification must stay
///                   inside the box
///  * shape          "sphere" or "cylinder" (about local z), default "sphere"
void dilator(JsonReader& r, glm::dvec3 h, shader::OperatorParams& p) {
    const double hMin = std::min({h.x, h.y, h.z});
    const double radius = r.number("radius", 0.4 * hMin, Range::open(0.0, 1e5)) / hMin;
    const double m = r.number("magnification", 2.0, Range::closed(0.1, 10.0));
    const std::string shape = r.string("shape", "sphere", {"sphere", "cylinder"});
    if (radius * std::max(m, 1.0) >= 0.95)
        r.error("radius", "expected radius * max(magnification, 1) < 0.95 of the smallest half "
                          "edge, so the lens fits in the operator's box");
    p.a = glm::vec4(f(radius), f(m), shape == "cylinder" ? 1.0f : 0.0f, 0.0f);
    p.kind.x = CW_OP_DILATOR;
}

/// /operators/N/alignment: which points of the operator's box may move
/// (paper section 4; docs/operators.md).
///
///  * mode       "axis" | "surface" | "segment", default "axis"
///               axis: every point (Eq. 6). surface: all but the points deeper
///               than `depth` below the object's surface. segment: all but the
///               points of `labels` (or of `range`).
///  * threshold  number (volume value) or "otsu", default "otsu"; surface only:
///               voxels with a value above it are the object, the rest background
///  * depth      number, mm, in (0, 10000], default 5; surface only: tau of Eq. 9
///  * band       number, mm, in [0, 1000], default 2: surface: delta of Eq. 9,
///               the band over which normals blend to the feature's; segment:
///               the width over which the mask M is smoothed (Eq. 10)
///  * labels     array of label names or ids; segment only, needs /labels
///  * range      [lo, hi], volume values, lo <= hi; segment only, instead of labels:
///               the voxels with a value in [lo, hi] are the feature
Alignment parseAlignment(JsonReader& a, const std::optional<LabelSource>& labels) {
    Alignment result;
    const std::string mode = a.string("mode", "axis", {"axis", "surface", "segment"});
    result.mode = mode == "surface"   ? AlignmentMode::Surface
                  : mode == "segment" ? AlignmentMode::Segment
                                      : AlignmentMode::Axis;
    const auto onlyFor = [&](std::string_view key, std::string_view wanted) {
        if (mode != wanted && a.has(key))
            a.error(key, "only with \"mode\": \"" + std::string(wanted) + "\"");
    };
    onlyFor("threshold", "surface");
    onlyFor("depth", "surface");
    onlyFor("labels", "segment");
    onlyFor("range", "segment");
    if (mode == "axis" && a.has("band")) a.error("band", "only with \"surface\" or \"segment\"");
    if (mode == "axis") return result;
    result.band = a.number("band", result.band, Range::closed(0.0, 1000.0));
    if (mode == "surface") {
        if (const nlohmann::json* t = a.find("threshold")) {
            if (t->is_string()) {
                if (t->get<std::string>() != "otsu")
                    a.expected(a.pointerOf("threshold"), "a number or \"otsu\"", *t);
            } else {
                result.threshold = a.number("threshold", Range::closed(-kMaxValue, kMaxValue));
            }
        }
        result.depth = a.number("depth", result.depth, Range::openClosed(0.0, 1.0e4));
        return result;
    }
    const bool hasLabels = a.has("labels"), hasRange = a.has("range");
    if (hasLabels == hasRange) {
        a.errorHere(std::string("segment alignment needs exactly one of \"labels\" or "
                                "\"range\", got ") +
                    (hasLabels ? "both" : "neither"));
    }
    if (hasLabels) {
        if (const auto ids = readLabelList(a, "labels", labels, true)) result.labels = *ids;
    }
    if (hasRange) {
        if (const auto range = a.numbers("range", 2, 2, Range::closed(-kMaxValue, kMaxValue))) {
            if ((*range)[0] <= (*range)[1])
                result.range = std::array<double, 2>{(*range)[0], (*range)[1]};
            else
                a.expected(a.pointerOf("range"), "[lo, hi] with lo <= hi", *a.find("range"));
        }
    }
    return result;
}

/// /operators/N/glyph: true, false, or an object:
///  * show   boolean, default true
///  * color  [r, g, b] in [0, 1], default [1, 0.8, 0.25]
///  * width  number, mm, in (0, 1000], default 1/300 of the volume's diagonal
void parseGlyph(JsonReader& r, OperatorGlyph& glyph) {
    const nlohmann::json* g = r.find("glyph");
    if (!g) return;
    if (g->is_boolean()) {
        glyph.enabled = g->get<bool>();
        return;
    }
    if (!g->is_object()) {
        r.expected(r.pointerOf("glyph"), "true, false or an object", *g);
        return;
    }
    r.object("glyph", [&](JsonReader& o) {
        glyph.enabled = o.boolean("show", true);
        glyph.color = o.colour("color", glyph.color);
        glyph.width = o.number("width", glyph.width, Range::openClosed(0.0, 1000.0));
    });
}

/// /operators/N/cut_face: an object, for peelers and retractors (pliers and
/// dilators cut nothing).
///  * color   [number x3], linear RGB in [0, 1], required
///  * mix     number in [0, 1], default 1: how much of it over the data's colour
///  * depth   number, mm, in (0, 1000], default 1: the layer under the cut it colours
void parseCutFace(JsonReader& r, const std::string& type, std::optional<CutFace>& cutFace) {
    if (!r.find("cut_face")) return;
    if (type == "pliers" || type == "dilator") {
        r.error("cut_face", type + " cut nothing: only \"peeler\" and \"retractor\" take it");
        return;
    }
    r.object("cut_face", [&](JsonReader& c) {
        CutFace face;
        face.color = c.colour("color", true).value_or(face.color);
        face.mix = c.number("mix", face.mix, Range::closed(0.0, 1.0));
        face.depth = c.number("depth", face.depth, Range::openClosed(0.0, 1000.0));
        cutFace = face;
    });
}

} // namespace

/// /operators: an array of manipulation operators, rendered together; their
/// deformed boxes must not overlap (see docs/operators.md).
///
///  * type         "peeler" | "retractor" | "pliers" | "dilator", required
///  * name         string, default "operator N (TYPE)": used in messages
///  * placement    object, required: see parsePlacement
///  * alignment    object, default {"mode": "axis"}: see parseAlignment
///  * params       object, default {}: per type, see above
///  * resolution   integer in [8, 256], texels of the baked map per axis, default 64
///  * normal_band  number, mm, in [0, 1000], default 2: D of Eq. 7, the band over
///                 which normals blend to the cut's normal
///  * glyph        boolean or object, default false: the box's outline, see parseGlyph
///  * cut_face     object, default none: the colour of cut faces, see parseCutFace
void parseOperators(JsonReader& root, std::vector<OperatorSpec>& operators,
                    const std::optional<LabelSource>& labels) {
    root.objects("operators", 0, 8, [&](JsonReader& r, std::size_t index) {
        OperatorSpec op;
        const std::string type =
            r.string("type", {"peeler", "retractor", "pliers", "dilator"}, true).value_or("");
        op.name = r.string("name", "operator " + std::to_string(index) + " (" + type + ")");
        op.index = static_cast<int>(index);
        glm::dvec3 halfSize(1.0);
        r.object(
            "placement",
            [&](JsonReader& p) {
                op.space = readSpace(p);
                op.localToWorld = parsePlacement(p, halfSize);
            },
            true);
        r.object("alignment", [&](JsonReader& a) { op.alignment = parseAlignment(a, labels); });
        const auto resolution = r.integer("resolution", 64, 8, 256);
        op.resolution = glm::ivec3(static_cast<int>(resolution));
        op.normalBand = r.number("normal_band", op.normalBand, Range::closed(0.0, 1000.0));
        parseGlyph(r, op.glyph);
        parseCutFace(r, type, op.cutFace);
        const glm::dvec3 h = halfSize;
        r.object("params", [&](JsonReader& p) {
            if (type == "peeler") peeler(p, h, op.params);
            if (type == "retractor") retractor(p, h, op.params);
            if (type == "pliers") pliers(p, h, op.params);
            if (type == "dilator") dilator(p, h, op.params);
        });
        if (!r.find("params")) { // defaults: parse an empty object
            const nlohmann::json empty = nlohmann::json::object();
            JsonReader p(empty, r.pointerOf("params"), r.diagnostics());
            if (type == "peeler") peeler(p, h, op.params);
            if (type == "retractor") retractor(p, h, op.params);
            if (type == "pliers") pliers(p, h, op.params);
            if (type == "dilator") dilator(p, h, op.params);
        }
        op.type = type == "peeler"    ? OperatorType::Peeler
                  : type == "pliers"  ? OperatorType::Pliers
                  : type == "dilator" ? OperatorType::Dilator
                                      : OperatorType::Retractor;
        operators.push_back(op);
    });
}

} // namespace cutaway::scene_detail
