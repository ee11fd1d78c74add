// Validators for numeric options: CLI11's PositiveNumber lets "nan" through, these do not.
#pragma once

#include <CLI/CLI.hpp>

namespace rfrecon::cli {

// A finite number > 0.
const CLI::Validator& finite_positive();

// A finite number >= 0.
const CLI::Validator& finite_non_negative();

}  // namespace rfrecon::cli
