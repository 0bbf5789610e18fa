// listDicom and readDicom: GDCM's parsing in a child process
// (volume/child_process.hpp), its listing or volume sent back field by field.
#include "core/error.hpp"
#include "volume/child_process.hpp"
#include "volume/dicom.hpp"

#include <csignal>
#include <cstring>

namespace cutaway {
namespace {

namespace fs = std::filesystem;
using detail::Wire;
using detail::WireReader;

// The error of a child that died reading `file` (the last it named).
std::string diedReading(const fs::path& path, const std::string& file, int signal,
                        const std::string& said) {
    const std::string what = file.empty() ? path.string() : file;
    const std::string gdcm = said.empty() ? "" : " (GDCM: " + said + ")";
    if (signal == 0) return what + ": the DICOM reader ended without a result" + gdcm;
    const char* name = strsignal(signal);
    return what + ": a damaged or truncated DICOM file: GDCM stopped on it, " +
           (name ? std::string(name) : "signal " + std::to_string(signal)) + gdcm;
}

std::vector<std::byte>
inChild(const fs::path& path,
        const std::function<void(Wire&, const detail::DicomProgress&)>& work) {
    return detail::runInChild(
        [&](detail::ChildChannel& channel) {
            Wire wire;
            work(wire, [&](const std::string& file) { channel.progress(file); });
            channel.result(wire.data());
        },
        [&](const std::string& file, int signal, const std::string& said) {
            return diedReading(path, file, signal, said);
        },
        "GDCM");
}

void put(Wire& w, const DicomListing& listing) {
    w.u64(listing.series.size());
    for (const DicomSeries& s : listing.series) {
        for (const std::string* text : {&s.uid, &s.number, &s.description, &s.modality})
            w.str(*text);
        for (int a = 0; a < 3; ++a)
            w.u64(std::uint64_t(std::int64_t(s.dims[a])));
        w.u64(std::uint64_t(s.bitsAllocated));
        w.u64(s.files.size());
        for (const fs::path& f : s.files)
            w.str(f.string());
    }
    w.u64(listing.ignored);
    w.str(listing.namedUid);
}

DicomListing takeListing(WireReader& r) {
    DicomListing listing;
    listing.series.resize(r.u64());
    for (DicomSeries& s : listing.series) {
        for (std::string* text : {&s.uid, &s.number, &s.description, &s.modality})
            *text = r.str();
        for (int a = 0; a < 3; ++a)
            s.dims[a] = int(std::int64_t(r.u64()));
        s.bitsAllocated = int(r.u64());
        s.files.resize(r.u64());
        for (fs::path& f : s.files)
            f = r.str();
    }
    listing.ignored = r.u64();
    listing.namedUid = r.str();
    return listing;
}

void put(Wire& w, const Volume& v) {
    for (int a = 0; a < 3; ++a)
        w.u64(std::uint64_t(v.dims[a]));
    for (int a = 0; a < 3; ++a)
        w.f64(v.spacing[a]), w.f64(v.origin[a]);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            w.f64(v.direction[c][r]);
    w.u64(std::uint64_t(v.space));
    w.u64(std::uint64_t(v.type));
    w.f64(v.slope), w.f64(v.inter);
    w.bytes(v.data);
}

Volume takeVolume(WireReader& r) {
    Volume v;
    for (int a = 0; a < 3; ++a)
        v.dims[a] = int(r.u64());
    for (int a = 0; a < 3; ++a)
        v.spacing[a] = r.f64(), v.origin[a] = r.f64();
    for (int c = 0; c < 3; ++c)
        for (int row = 0; row < 3; ++row)
            v.direction[c][row] = r.f64();
    v.space = Space(r.u64());
    v.type = VoxelType(r.u64());
    v.slope = r.f64(), v.inter = r.f64();
    v.data = r.bytes();
    return v;
}

} // namespace

DicomListing listDicom(const fs::path& path) {
    const std::vector<std::byte> bytes =
        inChild(path, [&](Wire& w, const detail::DicomProgress& progress) {
            put(w, detail::listDicomHere(path, progress));
        });
    WireReader reader(bytes);
    return takeListing(reader);
}

Volume readDicom(const fs::path& path, std::string_view selector) {
    const std::string wanted(selector);
    const std::vector<std::byte> bytes =
        inChild(path, [&](Wire& w, const detail::DicomProgress& progress) {
            put(w, detail::readDicomHere(path, wanted, progress));
        });
    WireReader reader(bytes);
    return takeVolume(reader);
}

} // namespace cutaway
