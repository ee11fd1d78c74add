// --family and --dot-spacing: the registered families in the help, the dot spacing's default by family.
#include "host/cli/protocol_option.h"

#include <algorithm>
#include <set>

#include "host/capture/dot_grid.h"
#include "host/capture/pattern_family.h"
#include "host/cli/number_checks.h"

namespace rfrecon::cli {

void add_protocol_options(CLI::App& command, const std::shared_ptr<capture::ProtocolOptions>& protocol) {
  constexpr int kGraycodeDotSpacing = 8;
  std::string families;
  for (const auto& name : capture::pattern_family_names()) {
    families += "\n  " + name + ": " + capture::pattern_family(name).help();
  }
  command.add_option("--family", protocol->family, "Pattern family:" + families)
      ->check(CLI::IsMember(capture::pattern_family_names()))
      ->capture_default_str();
  auto* dot_spacing = command
                          .add_option("--dot-spacing", protocol->dot_spacing,
                                      "Dot grid spacing s (s x s frames after the family's patterns); 0 = no dot grid "
                                      "[default: 8 for graycode, 0 for the others]")
                          ->check(zero_or_range(2, capture::kMaxDotSpacing, "no dot grid"));
  auto parameters = std::make_shared<std::map<std::string, int>>();
  add_family_parameter_options(command, parameters);
  command.parse_complete_callback([protocol, dot_spacing, parameters] {
    if (dot_spacing->count() == 0) {
      protocol->dot_spacing = protocol->family == capture::kDefaultFamily ? kGraycodeDotSpacing : 0;
    }
    protocol->parameters = *parameters;
  });
}

void add_family_parameter_options(CLI::App& command, const std::shared_ptr<std::map<std::string, int>>& parameters) {
  std::set<std::string> added;
  for (const auto& family : capture::pattern_family_names()) {
    for (const auto& parameter : capture::pattern_family(family).parameters()) {
      if (!added.insert(parameter.name).second) continue;
      std::string flag = "--" + parameter.name;
      std::replace(flag.begin(), flag.end(), '_', '-');
      command
          .add_option_function<int>(
              flag, [parameters, name = parameter.name](const int& value) { (*parameters)[name] = value; },
              parameter.help + " [default: " + std::to_string(parameter.default_value) + "]")
          ->check(parameter.zero_means.empty() ? CLI::Validator(CLI::Range(parameter.min, parameter.max))
                                               : zero_or_range(parameter.min, parameter.max, parameter.zero_means));
    }
  }
}

}  // namespace rfrecon::cli
