#pragma once
// What GDCM would allocate, checked first: GDCM sizes a value's buffer by
// its declared length before it reads the value (volume/dicom_lengths.cpp).
#include <string>

namespace cutaway::detail {

/// Walks the element headers of `file` up to its pixel data. A file with
/// DICOM's preamble that declares an element longer than the bytes after it
/// throws InputError naming the element; a file without the preamble whose
/// headers fit neither explicit nor implicit VR is no DICOM (false), and GDCM
/// need not read it. Big-endian and deflated data sets are left to GDCM.
bool checkDeclaredLengths(const std::string& file);

/// Whether `file` has DICOM's preamble: 128 bytes, then "DICM".
bool hasDicomPreamble(const std::string& file);

} // namespace cutaway::detail
