#pragma once
// Built-in procedural phantoms: a volume plus a label volume on the same grid,
// generated at any size, so the demo and the fast tests need no scan on disk.
//
//   orange: rind (1), pith (2: the white layer under the rind and the core),
//           segments (3: juice sacs, ~10 wedges separated by pith membranes)
//   head:   skin (1: soft tissue shell), skull (2), brain (3: folded cortex)
//
// Values are uint8 in [0, 255] (CT-like: air 0, soft tissue ~ 60-100,
// bone ~ 200-255). Both phantoms are mirror-symmetric about the plane
// x = extent.x / 2, exactly on the voxel grid, so a symmetric view gives a
// symmetric image. Label 0 is background.
#include "volume/volume.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace cutaway {

struct Phantom {
    Volume values;                       ///< uint8 intensities
    Volume labels;                       ///< uint8 label ids on the same grid
    std::vector<std::string> labelNames; ///< index = label id; [0] = "background"
};

/// Names accepted by makePhantom.
std::vector<std::string> phantomNames();

/// Generates a phantom; dims each in [8, 1024]. Spacing 1 mm unless given.
/// Throws InputError for an unknown name or bad dims.
Phantom makePhantom(std::string_view name, glm::ivec3 dims, glm::dvec3 spacing = glm::dvec3(1.0));

} // namespace cutaway
