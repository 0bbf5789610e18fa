#include "scene/scene_sections.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <limits>

namespace cutaway::scene_detail {
namespace {

/// /meshes/N/placement: the model in its parent frame (the world, or the
/// attached operator's frame), applied as translate * rotate * scale * units.
///
///  * translate  [number x3], mm, default [0, 0, 0]
///  * rotate     [number x3], degrees about x, then y, then z, default [0, 0, 0]
///  * scale      number or [number x3], each in (0, 1e4], default 1: a factor
///               (an operator's scale is its box size; a mesh's is a factor)
///  * units      "m" | "mm", default "m": the model's length unit. glTF models
///               are in metres by the glTF specification, so "m" multiplies by 1000.
///  * space      "volume" | "lps" | "ras", default "volume": the frame the model is
///               placed in (scene.hpp, CoordinateSpace); not with `attach`
glm::dmat4 parseMeshPlacement(JsonReader& r) {
    const glm::dvec3 t = r.vec3("translate", glm::dvec3(0.0), Range::closed(-1e6, 1e6));
    const glm::dvec3 deg = r.vec3("rotate", glm::dvec3(0.0), Range::closed(-36000, 36000));
    glm::dvec3 scale(1.0);
    if (const nlohmann::json* s = r.find("scale")) {
        if (s->is_number())
            scale = glm::dvec3(r.number("scale", Range::openClosed(0.0, 1e4)).value_or(1.0));
        else
            scale = r.vec3("scale", glm::dvec3(1.0), Range::openClosed(0.0, 1e4));
    }
    const std::string units = r.string("units", "m", {"m", "mm"});
    const double unit = units == "m" ? 1000.0 : 1.0;
    return glm::scale(translateRotate(t, deg), scale * unit);
}

} // namespace

/// /meshes: opaque models drawn with the volume (paper Fig. 10), at most 16.
///
///  * file       string, required: a glTF 2.0 model, .gltf (with its buffers) or
///               .glb, relative to the scene's folder; read when the scene renders
///  * name       string, default "mesh N": used in messages
///  * placement  object, default identity: see parseMeshPlacement
///  * color      [r, g, b] in [0, 1], default: the model's base colours
///  * attach     integer, an index into /operators, default none: the mesh is
///               placed in that operator's frame (origin at its box centre,
///               axes along its box edges, unscaled) and moves with it
void parseMeshes(JsonReader& root, std::vector<MeshSpec>& meshes, std::size_t operatorCount,
                 const std::filesystem::path& baseDir) {
    root.objects("meshes", 0, 16, [&](JsonReader& r, std::size_t index) {
        MeshSpec mesh;
        mesh.file = readExistingFile(r, "file", baseDir);
        if (!r.has("file")) r.error("file", "missing: expected a .gltf or .glb file");
        const std::string ext = mesh.file.extension().string();
        if (!mesh.file.empty() && ext != ".gltf" && ext != ".glb" && ext != ".GLTF" &&
            ext != ".GLB")
            r.error("file", "expected a glTF 2.0 model (.gltf or .glb), got \"" +
                                mesh.file.filename().string() + "\"");
        mesh.name = r.string("name", "mesh " + std::to_string(index));
        r.object("placement", [&](JsonReader& p) {
            mesh.space = readSpace(p);
            mesh.placement = parseMeshPlacement(p);
        });
        if (!r.has("placement")) mesh.placement = glm::scale(glm::dmat4(1.0), glm::dvec3(1000.0));
        mesh.color = r.colour("color");
        if (r.has("attach")) {
            const auto limit = static_cast<std::int64_t>(operatorCount);
            // Without operators, an index of the right type is still wrong;
            // one of the wrong type is reported as such.
            if (operatorCount == 0) {
                if (r.integer("attach", {0, std::numeric_limits<std::int32_t>::max()}))
                    r.error("attach", "there are no operators to attach to");
            } else if (const auto i = r.integer("attach", {0, limit - 1})) {
                mesh.attach = static_cast<int>(*i);
            }
            if (mesh.space != CoordinateSpace::Volume)
                r.diagnostics().error(r.pointerOf("placement") + "/space",
                                      "an attached mesh is placed in its operator's frame: "
                                      "leave out \"space\" or \"attach\"");
        }
        meshes.push_back(mesh);
    });
}

} // namespace cutaway::scene_detail
