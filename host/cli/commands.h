// Each subcommand of the `rfrecon` tool registers itself on the application through one of these functions.
#pragma once

#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

namespace rfrecon::cl {
class EntryChoice;
}  // namespace rfrecon::cl

namespace rfrecon::cli {

// Thrown by a command to end with a specific exit code after it has reported what went wrong.
class CommandFailed : public std::runtime_error {
 public:
  CommandFailed(int exit_code, const std::string& message) : std::runtime_error(message), exit_code_(exit_code) {}
  int exit_code() const { return exit_code_; }

 private:
  int exit_code_;
};

// Adds the standard `--devices` option (see host/cl/device_selection.h) to a subcommand that runs kernels.
CLI::Option* add_devices_option(CLI::App* command, std::string& selection);

// Adds `--tile-timeout SECONDS` (0, or at least 5) to a subcommand whose kernels run through the scheduler: it sets
// RFRECON_TILE_TIMEOUT for the process, which every stage reads (docs/scheduler.md).
void add_tile_timeout_option(CLI::App* command);

// Adds `--entry auto|ndrange|single|LIST` (host/cl/entry_choice.h; default auto) to a subcommand whose kernels have
// both entries; a word that is none of these is a parse error (exit 2). The list's length is checked against the
// selected devices by the library call (UsageError, exit 2).
CLI::Option* add_entry_option(CLI::App* command, cl::EntryChoice& entries);

void add_devices_command(CLI::App& app);
void add_selfcheck_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_patterns_command(CLI::App& app);
void add_capture_command(CLI::App& app);
void add_transport_command(CLI::App& app);
void add_check_command(CLI::App& app);
void add_dual_command(CLI::App& app);
void add_calibrate_commands(CLI::App& app);
void add_evaluate_command(CLI::App& app);
void add_evaluate_rig_command(CLI::App& app);
void add_reconstruct_command(CLI::App& app);
void add_demo_command(CLI::App& app);

}  // namespace rfrecon::cli
