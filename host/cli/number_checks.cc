// Finite-number validators shared by the subcommands.
#include "host/cli/number_checks.h"

#include <cmath>
#include <string>

namespace rfrecon::cli {

namespace {
CLI::Validator number_check(const char* description, bool (*accept)(double)) {
  return CLI::Validator(
      [description, accept](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value) || !accept(value)) {
          return "expected " + std::string(description) + ", got '" + text + "'";
        }
        return {};
      },
      description);
}
}  // namespace

const CLI::Validator& finite_positive() {
  static const CLI::Validator validator = number_check("a finite number > 0", [](double v) { return v > 0.0; });
  return validator;
}

const CLI::Validator& finite_non_negative() {
  static const CLI::Validator validator = number_check("a finite number >= 0", [](double v) { return v >= 0.0; });
  return validator;
}

}  // namespace rfrecon::cli
