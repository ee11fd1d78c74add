// --family and --dot-spacing: the registered families in the help, the dot spacing's default by family.
#include "host/cli/protocol_option.h"

#include "host/capture/graycode_patterns.h"
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
                                      "graycode: dot grid spacing s (s x s frames); 0 = Gray code only [default: 8]")
                          ->check(zero_or_range(2, capture::kMaxDotSpacing, "Gray code only"));
  command.parse_complete_callback([protocol, dot_spacing] {
    if (dot_spacing->count() == 0) {
      protocol->dot_spacing = protocol->family == capture::kDefaultFamily ? kGraycodeDotSpacing : 0;
    }
  });
}

}  // namespace rfrecon::cli
