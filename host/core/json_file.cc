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
  } catch (const nlohmann::json::exception& error) {  // parse_error, out_of_range (a number like 1e999)
    throw InputError(file.string() + ": not valid JSON (" + error.what() + ")");
  }
}

}  // namespace rfrecon
