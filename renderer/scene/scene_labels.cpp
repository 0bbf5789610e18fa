// The /labels section, label references ("skull" or 2) used by /transfer/labels
// and segment alignment, and /transfer/labels itself.
#include "core/error.hpp"
#include "scene/label_table.hpp"
#include "scene/scene_sections.hpp"

#include <algorithm>
#include <fnmatch.h>
#include <system_error>

namespace cutaway::scene_detail {

namespace {

// The label names of the phantoms (volume/phantom.cpp); repeated here so the
// scene library does not link the volume library. Keep the lists in step.
const std::map<std::string, std::int64_t>& phantomLabelNames(const std::string& phantom) {
    static const std::map<std::string, std::int64_t> head{
        {"background", 0}, {"skin", 1}, {"skull", 2}, {"brain", 3}};
    static const std::map<std::string, std::int64_t> orange{
        {"background", 0}, {"rind", 1}, {"pith", 2}, {"segments", 3}};
    static const std::map<std::string, std::int64_t> none;
    return phantom == "head" ? head : phantom == "orange" ? orange : none;
}

// A name with shell wildcards (*, ?, [...]) selects every name it matches.
bool isGlob(const std::string& name) {
    return name.find_first_of("*?[") != std::string::npos;
}

std::string withoutWildcards(std::string pattern) {
    std::erase_if(pattern, [](char c) { return c == '*' || c == '?' || c == '[' || c == ']'; });
    return pattern;
}

// Adds the ids of the names `pattern` matches (fnmatch, case-sensitive, as
// names are); whether any did.
bool addMatches(const std::string& pattern, const std::map<std::string, std::int64_t>& names,
                std::vector<std::int64_t>& ids) {
    bool any = false;
    for (const auto& [name, id] : names)
        if (::fnmatch(pattern.c_str(), name.c_str(), 0) == 0) {
            ids.push_back(id);
            any = true;
        }
    return any;
}

/// /labels/table: the names and colours of a label table file (label_table.hpp).
void readTable(JsonReader& reader, LabelSource& labels, const std::filesystem::path& baseDir) {
    labels.table = readExistingFile(reader, "table", baseDir);
    std::error_code ec;
    if (labels.table.empty() || !std::filesystem::is_regular_file(labels.table, ec)) return;
    try {
        LabelTable table = readLabelTable(labels.table);
        for (const auto& [name, id] : table.names)
            labels.names[name] = id;
        labels.colors = std::move(table.colors);
    } catch (const InputError& e) {
        reader.error("table", e.what());
    }
}

} // namespace

/// /labels: a label volume, for classification by label (/transfer/labels)
/// and segment alignment. Exactly one of `file` or `phantom`.
///
///  * file     string, path: a .nrrd, .nhdr, .nii or .nii.gz label volume of
///             integer ids (any integer type; ids beyond 255 work) on the
///             scan's grid: same dims, same spacing to within 0.1 % (checked on load)
///  * phantom  true: the phantom's own labels (only with /volume/phantom);
///             their names come with them: head: skin 1, skull 2, brain 3;
///             orange: rind 1, pith 2, segments 3
///  * names    object, default {}: name -> id (an integer in [0, 2^31 - 1]),
///             so the scene can say "skull" where it means 2
///  * table    string, path, default none: a label table file (FreeSurfer
///             LUT, ITK-SNAP, 3D Slicer, plain id-name lists; label_table.hpp)
///             giving the names, and colours for "color": "table". Not with `names`.
void parseLabels(JsonReader& reader, LabelSource& labels, const VolumeSource& volume,
                 const std::filesystem::path& baseDir) {
    const bool hasFile = reader.has("file");
    const bool hasPhantom = reader.has("phantom");
    if (hasFile == hasPhantom) {
        reader.errorHere(std::string("expected exactly one of \"file\" or \"phantom\", got ") +
                         (hasFile ? "both" : "neither"));
    }
    labels.file = readExistingFile(reader, "file", baseDir);
    if (hasPhantom) {
        labels.phantom = reader.boolean("phantom", false);
        if (!labels.phantom)
            reader.error("phantom", "expected true (or leave it out and give \"file\")");
        else if (volume.phantom.empty())
            reader.error("phantom", "the volume is not a phantom: give the label \"file\"");
        else
            labels.names = phantomLabelNames(volume.phantom);
    }
    if (reader.has("table") && reader.has("names"))
        reader.errorHere("expected at most one of \"table\" or \"names\", got both");
    readTable(reader, labels, baseDir);
    if (const nlohmann::json* names = reader.find("names")) {
        if (!names->is_object()) {
            reader.expected(reader.pointerOf("names"), "an object of name: id", *names);
        } else {
            for (const auto& [name, id] : names->items()) {
                const std::string pointer =
                    reader.pointerOf("names") + "/" + escapePointerToken(name);
                if (name.empty()) {
                    reader.diagnostics().error(pointer, "a label name must not be empty");
                    continue;
                }
                if (const auto value = reader.asInteger(id, pointer, 0, 2147483647))
                    labels.names[name] = *value;
            }
        }
    }
}

/// A list of label references at `key`: ids (integers >= 0), names from
/// /labels/names, or patterns of them ("Frontal_*", "*_L": shell wildcards *,
/// ? and [...], each selecting every name it matches). Reports unknown names
/// and patterns that match none with the closest known name.
std::optional<std::vector<std::int64_t>> readLabelList(JsonReader& reader, std::string_view key,
                                                       const std::optional<LabelSource>& labels,
                                                       bool required) {
    const nlohmann::json* list = reader.find(key);
    if (!list) {
        if (required) reader.error(key, "missing: a list of label names or ids");
        return std::nullopt;
    }
    const std::string pointer = reader.pointerOf(key);
    if (!labels) {
        reader.diagnostics().error(pointer,
                                   "labels need a /labels section (a label volume) in the scene");
        return std::nullopt;
    }
    if (!list->is_array() || list->empty() || list->size() > 4096) {
        reader.expected(pointer, "a non-empty array of label names or ids", *list);
        return std::nullopt;
    }
    std::vector<std::int64_t> ids;
    std::vector<std::string> known;
    for (const auto& [name, id] : labels->names)
        known.push_back(name);
    bool ok = true;
    for (std::size_t i = 0; i < list->size(); ++i) {
        const nlohmann::json& item = (*list)[i];
        const std::string at = pointer + "/" + std::to_string(i);
        if (item.is_string() && isGlob(item.get<std::string>())) {
            if (!addMatches(item.get<std::string>(), labels->names, ids)) {
                std::string message = "no label name matches the pattern " + describeValue(item);
                if (const auto close =
                        closestMatch(withoutWildcards(item.get<std::string>()), known))
                    message += " (did you mean \"" + *close + "\"?)";
                reader.diagnostics().error(at, message);
                ok = false;
            }
        } else if (item.is_string()) {
            const auto found = labels->names.find(item.get<std::string>());
            if (found != labels->names.end()) {
                ids.push_back(found->second);
                continue;
            }
            std::string message = "unknown label name " + describeValue(item);
            if (const auto close = closestMatch(item.get<std::string>(), known))
                message += " (did you mean \"" + *close + "\"?)";
            else if (known.empty())
                message += " (/labels/names names none)";
            reader.diagnostics().error(at, message);
            ok = false;
        } else if (const auto id = reader.asInteger(item, at, 0, 2147483647)) {
            ids.push_back(*id);
        } else {
            ok = false;
        }
    }
    if (!ok) return std::nullopt;
    return ids;
}

/// "color": "table": one transfer function per label of `set`, its points'
/// opacities in the label's colour from /labels/table.
void addTableColoured(JsonReader& entry, const LabelTransfer& set,
                      const std::optional<LabelSource>& labels,
                      std::vector<LabelTransfer>& transfers) {
    if (!labels || labels->table.empty()) {
        entry.error("color", "\"table\" needs a /labels/table");
        return;
    }
    for (const std::int64_t id : set.ids) {
        const auto colour = labels->colors.find(id);
        if (colour == labels->colors.end()) {
            entry.error("color", "label " + std::to_string(id) + " has no colour in " +
                                     labels->table.string());
            return;
        }
        LabelTransfer one{{id}, set.transfer};
        for (TransferPoint& p : one.transfer.points)
            p.color = colour->second;
        transfers.push_back(std::move(one));
    }
}

/// "color": "auto": one transfer function per label of `set`, its points'
/// opacities in a colour of paletteColour, by the label's rank among the
/// set's ids (ascending): distinct for up to 20 labels, the same on every run.
void addAutoColoured(const LabelTransfer& set, std::vector<LabelTransfer>& transfers) {
    std::vector<std::int64_t> ids = set.ids;
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    for (std::size_t i = 0; i < ids.size(); ++i) {
        LabelTransfer one{{ids[i]}, set.transfer};
        for (TransferPoint& p : one.transfer.points)
            p.color = paletteColour(i);
        transfers.push_back(std::move(one));
    }
}

/// /transfer/labels: an array of objects, each a transfer function for some labels.
///
///  * labels  array of label names or ids, required
///  * points  array of at least 2 control points, as /transfer/points, required
///  * color   "table" or "auto", default none: each label in its /labels/table
///            colour, or in a colour of a categorical palette (addAutoColoured);
///            the points' opacities, their colours not used
///
/// A sample is classified by the transfer function of its voxel's label
/// (nearest voxel); labels not listed use /transfer/points. A label listed
/// twice takes the first entry's function.
void parseLabelTransfers(JsonReader& reader, std::vector<LabelTransfer>& transfers,
                         const std::optional<LabelSource>& labels) {
    reader.objects("labels", 1, 254, [&](JsonReader& entry, std::size_t) {
        LabelTransfer result;
        if (const auto ids = readLabelList(entry, "labels", labels, true)) result.ids = *ids;
        parseTransfer(entry, result.transfer);
        const std::string color = entry.string("color", {"table", "auto"}).value_or("");
        if (color == "table")
            addTableColoured(entry, result, labels, transfers);
        else if (color == "auto")
            addAutoColoured(result, transfers);
        else
            transfers.push_back(std::move(result));
    });
    if (transfers.size() > 254)
        reader.error("labels", "the sets take " + std::to_string(transfers.size()) +
                                   " transfer functions (each label coloured from the table takes "
                                   "its own); at most 254");
}

} // namespace cutaway::scene_detail
