// The `--devices` and `--tile-timeout` options shared by every command that runs kernels.
#include <cmath>
#include <cstdlib>
#include <string>

#include "host/cli/commands.h"
#include "host/sched/scheduler.h"

namespace rfrecon::cli {

namespace {
constexpr double kMinTileTimeoutS = 5.0;  // shorter limits drop devices that are only building their kernels
}  // namespace

void add_tile_timeout_option(CLI::App* command) {
  command
      ->add_option_function<double>(
          "--tile-timeout",
          [](double seconds) { ::setenv(sched::kTileTimeoutEnv, std::to_string(seconds).c_str(), 1); },
          "Seconds a device may take on one tile before it is dropped and its tiles run on the others; 0 = no "
          "limit (default: $RFRECON_TILE_TIMEOUT, else " +
              std::to_string(static_cast<int>(sched::kDefaultTileTimeoutS)) + ")")
      ->check(CLI::Validator(
          [](std::string& text) {
            double seconds = -1.0;
            if (CLI::detail::lexical_cast(text, seconds) && std::isfinite(seconds) &&
                (seconds == 0.0 || seconds >= kMinTileTimeoutS)) {
              return std::string();
            }
            return "expected 0 or at least " + std::to_string(static_cast<int>(kMinTileTimeoutS)) + " seconds, got '" +
                   text + "'";
          },
          "SECONDS"));
}

CLI::Option* add_devices_option(CLI::App* command, std::string& selection) {
  return command
      ->add_option("--devices", selection,
                   "OpenCL devices to use: all|cpu|gpu|fpga|INDEX|NAME, comma-separated "
                   "(default: $RFRECON_DEVICES, else all)")
      ->check(CLI::Validator(
          [](const std::string& text) {
            return text.find_first_not_of(" ,") == std::string::npos ? std::string("names no device (use 'all')")
                                                                     : std::string();
          },
          "SEL"));
}

}  // namespace rfrecon::cli
