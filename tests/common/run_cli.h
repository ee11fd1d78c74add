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

// `arguments` go through the shell (quote paths with spaces). RFRECON_CLI_PATH is defined by rfrecon_add_test.
// `prefix`: a command the tool runs under, e.g. "timeout 60".
inline CliResult run_cli(const std::string& arguments, const std::string& prefix = {}) {
  CliResult result;
  const std::string command = prefix + (prefix.empty() ? "" : " ") + RFRECON_CLI_PATH + " " + arguments + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) result.output += buffer.data();
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace rfrecon::testing
