// The registry of pattern families, with the built-in one, and the entry readers families share.
#include "host/capture/pattern_family.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "host/capture/graycode_patterns.h"
#include "host/capture/phase_patterns.h"
#include "host/core/json_file.h"
#include "host/core/message_text.h"
#include "host/core/named_registry.h"

namespace rfrecon::capture {

namespace {

NamedRegistry<PatternFamily>& registry() {
  static NamedRegistry<PatternFamily> instance("pattern family", {graycode_family(), phase_family()});
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

int family_parameter(const PatternFamily& family, const ProtocolOptions& options, const std::string& name) {
  for (const auto& parameter : family.parameters()) {
    if (parameter.name != name) continue;
    const auto given = options.parameters.find(name);
    return given == options.parameters.end() ? parameter.default_value : given->second;
  }
  throw std::invalid_argument("family_parameter: " + family.name() + " has no parameter " + name);
}

void check_family_parameters(const PatternFamily& family, const std::map<std::string, int>& parameters,
                             const std::string& where) {
  const auto declared = family.parameters();
  for (const auto& given : parameters) {
    const std::string& name = given.first;
    const auto it = std::find_if(declared.begin(), declared.end(), [&](const auto& p) { return p.name == name; });
    std::string problem = where;
    if (it == declared.end()) {
      problem += ": parameter '" + excerpt(name) + "' is not one of the ";
      problem += family.name() + " family's";
      throw InputError(problem);
    }
    const bool zero = given.second == 0 && !it->zero_means.empty();
    if (!zero && (given.second < it->min || given.second > it->max)) {
      problem += ": parameter " + name;
      problem += " = " + std::to_string(given.second);
      problem += " is outside " + std::to_string(it->min);
      problem += " to " + std::to_string(it->max);
      if (!it->zero_means.empty()) problem += " (or 0: " + it->zero_means + ")";
      throw InputError(problem);
    }
  }
}

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
