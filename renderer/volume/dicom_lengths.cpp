// The lengths a DICOM file declares, checked against the bytes it holds
// before GDCM reads it: GDCM sizes each value's buffer by its declared
// length before reading it, so a 465-byte file declaring a 1.3 GB element
// took seconds and gigabytes to refuse. The walk reads only element headers
// (tag, VR, length), never values, up to the pixel data.
#include "volume/dicom_lengths.hpp"

#include "core/error.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string_view>

namespace cutaway::detail {
namespace {

constexpr std::uint32_t kUndefined = 0xffffffffu;
constexpr std::uint16_t kItemGroup = 0xfffe;
constexpr std::uint16_t kItem = 0xe000;

struct Element {
    std::uint16_t group = 0, element = 0;
    std::array<char, 2> vr{};
    std::uint32_t length = 0;
    std::uint64_t valueAt = 0; // the file offset of its value
};

std::string tagText(const Element& e) {
    char text[16];
    std::snprintf(text, sizeof text, "(%04X,%04X)", e.group, e.element);
    return text;
}

// VRs whose explicit length has 4 bytes after 2 reserved ones.
bool longLength(std::array<char, 2> vr) {
    static constexpr std::string_view kLong[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ",
                                                 "SV", "UC", "UN", "UR", "UT", "UV"};
    for (std::string_view v : kLong)
        if (v[0] == vr[0] && v[1] == vr[1]) return true;
    return false;
}

class ElementWalk {
public:
    ElementWalk(std::ifstream& in, std::uint64_t size) : m_in(in), m_size(size) {}

    std::uint64_t left(std::uint64_t at) const { return at > m_size ? 0 : m_size - at; }

    /// The element header at `at`, read as explicit or implicit VR (little
    /// endian); none where the file ends first.
    bool read(std::uint64_t at, bool explicitVr, Element& e) {
        unsigned char b[12];
        if (!bytes(at, b, 8)) return false;
        e.group = std::uint16_t(b[0] | b[1] << 8);
        e.element = std::uint16_t(b[2] | b[3] << 8);
        if (e.group == kItemGroup || !explicitVr) {
            e.vr = {0, 0};
            e.length = word(b + 4);
            e.valueAt = at + 8;
            return true;
        }
        e.vr = {char(b[4]), char(b[5])};
        if (!longLength(e.vr)) {
            e.length = std::uint32_t(b[6] | b[7] << 8);
            e.valueAt = at + 8;
            return true;
        }
        if (!bytes(at + 8, b + 8, 4)) return false;
        e.length = word(b + 8);
        e.valueAt = at + 12;
        return true;
    }

    /// Text of the value of `e` (at most 64 bytes), for the transfer syntax.
    std::string text(const Element& e) {
        std::string s(std::min<std::uint32_t>(e.length, 64), '\0');
        if (!bytes(e.valueAt, reinterpret_cast<unsigned char*>(s.data()), s.size())) return {};
        while (!s.empty() && (s.back() == '\0' || s.back() == ' '))
            s.pop_back();
        return s;
    }

private:
    static std::uint32_t word(const unsigned char* b) {
        return std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
               std::uint32_t(b[3]) << 24;
    }
    bool bytes(std::uint64_t at, unsigned char* out, std::size_t n) {
        if (left(at) < n) return false;
        m_in.clear();
        m_in.seekg(std::streamoff(at));
        return bool(m_in.read(reinterpret_cast<char*>(out), std::streamsize(n)));
    }

    std::ifstream& m_in;
    std::uint64_t m_size;
};

// Walks the elements from `at` on (descending into sequences and items,
// skipping other values) until the pixel data, the end of the file or,
// with `group2Only`, the first element past group 0002. Returns the first
// element whose defined length runs past the end of the file, if any;
// `end` is where the walk stopped.
std::optional<Element> walk(ElementWalk& w, std::uint64_t at, bool explicitVr, bool group2Only,
                            std::uint64_t& end, std::string* transferSyntax) {
    Element e;
    // At most kMostElements headers: a large file that is not DICOM may walk
    // as one for long; GDCM decides about what lies beyond.
    constexpr int kMostElements = 100000;
    for (int n = 0; n < kMostElements && w.read(at, explicitVr, e); ++n) {
        if (group2Only && e.group != 0x0002) break;
        const bool pixelData = e.group == 0x7fe0 && e.element == 0x0010;
        if (e.length == kUndefined) {
            // Encapsulated pixel data, or an explicit UN whose contents are
            // implicit VR: the walk ends there.
            if (pixelData || (e.vr[0] == 'U' && e.vr[1] == 'N')) break;
            at = e.valueAt; // a sequence or item of undefined length: its elements follow
            continue;
        }
        if (e.length > w.left(e.valueAt)) return e;
        if (pixelData) break;
        if (transferSyntax && e.group == 0x0002 && e.element == 0x0010) *transferSyntax = w.text(e);
        // Into items and explicit sequences (their elements follow), past other values.
        const bool container = e.group == kItemGroup || (e.vr[0] == 'S' && e.vr[1] == 'Q');
        at = container ? e.valueAt : e.valueAt + e.length;
    }
    end = at;
    return std::nullopt;
}

std::optional<Element> walkDataset(ElementWalk& w, std::uint64_t at, bool explicitVr) {
    std::uint64_t end = 0;
    return walk(w, at, explicitVr, false, end, nullptr);
}

} // namespace

bool checkDeclaredLengths(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return true; // GDCM says what is wrong with a file it cannot open
    in.seekg(0, std::ios::end);
    const std::uint64_t size = std::uint64_t(std::max<std::streamoff>(in.tellg(), 0));
    ElementWalk w(in, size);
    if (!hasDicomPreamble(file)) {
        // A bare data set (no preamble), as GDCM also reads: laid out either
        // way, or not DICOM at all.
        return !walkDataset(w, 0, false) || !walkDataset(w, 0, true);
    }
    std::string syntax;
    std::uint64_t datasetAt = 132;
    std::optional<Element> bad = walk(w, 132, true, true, datasetAt, &syntax);
    if (!bad && syntax == "1.2.840.10008.1.2.1.99") return true; // deflated: GDCM inflates it
    if (!bad && syntax != "1.2.840.10008.1.2.2")                 // big endian: left to GDCM
        bad = walkDataset(w, datasetAt, syntax != "1.2.840.10008.1.2");
    if (!bad) return true;
    const std::uint64_t held = w.left(bad->valueAt);
    if (bad->group == 0x7fe0 && bad->element == 0x0010)
        throw InputError(file + ": its pixel data holds " + std::to_string(held) +
                         " bytes where it declares " + std::to_string(bad->length) +
                         " (cut short, or damaged)");
    throw InputError(file + ": its element " + tagText(*bad) + " declares " +
                     std::to_string(bad->length) + " bytes where the file holds " +
                     std::to_string(held) + " after it (cut short, or damaged)");
}

bool hasDicomPreamble(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    char magic[4] = {};
    return in.seekg(128) && in.read(magic, 4) && std::string_view(magic, 4) == "DICM";
}

} // namespace cutaway::detail
