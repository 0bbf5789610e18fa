// Tokenising a NRRD header: lines, fields, type names and vectors. The
// interpretation (sizes, spacing, where the data is) is in nrrd.cpp.
#include "volume/nrrd_header.hpp"

#include "core/error.hpp"
#include "core/quote_text.hpp"
#include "volume/io_util.hpp"

#include <cctype>

namespace cutaway::detail {

namespace {

/// A header longer than this is not a header (a binary file without the blank line).
constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;

} // namespace

std::vector<std::string_view> splitWords(std::string_view text) {
    std::vector<std::string_view> words;
    text = trim(text);
    while (!text.empty()) {
        std::size_t end = 0;
        while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end])))
            ++end;
        words.push_back(text.substr(0, end));
        text = trim(text.substr(end));
    }
    return words;
}

/// Reads one line (without "\n" or "\r\n"); false at the end of the stream.
bool readNrrdLine(std::istream& in, std::string& line, std::size_t& budget,
                  const std::string& ctx) {
    line.clear();
    std::streambuf* buffer = in.rdbuf();
    bool any = false;
    for (;;) {
        const int c = buffer->sbumpc();
        if (c == std::char_traits<char>::eof()) break;
        any = true;
        if (budget-- == 0) {
            throw InputError(ctx + ": header longer than 1 MiB (is the blank line that ends it "
                                   "missing?)");
        }
        if (c == '\n') break;
        line.push_back(static_cast<char>(c));
    }
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return any;
}

VoxelType parseNrrdType(std::string_view text, const std::string& ctx) {
    // Collapse whitespace so "unsigned   short" is "unsigned short".
    std::string name;
    for (std::string_view word : splitWords(text)) {
        if (!name.empty()) name += ' ';
        name += toLower(word);
    }
    struct Spelling {
        const char* name;
        VoxelType type;
    };
    static constexpr Spelling kSpellings[] = {
        {"signed char", VoxelType::I8},
        {"int8", VoxelType::I8},
        {"int8_t", VoxelType::I8},
        {"uchar", VoxelType::U8},
        {"unsigned char", VoxelType::U8},
        {"uint8", VoxelType::U8},
        {"uint8_t", VoxelType::U8},
        {"short", VoxelType::I16},
        {"short int", VoxelType::I16},
        {"signed short", VoxelType::I16},
        {"signed short int", VoxelType::I16},
        {"int16", VoxelType::I16},
        {"int16_t", VoxelType::I16},
        {"ushort", VoxelType::U16},
        {"unsigned short", VoxelType::U16},
        {"unsigned short int", VoxelType::U16},
        {"uint16", VoxelType::U16},
        {"uint16_t", VoxelType::U16},
        {"int", VoxelType::I32},
        {"signed int", VoxelType::I32},
        {"int32", VoxelType::I32},
        {"int32_t", VoxelType::I32},
        {"uint", VoxelType::U32},
        {"unsigned int", VoxelType::U32},
        {"uint32", VoxelType::U32},
        {"uint32_t", VoxelType::U32},
        {"float", VoxelType::F32},
        {"double", VoxelType::F64},
    };
    for (const Spelling& s : kSpellings) {
        if (name == s.name) return s.type;
    }
    static constexpr const char* kKnownUnsupported[] = {
        "longlong", "long long", "long long int", "signed long long",   "signed long long int",
        "int64",    "int64_t",   "ulonglong",     "unsigned long long", "unsigned long long int",
        "uint64",   "uint64_t",  "block"};
    for (const char* s : kKnownUnsupported) {
        if (name == s) {
            throw InputError(ctx + ": unsupported type '" + name +
                             "' (cutaway reads 8, 16 and 32-bit integers, float and double)");
        }
    }
    throw InputError(ctx + ": unknown type " + quoteText(text));
}

/// Parses "(a,b,c)" vectors and "none" entries of `space directions` / `space origin`.
std::vector<std::optional<std::vector<double>>>
parseNrrdVectors(std::string_view text, const char* field, const std::string& ctx) {
    std::vector<std::optional<std::vector<double>>> out;
    const auto bad = [&]() {
        return InputError(ctx + ": malformed '" + field + "': '" + std::string(trim(text)) +
                          "' (expected vectors like (1,0,0) or none)");
    };
    std::string_view rest = trim(text);
    while (!rest.empty()) {
        if (rest.size() >= 4 && toLower(rest.substr(0, 4)) == "none") {
            out.emplace_back(std::nullopt);
            rest = trim(rest.substr(4));
            continue;
        }
        if (rest.front() != '(') throw bad();
        const std::size_t close = rest.find(')');
        if (close == std::string_view::npos) throw bad();
        std::vector<double> vec;
        std::string_view inner = rest.substr(1, close - 1);
        while (true) {
            const std::size_t comma = inner.find(',');
            double value = 0.0;
            if (!parseDouble(trim(inner.substr(0, comma)), value)) throw bad();
            vec.push_back(value);
            if (comma == std::string_view::npos) break;
            inner.remove_prefix(comma + 1);
        }
        out.emplace_back(std::move(vec));
        rest = trim(rest.substr(close + 1));
    }
    return out;
}

NrrdFields readNrrdHeader(std::istream& in, const std::string& ctx, bool& endedByBlankLine) {
    std::size_t budget = kMaxHeaderBytes;
    std::string line;
    if (!readNrrdLine(in, line, budget, ctx))
        throw InputError(ctx + ": empty file, not a NRRD file");
    const std::string_view magic = trim(line);
    if (magic.size() != 8 || magic.substr(0, 7) != "NRRD000" || magic[7] < '1' || magic[7] > '5') {
        throw InputError(ctx + ": not a NRRD file (expected the magic NRRD0001..NRRD0005, found " +
                         quoteText(magic, 16) + ")");
    }
    NrrdFields f;
    endedByBlankLine = false;
    int lineNumber = 1;
    while (readNrrdLine(in, line, budget, ctx)) {
        ++lineNumber;
        if (trim(line).empty()) {
            endedByBlankLine = true;
            break;
        }
        if (line.front() == '#') continue;
        const std::size_t colon = line.find(':');
        if (colon == std::string::npos) {
            throw InputError(ctx + ": line " + std::to_string(lineNumber) +
                             ": expected 'field: value', found " + quoteText(line));
        }
        if (colon + 1 < line.size() && line[colon + 1] == '=') {
            // key:=value pairs are free-form; cutaway's writer keeps a NIfTI-style
            // value scaling in two of them so it survives a round trip.
            const std::string key(trim(std::string_view(line).substr(0, colon)));
            const std::string value(trim(std::string_view(line).substr(colon + 2)));
            if (key == "cutaway_slope") f.slope = value;
            if (key == "cutaway_inter") f.inter = value;
            continue;
        }
        const std::string name = toLower(trim(std::string_view(line).substr(0, colon)));
        std::string value(trim(std::string_view(line).substr(colon + 1)));
        if (name == "type")
            f.type = value;
        else if (name == "dimension")
            f.dimension = value;
        else if (name == "sizes")
            f.sizes = value;
        else if (name == "endian")
            f.endian = value;
        else if (name == "encoding")
            f.encoding = value;
        else if (name == "spacings")
            f.spacings = value;
        else if (name == "space")
            f.space = value;
        else if (name == "space dimension")
            f.spaceDimension = value;
        else if (name == "space directions")
            f.directions = value;
        else if (name == "space origin")
            f.origin = value;
        else if (name == "data file" || name == "datafile") {
            f.dataFile = value;
            // "LIST": the rest of the header names the data files, one per line.
            if (value.rfind("LIST", 0) == 0) break;
        } else if (name == "byte skip" || name == "byteskip")
            f.byteSkip = value;
        else if (name == "line skip" || name == "lineskip")
            f.lineSkip = value;
        // content, kinds, centerings, labels, units, space units, ...: descriptive only.
    }
    return f;
}

} // namespace cutaway::detail
