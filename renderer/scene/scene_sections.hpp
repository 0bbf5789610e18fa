#pragma once
// Internal to the scene library: one parse function per top-level section of a
// scene document. Each reads its keys from `reader` (the section's object),
// writes them into the section's struct (whose current values are the
// defaults), and reports problems to the reader's diagnostics. The keys of each
// section are documented at the top of its parse function.
#include "scene/json_reader.hpp"
#include "scene/scene.hpp"

#include <filesystem>

namespace cutaway::scene_detail {

/// Bounds that keep numbers far from overflow in the renderer's float math.
inline constexpr double kMaxCoordinate = 1.0e6; ///< mm: positions, distances, heights
inline constexpr double kMaxValue = 1.0e30;     ///< volume values (window, transfer points)

void parseVolume(JsonReader& reader, VolumeSource& volume, const std::filesystem::path& baseDir);
void parseTransfer(JsonReader& reader, TransferFunction& transfer);
/// /labels (scene_labels.cpp); `volume` is the parsed /volume (for its phantom).
void parseLabels(JsonReader& reader, LabelSource& labels, const VolumeSource& volume,
                 const std::filesystem::path& baseDir);
/// /transfer/labels, read from the /transfer reader.
void parseLabelTransfers(JsonReader& reader, std::vector<LabelTransfer>& transfers,
                         const std::optional<LabelSource>& labels);
/// A list of label names or ids at `key`, resolved to ids through `labels`.
std::optional<std::vector<std::int64_t>> readLabelList(JsonReader& reader, std::string_view key,
                                                       const std::optional<LabelSource>& labels,
                                                       bool required);
/// The transfer function used when a scene has no /transfer section.
TransferFunction defaultTransfer();
void parseCamera(JsonReader& reader, Camera& camera);
void parseLights(JsonReader& reader, Lights& lights);
void parseRender(JsonReader& reader, RenderSettings& render);
/// Leaves `output.pattern` as written; parseScene resolves it against the scene's folder.
/// `labels` resolves the label names of /output/mattes.
void parseOutput(JsonReader& reader, OutputSettings& output,
                 const std::optional<LabelSource>& labels);

void parseAnimation(JsonReader& reader, Animation& animation);
/// Reads /operators from the root (an array, so it takes the root reader).
/// `labels` resolves the label names of segment alignment.
void parseOperators(JsonReader& root, std::vector<OperatorSpec>& operators,
                    const std::optional<LabelSource>& labels);

/// /meshes (scene_meshes.cpp), read from the root; `operatorCount` bounds /meshes/N/attach.
void parseMeshes(JsonReader& root, std::vector<MeshSpec>& meshes, std::size_t operatorCount,
                 const std::filesystem::path& baseDir);
/// translate(t) * rotate about z * about y * about x (degrees): the rigid part of a placement.
glm::dmat4 translateRotate(glm::dvec3 translate, glm::dvec3 rotateDeg);

/// Resolves the path at `key` against `baseDir` and reports a missing file or
/// one that is not a regular file (nor a folder, with `folders`). Returns the
/// resolved path (empty if absent).
std::filesystem::path readExistingFile(JsonReader& reader, std::string_view key,
                                       const std::filesystem::path& baseDir, bool folders = false);

/// Reads "space" ("volume" | "lps" | "ras", default "volume"): the frame of a
/// placement's coordinates.
CoordinateSpace readSpace(JsonReader& reader);

/// Reads a direction: 3 numbers in [-kMaxCoordinate, kMaxCoordinate], not all zero.
std::optional<glm::dvec3> readDirection(JsonReader& reader, std::string_view key, bool required);

} // namespace cutaway::scene_detail
