// Error categories that the command line maps to documented exit codes (docs/cli.md).
#pragma once

#include <stdexcept>

namespace rfrecon {

// Bad input: a missing, unreadable, malformed or mis-sized file or value. The message names the file or field.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Valid input that the method cannot process: no checkerboard found, too few poses, everything masked.
class ProcessingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rfrecon
