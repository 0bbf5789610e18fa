#pragma once
// Otsu's threshold: the value that best splits a volume into two classes
// (background and object) by maximizing the between-class variance of a
// 256-bin histogram over the volume's value range. Used to segment the
// background for the distance field of surface alignment (paper section 4.2).
#include "volume/volume.hpp"

namespace cutaway {

/// The threshold in physical units: voxels with value > threshold form the
/// upper class. A constant volume gives its value; NaN voxels are ignored.
/// When several splits are equally good (e.g. a volume of two values), the
/// middle of them is taken.
double otsuThreshold(const Volume& volume);

} // namespace cutaway
