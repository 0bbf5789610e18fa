#pragma once
// A small validating reader for JSON documents (scenes and whatever later
// sections need): it walks an object with its JSON pointer, reads typed values
// with defaults and ranges, remembers which keys it was asked about so that
// every other key can be reported as unknown (with a "did you mean" hint), and
// collects every problem instead of stopping at the first.
//
// Messages have the form "SOURCE: /json/pointer: expected <what>, got <value>"
// with the value as JSON, abbreviated to about 40 characters.
//
//   Diagnostics diagnostics("scene.json");
//   JsonReader root(document, diagnostics);
//   int version = int(root.integer("version", 1, 1, 1));
//   root.object("render", [&](JsonReader& render) {
//       settings.sliceSpacing = render.number("slice_spacing", 1.0, 0.05, 16.0);
//   });
//   root.finish();            // reports keys nobody asked about
//   diagnostics.throwIfAny(); // one InputError, one line per problem
#include <cstddef>
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace cutaway {

/// Collects problems found in one document; each is "SOURCE: POINTER: MESSAGE".
class Diagnostics {
public:
    explicit Diagnostics(std::string source) : m_source(std::move(source)) {}

    void error(std::string_view pointer, std::string_view message);
    bool empty() const { return m_messages.empty(); }
    const std::vector<std::string>& messages() const { return m_messages; }
    const std::string& source() const { return m_source; }
    /// Throws one InputError with every message, one per line, if there are any.
    void throwIfAny() const;

private:
    std::string m_source;
    std::vector<std::string> m_messages;
};

/// An interval of accepted numbers; every bound may be open or closed. Numbers
/// are always required to be finite.
struct Range {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool minOpen = false;
    bool maxOpen = false;

    static Range any() { return {}; }
    static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
    static Range open(double lo, double hi) { return {lo, hi, true, true}; }
    static Range openClosed(double lo, double hi) { return {lo, hi, true, false}; }
    static Range atLeast(double lo) { return {lo, std::numeric_limits<double>::infinity()}; }

    bool contains(double value) const;
    /// "" (any finite), " in [0, 1]", " in (0, 170)", " >= 0", " > 0", ...
    std::string describe() const;
};

/// A closed interval of accepted integers.
struct IntegerRange {
    std::int64_t min = std::numeric_limits<std::int64_t>::min();
    std::int64_t max = std::numeric_limits<std::int64_t>::max();
};

/// Shortest text that reads back as the same double ("0.05", "10000", "1e+30").
std::string formatNumber(double value);
/// A JSON value as text, cut to about `maxChars` characters ("..." marks a cut);
/// its cost does not grow with the value's size or depth.
std::string describeValue(const nlohmann::json& value, std::size_t maxChars = 40);
/// `text` cut to about `maxChars` characters ("..." marks a cut, never inside
/// a UTF-8 sequence): for a pointer or an argument quoted in a message.
std::string abbreviate(std::string_view text, std::size_t maxChars = 40);
/// A JSON pointer with each token longer than about 40 characters cut (an
/// unknown key of a megabyte), as messages show pointers.
std::string abbreviatePointer(std::string_view pointer);
/// Edit distance: insertions, deletions, substitutions and swaps of two
/// neighbouring characters, one edit each (optimal string alignment).
std::size_t editDistance(std::string_view a, std::string_view b);
/// The candidate closest to `word` if it is close enough to be a likely typo.
std::optional<std::string> closestMatch(std::string_view word,
                                        const std::vector<std::string>& candidates);
/// Escapes a key for use as one JSON pointer token ("~" -> "~0", "/" -> "~1").
std::string escapePointerToken(std::string_view key);

/// Parses JSON text. Syntax errors throw InputError "SOURCE:LINE:COLUMN: JSON
/// syntax error: ...". Text past the bounds of io/json_limits.hpp (larger
/// than kMaxSceneBytes, nested deeper than kMaxJsonDepth arrays/objects, a
/// string longer than kMaxSceneStringBytes) is refused before parsing.
nlohmann::json parseJsonText(std::string_view text, const std::string& source);

/// Reads one JSON object. Getters mark their key as known; `finish()` reports
/// every present key that no getter asked about. A value that is not an object
/// is reported at construction and then reads as an empty object (defaults).
/// The reader keeps references to the json value and the diagnostics.
class JsonReader {
public:
    /// The document root; its pointer is "" and messages call it "(root)".
    JsonReader(const nlohmann::json& value, Diagnostics& diagnostics);
    JsonReader(const nlohmann::json& value, std::string pointer, Diagnostics& diagnostics);

    const std::string& pointer() const { return m_pointer; }
    /// The pointer of a key of this object ("/render" + "size" -> "/render/size").
    std::string pointerOf(std::string_view key) const;
    Diagnostics& diagnostics() { return m_diagnostics; }

    /// Marks `key` as known; whether it is present.
    bool has(std::string_view key);
    /// Marks `key` as known; the value, or nullptr if absent.
    const nlohmann::json* find(std::string_view key);

    /// Records "POINTER-OF-KEY: MESSAGE" / "POINTER: MESSAGE" / "...: expected WHAT, got VALUE".
    void error(std::string_view key, std::string_view message);
    void errorHere(std::string_view message);
    void expected(std::string_view pointer, std::string_view what, const nlohmann::json& got);

    // Typed getters. The optional forms return nullopt when the key is absent
    // (an error too if `required`) or its value is invalid (reported); the forms
    // with a default return the default then.
    std::optional<double> number(std::string_view key, Range range, bool required = false);
    double number(std::string_view key, double fallback, Range range);
    double number(std::string_view key, double fallback, double min, double max);

    std::optional<std::int64_t> integer(std::string_view key, IntegerRange range,
                                        bool required = false);
    std::int64_t integer(std::string_view key, std::int64_t fallback, std::int64_t min,
                         std::int64_t max);

    bool boolean(std::string_view key, bool fallback);

    /// A string; with `allowed` non-empty, one of them (the message suggests
    /// the closest). Empty strings are rejected when `allowEmpty` is false.
    std::optional<std::string> string(std::string_view key,
                                      std::initializer_list<std::string_view> allowed = {},
                                      bool required = false, bool allowEmpty = false);
    std::string string(std::string_view key, std::string fallback,
                       std::initializer_list<std::string_view> allowed = {});

    /// An array of exactly 3 numbers, each in `range`.
    std::optional<glm::dvec3> vec3(std::string_view key, Range range = Range::any(),
                                   bool required = false);
    glm::dvec3 vec3(std::string_view key, glm::dvec3 fallback, Range range = Range::any());
    /// Linear RGB: 3 numbers in [0, 1].
    std::optional<glm::vec3> colour(std::string_view key, bool required = false);
    glm::vec3 colour(std::string_view key, glm::vec3 fallback);

    /// An array of `minCount` to `maxCount` numbers, each in `range`.
    std::optional<std::vector<double>> numbers(std::string_view key, std::size_t minCount,
                                               std::size_t maxCount, Range range = Range::any(),
                                               bool required = false);
    /// An array of `minCount` to `maxCount` integers, each in [min, max].
    std::optional<std::vector<std::int64_t>> integers(std::string_view key, std::size_t minCount,
                                                      std::size_t maxCount, std::int64_t min,
                                                      std::int64_t max, bool required = false);

    /// Reads the object at `key` with `body`, then reports its unknown keys.
    /// Absent: `body` is not called (an error if `required`). Returns whether
    /// `body` ran.
    bool object(std::string_view key, const std::function<void(JsonReader&)>& body,
                bool required = false);
    /// Reads an array of `minCount` to `maxCount` objects, each with `body`
    /// (index = position in the array), then reports each one's unknown keys.
    /// Returns whether the array was present and well-formed.
    bool objects(std::string_view key, std::size_t minCount, std::size_t maxCount,
                 const std::function<void(JsonReader&, std::size_t)>& body, bool required = false);

    /// A section reserved for a later version: known, but reported if present.
    void reserved(std::string_view key);

    /// Reports every present key no getter asked about, suggesting the closest
    /// known key. Called by object()/objects() for nested readers; call it for
    /// the root. Idempotent.
    void finish();

    // Checks of a value already found (array elements, hand-parsed keys), at
    // `pointer`; each reports a problem and returns nullopt.
    std::optional<double> asNumber(const nlohmann::json& value, const std::string& pointer,
                                   Range range);
    std::optional<std::int64_t> asInteger(const nlohmann::json& value, const std::string& pointer,
                                          std::int64_t min, std::int64_t max);
    std::optional<std::vector<double>> asNumbers(const nlohmann::json& value,
                                                 const std::string& pointer, std::size_t minCount,
                                                 std::size_t maxCount, Range range);

private:
    void missing(std::string_view key, std::string_view what);

    const nlohmann::json& m_value;
    std::string m_pointer;
    Diagnostics& m_diagnostics;
    bool m_isObject = false;
    bool m_finished = false;
    std::vector<std::string> m_known;
};

} // namespace cutaway
