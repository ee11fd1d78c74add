// Reading and parsing one JSON file.
#include "host/core/json_file.h"

#include <fstream>

#include "host/core/errors.h"

namespace rfrecon {

nlohmann::json read_json_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError("cannot read " + file.string());
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& error) {
    throw InputError(file.string() + ": not valid JSON (" + error.what() + ")");
  }
}

}  // namespace rfrecon
