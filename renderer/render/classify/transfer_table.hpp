#pragma once
// The piecewise-linear transfer function tabulated over the value window, as
// uploaded into an RGBA16F texture (colour straight, alpha per reference step).
#include "bake/volume_upload.hpp"
#include "scene/scene.hpp"

#include <glm/glm.hpp>
#include <vector>

namespace cutaway::render {

constexpr int kTransferTableSize = 1024;

/// Entry i holds the transfer function at value lo + (hi - lo) * i / (n - 1),
/// the first and last at window.below and window.above (the values the
/// voxels clamped to the window's ends stand for).
std::vector<glm::vec4> tabulateTransfer(const TransferFunction& tf, bake::ValueWindow window,
                                        int n = kTransferTableSize);

/// The functions a scene classifies with, in the order of the table's layers:
/// /transfer, then /transfer/labels when the volume has labels.
std::vector<const TransferFunction*> classifyingTransfers(const Scene& scene, bool withLabels);

/// Evaluates the piecewise-linear function at one value (clamped to the end points).
glm::vec4 evaluateTransfer(const TransferFunction& tf, double value);

} // namespace cutaway::render
