// JSON files read with rfrecon's error rules: a missing or malformed file is an InputError naming it.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace rfrecon {

// Parses `file`. Throws InputError "cannot read FILE" when it cannot be opened and "FILE: not valid JSON (...)".
nlohmann::json read_json_file(const std::filesystem::path& file);

}  // namespace rfrecon
