// Validators for numeric options: CLI11's PositiveNumber lets "nan" through, these do not.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace rfrecon::cli {

// A finite number > 0.
const CLI::Validator& finite_positive();

// A finite number >= 0.
const CLI::Validator& finite_non_negative();

// A finite number from `low` to `high`: the documented range of an option whose ends both run (docs/cli.md).
CLI::Validator finite_range(double low, double high);

// 0 (what `zero_means`) or an integer from `low` to `high`.
CLI::Validator zero_or_range(int low, int high, const std::string& zero_means);

}  // namespace rfrecon::cli
