// Finding DICOM series: which files a path names, grouped by
// SeriesInstanceUID through GDCM's Scanner (it reads each file's header up to
// the tags asked for), and picking one.
#include "core/error.hpp"
#include "core/quote_text.hpp"
#include "volume/dicom.hpp"
#include "volume/dicom_lengths.hpp"
#include "volume/io_util.hpp"

#include <algorithm>
#include <gdcmMediaStorage.h>
#include <gdcmReader.h>
#include <gdcmScanner.h>
#include <gdcmTag.h>
#include <map>
#include <set>
#include <sstream>

namespace cutaway {
namespace {

namespace fs = std::filesystem;

const gdcm::Tag kSeriesUid(0x0020, 0x000e);
const gdcm::Tag kSeriesNumber(0x0020, 0x0011);
const gdcm::Tag kSeriesDescription(0x0008, 0x103e);
const gdcm::Tag kModality(0x0008, 0x0060);
const gdcm::Tag kRows(0x0028, 0x0010);
const gdcm::Tag kColumns(0x0028, 0x0011);
const gdcm::Tag kSopClass(0x0008, 0x0016);
const gdcm::Tag kBitsAllocated(0x0028, 0x0100);

// A tag's value as the scanner gives it, without DICOM's padding.
std::string valueOf(const gdcm::Scanner& scanner, const std::string& file, const gdcm::Tag& tag) {
    const char* v = scanner.GetValue(file.c_str(), tag);
    if (!v) return {};
    std::string s(v);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\0'))
        s.pop_back();
    return std::string(detail::trim(s));
}

// The tags the listing reads of one file ("" where absent).
struct FileTags {
    bool dicom = false; // GDCM read its header up to the tags
    std::string uid, number, description, modality, rows, columns, sopClass, bits;
};

// One file's tags, through GDCM's Scanner (a file at a time, so that a
// crash inside GDCM is known to be this file's: the progress names it).
FileTags scanFile(const std::string& file) {
    if (!detail::checkDeclaredLengths(file)) return {};
    gdcm::Scanner scanner;
    for (const gdcm::Tag& t : {kSeriesUid, kSeriesNumber, kSeriesDescription, kModality, kRows,
                               kColumns, kSopClass, kBitsAllocated})
        scanner.AddTag(t);
    if (!scanner.Scan({file})) throw InputError(file + ": GDCM could not scan it for DICOM tags");
    FileTags t;
    t.dicom = scanner.IsKey(file.c_str());
    t.uid = valueOf(scanner, file, kSeriesUid);
    t.number = valueOf(scanner, file, kSeriesNumber);
    t.description = valueOf(scanner, file, kSeriesDescription);
    t.modality = valueOf(scanner, file, kModality);
    t.rows = valueOf(scanner, file, kRows);
    t.columns = valueOf(scanner, file, kColumns);
    t.sopClass = valueOf(scanner, file, kSopClass);
    t.bits = valueOf(scanner, file, kBitsAllocated);
    return t;
}

// A file that says it is DICOM (its preamble) and either is of a series and
// an image class without Rows (the rest of it cut off), or cannot be read at
// all: damaged, not foreign.
bool damaged(const std::string& file, const std::string& uid, const std::string& sopClass) {
    if (!detail::hasDicomPreamble(file)) return false;
    if (!uid.empty() &&
        gdcm::MediaStorage::IsImage(gdcm::MediaStorage::GetMSType(sopClass.c_str())))
        return true;
    gdcm::Reader reader;
    reader.SetFileName(file.c_str());
    return !reader.Read();
}

bool isDicomdir(const fs::path& path) {
    return detail::toLower(path.filename().string()) == "dicomdir";
}

// Whether `inner` (canonical) lies inside folder `outer` (canonical).
bool inside(const fs::path& inner, const fs::path& outer) {
    auto i = inner.begin();
    for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
        if (i == inner.end() || *i != *o) return false;
    return true;
}

// The regular files of folder `root` (its subfolders' too when `recursive`),
// each once, sorted by name (so the order does not depend on the file
// system). Symbolic links to folders are not followed (a link to a parent
// would loop), links to files only to a file inside `root`.
std::vector<std::string> filesIn(const fs::path& root, bool recursive) {
    std::error_code ec;
    const fs::path top = fs::canonical(root, ec);
    if (ec) throw InputError(root.string() + ": " + ec.message());
    std::vector<std::string> files;
    std::set<fs::path> seen; // canonical paths: a file linked twice is read once
    const auto consider = [&](const fs::directory_entry& entry) {
        std::error_code e;
        if (!entry.is_regular_file(e)) return; // a link to a file counts as one
        const fs::path target = fs::canonical(entry.path(), e);
        if (e || (entry.is_symlink(e) && !inside(target, top))) return;
        if (seen.insert(target).second) files.push_back(entry.path().string());
    };
    const auto options = fs::directory_options::skip_permission_denied;
    if (recursive) {
        for (fs::recursive_directory_iterator it(root, options, ec), end; !ec && it != end;
             it.increment(ec))
            consider(*it);
    } else {
        for (fs::directory_iterator it(root, options, ec), end; !ec && it != end; it.increment(ec))
            consider(*it);
    }
    if (ec) throw InputError(root.string() + ": cannot list its files: " + ec.message());
    std::sort(files.begin(), files.end());
    return files;
}

// The files to scan for `path`: a folder's, recursively; a DICOMDIR's
// folder's; a single file's folder's (not recursively).
std::vector<std::string> candidateFiles(const fs::path& path) {
    std::error_code ec;
    const bool folder = fs::is_directory(path, ec);
    const fs::path root = folder ? path : path.parent_path().empty() ? "." : path.parent_path();
    return filesIn(root, folder || isDicomdir(path));
}

int parsedCount(const std::string& text) {
    std::int64_t v = 0;
    return detail::parseInt(text, v) && v > 0 && v < (std::int64_t{1} << 30) ? int(v) : 0;
}

// Series by number (numerically where both are numbers), then UID.
bool seriesBefore(const DicomSeries& a, const DicomSeries& b) {
    std::int64_t na = 0, nb = 0;
    const bool numbers = detail::parseInt(a.number, na) && detail::parseInt(b.number, nb);
    if (numbers && na != nb) return na < nb;
    if (!numbers && a.number != b.number) return a.number < b.number;
    return a.uid < b.uid;
}

} // namespace

bool isDicomPath(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) return true;
    if (isDicomdir(path)) return true;
    if (detail::toLower(path.extension().string()) == ".dcm") return true;
    return fs::is_regular_file(path, ec) && detail::hasDicomPreamble(path.string());
}

namespace detail {

DicomListing listDicomHere(const fs::path& path, const DicomProgress& progress) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw InputError(path.string() + ": no such file or folder");
    const std::vector<std::string> files = candidateFiles(path);
    DicomListing listing;
    std::map<std::string, DicomSeries> byUid;
    const bool namesOneFile = fs::is_regular_file(path, ec) && !isDicomdir(path);
    for (const std::string& file : files) {
        if (progress) progress(file);
        const FileTags tags = scanFile(file);
        const std::string& uid = tags.uid;
        // Not DICOM, or no image (a DICOMDIR, a structured report).
        if (!tags.dicom || uid.empty() || tags.rows.empty()) {
            if (damaged(file, uid, tags.sopClass))
                throw InputError(file + ": a DICOM image without its image (truncated or "
                                        "damaged), or a DICOM file GDCM cannot read");
            ++listing.ignored;
            continue;
        }
        DicomSeries& s = byUid[uid];
        if (s.files.empty()) {
            s.uid = uid;
            s.number = tags.number;
            s.description = tags.description;
            s.modality = tags.modality;
            s.dims = {parsedCount(tags.columns), parsedCount(tags.rows), 0};
            s.bitsAllocated = parsedCount(tags.bits);
        }
        s.files.push_back(file);
        s.dims.z = int(s.files.size());
        if (namesOneFile && fs::equivalent(fs::path(file), path, ec)) listing.namedUid = uid;
    }
    if (namesOneFile && listing.namedUid.empty())
        throw InputError(path.string() + ": not a DICOM image");
    for (auto& [uid, s] : byUid)
        listing.series.push_back(std::move(s));
    std::sort(listing.series.begin(), listing.series.end(), seriesBefore);
    if (listing.series.empty())
        throw InputError(path.string() + ": no DICOM image found (" + std::to_string(files.size()) +
                         " file(s) looked at)");
    return listing;
}

} // namespace detail

std::string describeSeries(const DicomListing& listing) {
    std::ostringstream out;
    // The tags as the files wrote them, escaped: a file cannot put a
    // terminal escape sequence on the screen.
    for (const DicomSeries& s : listing.series) {
        out << "  series " << (s.number.empty() ? "-" : escapeText(s.number)) << "  "
            << (s.description.empty() ? "(no description)"
                                      : "\"" + escapeText(s.description) + "\"")
            << (s.modality.empty() ? "" : "  " + escapeText(s.modality)) << "  " << s.dims.x
            << " x " << s.dims.y << " x " << s.dims.z << "  " << s.files.size() << " file(s)  uid "
            << escapeText(s.uid) << "\n";
    }
    if (listing.ignored > 0)
        out << "  (" << listing.ignored << " other file(s) passed over: not DICOM images)\n";
    return out.str();
}

const DicomSeries& pickSeries(const DicomListing& listing, std::string_view selector,
                              const fs::path& path) {
    std::string wanted(selector);
    if (wanted.empty() && listing.series.size() == 1) return listing.series.front();
    if (wanted.empty() && !listing.namedUid.empty()) wanted = listing.namedUid;
    std::vector<const DicomSeries*> hits;
    for (const DicomSeries& s : listing.series)
        if (s.uid == wanted || (!s.number.empty() && s.number == wanted) ||
            (!s.description.empty() && detail::toLower(s.description) == detail::toLower(wanted)))
            hits.push_back(&s);
    if (hits.size() == 1) return *hits.front();
    std::string why = wanted.empty() ? "holds " + std::to_string(listing.series.size()) +
                                           " series; pick one with /volume/series (its number, "
                                           "UID or description)"
                      : hits.empty() ? "no series matches \"" + escapeText(wanted) + "\""
                                     : std::to_string(hits.size()) + " series match \"" + wanted +
                                           "\"; give the UID";
    throw InputError(path.string() + ": " + why + ":\n" + describeSeries(listing));
}

} // namespace cutaway
