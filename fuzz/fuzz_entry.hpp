#pragma once
// The bodies of the fuzz targets, shared by the libFuzzer executables
// (fuzz_target.cpp, built with -DCUTAWAY_FUZZ=ON) and by the test that
// replays the seed corpus and every regression input in the ordinary build
// (tests/fuzz). Each takes one input and returns normally when cutaway reads
// it or rejects it with an InputError or RuntimeError; anything else (another
// exception, a crash, a sanitizer report) escapes and is a finding.
#include <cstddef>
#include <cstdint>

namespace cutaway::fuzz {

/// JSON text -> what `cutaway validate` does without touching a device or a
/// file: the nesting-limited JSON parse, parseScene (relative paths resolve
/// against the source tree's scenes/ folder, so existing files are found),
/// then the scene of a sample of its frames (validate checks them all).
void fuzzScene(const std::uint8_t* data, std::size_t size);

/// The bytes of an attached-header NRRD (raw or gzip data) -> readNrrdBytes.
void fuzzNrrd(const std::uint8_t* data, std::size_t size);

/// The bytes of a .nii or .nii.gz -> readNiftiBytes.
void fuzzNifti(const std::uint8_t* data, std::size_t size);

/// The bytes of a MetaImage with attached data (.mha) -> readMetaImageBytes.
void fuzzMetaImage(const std::uint8_t* data, std::size_t size);
/// The bytes of a detached NRRD header (.nhdr) -> readNrrdBytes with its
/// data file looked up in fuzz/nhdr_data/ (raw and gzip data files; what a
/// header names beyond them, a folder, a device, is refused unread).
void fuzzNhdr(const std::uint8_t* data, std::size_t size);

/// The bytes of a .gltf or .glb -> loadGltfBytes, the files it names read
/// from scenes/meshes/ (the example models).
void fuzzGltf(const std::uint8_t* data, std::size_t size);

/// The bytes of one DICOM file -> readDicom on it, alone in a folder of
/// this process's own: GDCM parses in a child process, so its assertions
/// must come back as an InputError naming the file.
void fuzzDicom(const std::uint8_t* data, std::size_t size);

} // namespace cutaway::fuzz
