// JSON files read with rfrecon's error rules: a missing or malformed file is an InputError naming it, and a value
// of the wrong type or out of range never reaches a conversion whose result is undefined.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

namespace rfrecon {

// `text` parsed, or std::nullopt with `problem` set: "not valid JSON (...)" (bad syntax, or a number outside the
// range of a double) or "arrays and objects nested deeper than kMaxNestingDepth levels ...". The depth is checked as
// the parser goes, before the tree that code walks recursively (copies, comparisons, dump) exists.
std::optional<nlohmann::json> parse_json_text(std::string_view text, std::string& problem);

// Parses `file`, a regular file (check_input_file: a FIFO is refused without being opened) of at most kMaxJsonBytes.
// Throws InputError naming the file for each of these and for the problems of parse_json_text.
nlohmann::json read_json_file(const std::filesystem::path& file);

namespace detail {
template <typename T>
struct is_vector : std::false_type {};
template <typename U>
struct is_vector<std::vector<U>> : std::true_type {};

// Whether `value` is an integer token that T holds.
template <typename T>
bool fits_integer(const nlohmann::json& value) {
  if (value.is_number_unsigned()) {
    return value.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<T>::max());
  }
  if (!value.is_number_integer()) return false;
  const std::int64_t v = value.get<std::int64_t>();
  if constexpr (std::is_signed_v<T>) {
    return v >= static_cast<std::int64_t>(std::numeric_limits<T>::min()) &&
           v <= static_cast<std::int64_t>(std::numeric_limits<T>::max());
  } else {
    return v >= 0 && static_cast<std::uint64_t>(v) <= static_cast<std::uint64_t>(std::numeric_limits<T>::max());
  }
}
}  // namespace detail

// `value` as T, or std::nullopt with `problem` set to what was expected. Integers (and vectors of integers) must be
// integer tokens within T's range: nlohmann's own conversion of 1e10 to int is undefined behaviour.
template <typename T>
std::optional<T> json_as(const nlohmann::json& value, std::string& problem) {
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    if (!detail::fits_integer<T>(value)) {
      problem = "an integer from " + std::to_string(std::numeric_limits<T>::min()) + " to " +
                std::to_string(std::numeric_limits<T>::max());
      return std::nullopt;
    }
  } else if constexpr (detail::is_vector<T>::value) {
    using Element = typename T::value_type;
    if (!value.is_array()) {
      problem = "an array";
      return std::nullopt;
    }
    T out;
    for (const auto& item : value) {
      auto element = json_as<Element>(item, problem);
      if (!element) {
        problem.insert(0, "an array of ");
        problem += "s";
        return std::nullopt;
      }
      out.push_back(std::move(*element));
    }
    return out;
  }
  try {
    return value.get<T>();
  } catch (const nlohmann::json::exception&) {
    problem = std::string("of another type (got ") + value.type_name() + ")";
    return std::nullopt;
  }
}

}  // namespace rfrecon
