#include "vtk_spec.hpp"

#include "render/camera.hpp"

#include <cstdio>
#include <fstream>

namespace cutaway::bench {
namespace {

nlohmann::json vec(glm::dvec3 v) {
    return {v.x, v.y, v.z};
}

} // namespace

VtkSpec::VtkSpec(std::string dataset, const Scene& base, const BenchOptions& options)
    : m_dataset(std::move(dataset)), m_options(options) {
    m_spec["dataset"] = m_dataset;
    m_spec["width"] = options.width;
    m_spec["height"] = options.height;
    m_spec["warmup"] = 1;
    m_spec["frames"] = options.frames;
    m_spec["background"] = {base.render.background.x, base.render.background.y,
                            base.render.background.z};
    const Shading& s = base.render.shading;
    m_spec["shading"] = {{"enabled", true},
                         {"ambient", base.lights.ambient},
                         {"diffuse", s.diffuse},
                         {"specular", s.specular},
                         {"power", s.shininess}};
    m_spec["cameras"] = nlohmann::json::array();
    m_spec["sample_distances"] = nlohmann::json::array();
    m_transfer = base.transfer;
}

void VtkSpec::setVolume(const Volume& scan, bake::ValueWindow window) {
    m_dims = scan.dims;
    m_spacing = scan.spacing;
    m_spec["dims"] = {scan.dims.x, scan.dims.y, scan.dims.z};
    m_spec["spacing"] = vec(scan.spacing);
    // World space centres the volume on the origin; VTK places voxel centres.
    m_spec["origin"] = vec(-0.5 * scan.extent() + 0.5 * scan.spacing);
    const double smallest = std::min({scan.spacing.x, scan.spacing.y, scan.spacing.z});
    m_spec["opacity_unit_distance"] = smallest;
    nlohmann::json points = nlohmann::json::array();
    for (const TransferPoint& p : m_transfer.points)
        points.push_back({{"value", (p.value - window.lo) / (window.hi - window.lo)},
                          {"color", {p.color.x, p.color.y, p.color.z}},
                          {"alpha", p.alpha}});
    m_spec["transfer"] = points;
    for (const double d : m_options.spacings)
        m_spec["sample_distances"].push_back({{"slice_spacing", d}, {"mm", d * smallest}});
    m_spec["raw"] = "vtk_" + m_dataset + ".u16";
    if (m_options.vtkDir.empty()) return;
    std::filesystem::create_directories(m_options.vtkDir);
    const std::vector<uint16_t> normalized = bake::normalizeVolume(scan, window);
    std::ofstream out(m_options.vtkDir / m_spec["raw"].get<std::string>(), std::ios::binary);
    out.write(reinterpret_cast<const char*>(normalized.data()),
              std::streamsize(normalized.size() * sizeof(uint16_t)));
}

void VtkSpec::addCamera(const Scene& scene, double spacing) {
    if (spacing != 1.0 || m_dims.x == 0) return;
    const glm::dvec3 extent = glm::dvec3(m_dims) * m_spacing;
    const render::Box box{-0.5 * extent, 0.5 * extent};
    const render::CameraMatrices cam =
        render::computeCamera(scene.camera, box, scene.render.width, scene.render.height);
    const glm::dvec3 focal = glm::dvec3(0.0) + scene.camera.target;
    const double distance = glm::length(focal - cam.eye);
    nlohmann::json c;
    c["position"] = vec(cam.eye);
    c["focal_point"] = vec(cam.eye + cam.forward * distance);
    c["view_up"] = vec(scene.camera.up);
    c["view_angle"] = scene.camera.fovDeg;
    c["parallel"] = !cam.perspective;
    c["parallel_scale"] = 0.5 * scene.camera.orthoHeight;
    c["clipping_range"] = {std::max(1.0, distance - box.radius() * 1.01),
                           distance + box.radius() * 1.01};
    m_spec["cameras"].push_back(c);
}

void VtkSpec::write(const std::filesystem::path& dir) const {
    if (m_spec["cameras"].empty()) return;
    std::ofstream out(dir / ("vtk_" + m_dataset + ".json"));
    out << m_spec.dump(1) << '\n';
}

} // namespace cutaway::bench
