// JsonReader: typed, range-checked reads from a JSON object (json_reader.hpp).
#include "scene/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace cutaway {

namespace {

const nlohmann::json& emptyObject() {
    static const nlohmann::json empty = nlohmann::json::object();
    return empty;
}

std::string describeIntegers(std::int64_t min, std::int64_t max) {
    const bool hasMin = min != std::numeric_limits<std::int64_t>::min();
    const bool hasMax = max != std::numeric_limits<std::int64_t>::max();
    if (hasMin && hasMax) return " in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
    if (hasMin) return " >= " + std::to_string(min);
    if (hasMax) return " <= " + std::to_string(max);
    return "";
}

/// "3", "2 to 4", "at least 2", "at most 4" (maxCount SIZE_MAX = no limit).
std::string describeCount(std::size_t minCount, std::size_t maxCount) {
    constexpr std::size_t kUnlimited = std::numeric_limits<std::size_t>::max();
    if (minCount == maxCount) return std::to_string(minCount);
    if (maxCount == kUnlimited) return "at least " + std::to_string(minCount);
    if (minCount == 0) return "at most " + std::to_string(maxCount);
    return std::to_string(minCount) + " to " + std::to_string(maxCount);
}

std::string describeChoices(std::initializer_list<std::string_view> allowed) {
    std::string text = "one of";
    for (const std::string_view choice : allowed) {
        text += (text.size() == 6 ? " \"" : ", \"");
        text += choice;
        text += '"';
    }
    return text;
}

std::string withIndex(const std::string& pointer, std::size_t index) {
    return pointer + "/" + std::to_string(index);
}

} // namespace

JsonReader::JsonReader(const nlohmann::json& value, Diagnostics& diagnostics)
    : JsonReader(value, std::string(), diagnostics) {}

JsonReader::JsonReader(const nlohmann::json& value, std::string pointer, Diagnostics& diagnostics)
    : m_value(value.is_object() ? value : emptyObject()), m_pointer(std::move(pointer)),
      m_diagnostics(diagnostics), m_isObject(value.is_object()) {
    if (!m_isObject) expected(m_pointer, "an object", value);
}

std::string JsonReader::pointerOf(std::string_view key) const {
    return m_pointer + "/" + escapePointerToken(key);
}

bool JsonReader::has(std::string_view key) {
    return find(key) != nullptr;
}

const nlohmann::json* JsonReader::find(std::string_view key) {
    if (std::find(m_known.begin(), m_known.end(), key) == m_known.end()) m_known.emplace_back(key);
    const auto it = m_value.find(key);
    return it == m_value.end() ? nullptr : &*it;
}

void JsonReader::error(std::string_view key, std::string_view message) {
    m_diagnostics.error(pointerOf(key), message);
}

void JsonReader::errorHere(std::string_view message) {
    m_diagnostics.error(m_pointer, message);
}

void JsonReader::expected(std::string_view pointer, std::string_view what,
                          const nlohmann::json& got) {
    m_diagnostics.error(pointer, "expected " + std::string(what) + ", got " + describeValue(got));
}

void JsonReader::missing(std::string_view key, std::string_view what) {
    error(key, "missing; expected " + std::string(what));
}

// ---- values at a pointer -------------------------------------------------------------------

std::optional<double> JsonReader::asNumber(const nlohmann::json& value, const std::string& pointer,
                                           Range range) {
    if (value.is_number()) {
        const double number = value.get<double>();
        if (range.contains(number)) return number;
    }
    expected(pointer, "a number" + range.describe(), value);
    return std::nullopt;
}

std::optional<std::int64_t> JsonReader::asInteger(const nlohmann::json& value,
                                                  const std::string& pointer, std::int64_t min,
                                                  std::int64_t max) {
    std::optional<std::int64_t> integer;
    if (value.is_number_unsigned()) {
        const auto number = value.get<std::uint64_t>();
        if (number <= static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
            integer = static_cast<std::int64_t>(number);
    } else if (value.is_number_integer()) {
        integer = value.get<std::int64_t>();
    } else if (value.is_number_float()) { // 512.0 is an integer too
        const double number = value.get<double>();
        if (std::isfinite(number) && std::trunc(number) == number && std::abs(number) < 9.0e15)
            integer = static_cast<std::int64_t>(number);
    }
    if (integer && *integer >= min && *integer <= max) return integer;
    expected(pointer, "an integer" + describeIntegers(min, max), value);
    return std::nullopt;
}

std::optional<std::vector<double>> JsonReader::asNumbers(const nlohmann::json& value,
                                                         const std::string& pointer,
                                                         std::size_t minCount, std::size_t maxCount,
                                                         Range range) {
    if (!value.is_array() || value.size() < minCount || value.size() > maxCount) {
        expected(pointer,
                 "an array of " + describeCount(minCount, maxCount) + " numbers" + range.describe(),
                 value);
        return std::nullopt;
    }
    std::vector<double> numbers;
    bool valid = true;
    for (std::size_t i = 0; i < value.size(); ++i) {
        const auto number = asNumber(value[i], withIndex(pointer, i), range);
        valid = valid && number.has_value();
        numbers.push_back(number.value_or(0.0));
    }
    if (!valid) return std::nullopt;
    return numbers;
}

// ---- typed getters -------------------------------------------------------------------------

std::optional<double> JsonReader::number(std::string_view key, Range range, bool required) {
    const nlohmann::json* value = find(key);
    if (value == nullptr) {
        if (required) missing(key, "a number" + range.describe());
        return std::nullopt;
    }
    return asNumber(*value, pointerOf(key), range);
}

double JsonReader::number(std::string_view key, double fallback, Range range) {
    return number(key, range).value_or(fallback);
}

double JsonReader::number(std::string_view key, double fallback, double min, double max) {
    return number(key, Range::closed(min, max)).value_or(fallback);
}

std::optional<std::int64_t> JsonReader::integer(std::string_view key, IntegerRange range,
                                                bool required) {
    const nlohmann::json* value = find(key);
    if (value == nullptr) {
        if (required) missing(key, "an integer" + describeIntegers(range.min, range.max));
        return std::nullopt;
    }
    return asInteger(*value, pointerOf(key), range.min, range.max);
}

std::int64_t JsonReader::integer(std::string_view key, std::int64_t fallback, std::int64_t min,
                                 std::int64_t max) {
    return integer(key, IntegerRange{min, max}).value_or(fallback);
}

bool JsonReader::boolean(std::string_view key, bool fallback) {
    const nlohmann::json* value = find(key);
    if (value == nullptr) return fallback;
    if (value->is_boolean()) return value->get<bool>();
    expected(pointerOf(key), "true or false", *value);
    return fallback;
}

std::optional<std::string> JsonReader::string(std::string_view key,
                                              std::initializer_list<std::string_view> allowed,
                                              bool required, bool allowEmpty) {
    const std::string what = allowed.size() > 0 ? describeChoices(allowed)
                             : allowEmpty       ? std::string("a string")
                                                : std::string("a non-empty string");
    const nlohmann::json* value = find(key);
    if (value == nullptr) {
        if (required) missing(key, what);
        return std::nullopt;
    }
    if (value->is_string()) {
        const auto& text = value->get_ref<const std::string&>();
        if (allowed.size() == 0 && (allowEmpty || !text.empty())) return text;
        if (std::find(allowed.begin(), allowed.end(), text) != allowed.end()) return text;
        if (allowed.size() > 0) {
            const auto suggestion =
                closestMatch(text, std::vector<std::string>(allowed.begin(), allowed.end()));
            if (suggestion) {
                expected(pointerOf(key), what + " (did you mean \"" + *suggestion + "\"?)", *value);
                return std::nullopt;
            }
        }
    }
    expected(pointerOf(key), what, *value);
    return std::nullopt;
}

std::string JsonReader::string(std::string_view key, std::string fallback,
                               std::initializer_list<std::string_view> allowed) {
    auto value = string(key, allowed);
    return value ? std::move(*value) : std::move(fallback);
}

std::optional<glm::dvec3> JsonReader::vec3(std::string_view key, Range range, bool required) {
    const auto values = numbers(key, 3, 3, range, required);
    if (!values) return std::nullopt;
    return glm::dvec3((*values)[0], (*values)[1], (*values)[2]);
}

glm::dvec3 JsonReader::vec3(std::string_view key, glm::dvec3 fallback, Range range) {
    return vec3(key, range).value_or(fallback);
}

std::optional<glm::vec3> JsonReader::colour(std::string_view key, bool required) {
    const nlohmann::json* value = find(key);
    if (value == nullptr) {
        if (required) missing(key, "an RGB colour: 3 numbers in [0, 1]");
        return std::nullopt;
    }
    const auto values = asNumbers(*value, pointerOf(key), 3, 3, Range::closed(0.0, 1.0));
    if (!values) return std::nullopt;
    return glm::vec3(glm::dvec3((*values)[0], (*values)[1], (*values)[2]));
}

glm::vec3 JsonReader::colour(std::string_view key, glm::vec3 fallback) {
    return colour(key).value_or(fallback);
}

std::optional<std::vector<double>> JsonReader::numbers(std::string_view key, std::size_t minCount,
                                                       std::size_t maxCount, Range range,
                                                       bool required) {
    const nlohmann::json* value = find(key);
    if (value == nullptr) {
        if (required) {
            missing(key, "an array of " + describeCount(minCount, maxCount) + " numbers" +
                             range.describe());
        }
        return std::nullopt;
    }
    return asNumbers(*value, pointerOf(key), minCount, maxCount, range);
}

std::optional<std::vector<std::int64_t>>
JsonReader::integers(std::string_view key, std::size_t minCount, std::size_t maxCount,
                     std::int64_t min, std::int64_t max, bool required) {
    const std::string what = "an array of " + describeCount(minCount, maxCount) + " integers" +
                             describeIntegers(min, max);
    const nlohmann::json* value = find(key);
    if (value == nullptr) {
        if (required) missing(key, what);
        return std::nullopt;
    }
    if (!value->is_array() || value->size() < minCount || value->size() > maxCount) {
        expected(pointerOf(key), what, *value);
        return std::nullopt;
    }
    std::vector<std::int64_t> result;
    bool valid = true;
    for (std::size_t i = 0; i < value->size(); ++i) {
        const auto integer = asInteger((*value)[i], withIndex(pointerOf(key), i), min, max);
        valid = valid && integer.has_value();
        result.push_back(integer.value_or(0));
    }
    if (!valid) return std::nullopt;
    return result;
}

// ---- structure -----------------------------------------------------------------------------

bool JsonReader::object(std::string_view key, const std::function<void(JsonReader&)>& body,
                        bool required) {
    const nlohmann::json* value = find(key);
    if (value == nullptr) {
        if (required) missing(key, "an object");
        return false;
    }
    if (!value->is_object()) {
        expected(pointerOf(key), "an object", *value);
        return false;
    }
    JsonReader child(*value, pointerOf(key), m_diagnostics);
    body(child);
    child.finish();
    return true;
}

bool JsonReader::objects(std::string_view key, std::size_t minCount, std::size_t maxCount,
                         const std::function<void(JsonReader&, std::size_t)>& body, bool required) {
    const std::string what = "an array of " + describeCount(minCount, maxCount) + " objects";
    const nlohmann::json* value = find(key);
    if (value == nullptr) {
        if (required) missing(key, what);
        return false;
    }
    if (!value->is_array() || value->size() < minCount || value->size() > maxCount) {
        expected(pointerOf(key), what, *value);
        return false;
    }
    for (std::size_t i = 0; i < value->size(); ++i) {
        const std::string pointer = withIndex(pointerOf(key), i);
        if (!(*value)[i].is_object()) {
            expected(pointer, "an object", (*value)[i]);
            continue;
        }
        JsonReader child((*value)[i], pointer, m_diagnostics);
        body(child, i);
        child.finish();
    }
    return true;
}

void JsonReader::reserved(std::string_view key) {
    if (has(key)) error(key, "not supported yet by this version of cutaway");
}

void JsonReader::finish() {
    if (m_finished) return;
    m_finished = true;
    for (const auto& [key, value] : m_value.items()) {
        if (std::find(m_known.begin(), m_known.end(), key) != m_known.end()) continue;
        std::string message = "unknown key";
        if (const auto suggestion = closestMatch(key, m_known))
            message += " (did you mean \"" + *suggestion + "\"?)";
        error(key, message);
    }
}

} // namespace cutaway
