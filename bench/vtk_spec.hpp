#pragma once
// The VTK comparison's input (bench/vtk_bench.py): the volume normalized as
// cutaway uploads it (uint16 raw), its transfer function, shading, image size,
// sample distances and the exact cameras of the timed no-operator frames, so
// VTK's CPU ray caster does the same work in the same run.
#include "bake/volume_upload.hpp"
#include "dataset_bench.hpp"
#include "scene/scene.hpp"
#include "volume/volume.hpp"

#include <nlohmann/json.hpp>

namespace cutaway::bench {

class VtkSpec {
public:
    VtkSpec(std::string dataset, const Scene& base, const BenchOptions& options);
    /// Writes the raw volume right away (when the options name a folder).
    void setVolume(const Volume& scan, bake::ValueWindow window);
    /// Records the camera of a timed frame (at slice spacing 1.0; others ignored).
    void addCamera(const Scene& scene, double spacing);
    void write(const std::filesystem::path& dir) const;

private:
    std::string m_dataset;
    BenchOptions m_options;
    nlohmann::json m_spec;
    TransferFunction m_transfer;
    glm::ivec3 m_dims{0};
    glm::dvec3 m_spacing{1.0};
};

} // namespace cutaway::bench
