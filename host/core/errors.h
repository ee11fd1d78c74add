// Error categories that the command line maps to documented exit codes (docs/cli.md).
#pragma once

#include <stdexcept>

namespace rfrecon {

// Bad input: a missing, unreadable, malformed or mis-sized file or value. The message names the file or field.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A command line that asks for something no input could make right: an output that is a device, a directory where
// a file is meant, one of the command's own inputs, or an existing file without --force.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output that could not be written (permission, read-only file system, disk full). Nothing is left under the
// output's name; the message names it and the cause.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A camera or display that is missing, refuses a setting, stops answering or shows it did not capture what was
// shown (a dropped frame that a retry did not fix). The message names the device and what to check.
class HardwareError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Valid input that the method cannot process: no checkerboard found, too few poses, everything masked.
class ProcessingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rfrecon
