// Test helper: runs the built `rfrecon` tool with arguments and returns its exit code and output.
#pragma once

#include <array>
#include <cstdio>
#include <string>

#include <sys/wait.h>

namespace rfrecon::testing {

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs `program` (a path) with `arguments` through the shell (quote paths with spaces). `prefix`: a command the
// program runs under, e.g. "timeout 60".
inline CliResult run_program(const std::string& program, const std::string& arguments, const std::string& prefix = {}) {
  CliResult result;
  const std::string command = prefix + (prefix.empty() ? "" : " ") + program + " " + arguments + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) result.output += buffer.data();
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// The built `rfrecon` tool; RFRECON_CLI_PATH is defined by rfrecon_add_test.
inline CliResult run_cli(const std::string& arguments, const std::string& prefix = {}) {
  return run_program(RFRECON_CLI_PATH, arguments, prefix);
}

}  // namespace rfrecon::testing
