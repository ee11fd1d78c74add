// The registry of pattern families, with the built-in one, and the entry readers families share.
#include "host/capture/pattern_family.h"

#include <utility>

#include <nlohmann/json.hpp>

#include "host/capture/graycode_patterns.h"
#include "host/core/json_file.h"
#include "host/core/named_registry.h"

namespace rfrecon::capture {

namespace {

NamedRegistry<PatternFamily>& registry() {
  static NamedRegistry<PatternFamily> instance("pattern family", {graycode_family()});
  return instance;
}

template <typename T>
T entry_field(const nlohmann::json& entry, const std::string& key, const std::string& where) {
  if (!entry.contains(key)) throw InputError(where + ": missing field '" + key + "'");
  std::string problem;
  auto value = json_as<T>(entry.at(key), problem);
  if (!value) throw InputError(where + ": field '" + key + "' has the wrong type: must be " + problem);
  return std::move(*value);
}

}  // namespace

const PatternFamily& pattern_family(const std::string& name) { return registry().find(name); }

std::vector<std::string> pattern_family_names() { return registry().names(); }

void register_pattern_family(std::shared_ptr<const PatternFamily> family) { registry().add(std::move(family)); }

int entry_int(const nlohmann::json& entry, const std::string& key, const std::string& where) {
  return entry_field<int>(entry, key, where);
}

bool entry_bool(const nlohmann::json& entry, const std::string& key, const std::string& where) {
  return entry_field<bool>(entry, key, where);
}

std::vector<int> entry_ints(const nlohmann::json& entry, const std::string& key, const std::string& where) {
  return entry_field<std::vector<int>>(entry, key, where);
}

}  // namespace rfrecon::capture
