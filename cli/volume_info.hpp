#pragma once
// The text of `cutaway info FILE`: shape, type, spacing, value range and a
// coarse histogram, enough to pick a transfer function's control points.
#include "volume/volume.hpp"

#include <string>

namespace cutaway::cli {

std::string describeVolume(const Volume& volume, const std::string& name);

} // namespace cutaway::cli
