// Reading and parsing one JSON file, bounded in size and nesting.
#include "host/core/json_file.h"

#include "host/core/errors.h"
#include "host/core/limits.h"
#include "host/core/message_text.h"

namespace rfrecon {

namespace {
// Thrown by the parser callback to stop at the first container past the limit.
struct TooDeep {};

// nlohmann's message with the input it quotes ("last read: '...'", "number overflow parsing '...'") cut by excerpt().
std::string bounded_parse_error(const std::string& what) {
  for (const std::string marker : {"last read: '", "parsing '"}) {
    const std::size_t start = what.find(marker);
    if (start == std::string::npos) continue;
    const std::size_t token_start = start + marker.size();
    const std::size_t expected = what.find("'; expected ", token_start);
    const std::size_t token_end = expected != std::string::npos ? expected : what.rfind('\'');
    if (token_end == std::string::npos || token_end < token_start) return excerpt(what, 4 * kMaxQuotedChars);
    return what.substr(0, token_start) + excerpt(what.substr(token_start, token_end - token_start)) +
           what.substr(token_end);
  }
  return excerpt(what, 4 * kMaxQuotedChars);
}
}  // namespace

std::optional<nlohmann::json> parse_json_text(std::string_view text, std::string& problem) {
  // `depth` counts the containers around the event's: a new one at depth kMaxNestingDepth would be one too many.
  const nlohmann::json::parser_callback_t limit_depth = [](int depth, nlohmann::json::parse_event_t event,
                                                           nlohmann::json&) {
    const bool opens =
        event == nlohmann::json::parse_event_t::object_start || event == nlohmann::json::parse_event_t::array_start;
    if (opens && depth >= kMaxNestingDepth) throw TooDeep{};
    return true;
  };
  try {
    return nlohmann::json::parse(text, limit_depth);
  } catch (const TooDeep&) {
    problem = "arrays and objects nested deeper than " + std::to_string(kMaxNestingDepth) +
              " levels, the limit (docs/formats.md#limits)";
  } catch (const nlohmann::json::exception& error) {  // parse_error, out_of_range (a number like 1e999)
    problem = "not valid JSON (" + bounded_parse_error(error.what()) + ")";
  }
  return std::nullopt;
}

nlohmann::json read_json_file(const std::filesystem::path& file) {
  const std::string text = read_input_file(file, kMaxJsonBytes, "a JSON file");
  std::string problem;
  auto value = parse_json_text(text, problem);
  if (!value) throw InputError(file.string() + ": " + problem);
  return std::move(*value);
}

}  // namespace rfrecon
