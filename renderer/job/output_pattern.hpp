#pragma once
// Output patterns: a frame's file name from /output/pattern or -o.
#include <filesystem>
#include <string>

namespace cutaway::job {

/// Expands "####" (any run of #) or "%0Nd" / "%Nd" / "%d" in `pattern` with
/// `frame`, padded to the run's length or N with zeros (spaces for "%Nd").
/// "%%" is one '%', as in printf; a pattern without a placeholder is
/// otherwise used as is.
std::string expandPattern(const std::string& pattern, int frame);

/// How many frame-number placeholders `pattern` holds (runs of #, %d forms);
/// a run of several frames needs exactly one.
int framePlaceholders(const std::string& pattern);

/// The PNG preview path that goes with an EXR path (same name, .png).
std::filesystem::path previewPath(const std::filesystem::path& exrPath);

} // namespace cutaway::job
