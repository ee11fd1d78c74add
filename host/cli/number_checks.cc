// Finite-number validators shared by the subcommands.
#include "host/cli/number_checks.h"

#include <cmath>
#include <sstream>
#include <string>

namespace rfrecon::cli {

namespace {
// 0.01, 1000, 1e-04: as a person writes the number.
std::string shortest(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

template <typename Accept>
CLI::Validator number_check(std::string description, Accept accept) {
  return CLI::Validator(
      [description, accept](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value) || !accept(value)) {
          return "expected " + description + ", got '" + text + "'";
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

CLI::Validator finite_range(double low, double high) {
  return number_check("a finite number from " + shortest(low) + " to " + shortest(high),
                      [low, high](double v) { return v >= low && v <= high; });
}

CLI::Validator zero_or_range(int low, int high, const std::string& zero_means) {
  return number_check(
      "0 (" + zero_means + ") or an integer from " + std::to_string(low) + " to " + std::to_string(high),
      [low, high](double v) { return v == 0.0 || (v == std::floor(v) && v >= low && v <= high); });
}

}  // namespace rfrecon::cli
