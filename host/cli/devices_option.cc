// The `--devices`, `--tile-timeout` and `--entry` options shared by the commands that run kernels.
#include <cmath>
#include <cstdlib>
#include <string>

#include "host/cl/entry_choice.h"
#include "host/cli/commands.h"
#include "host/core/errors.h"
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

CLI::Option* add_entry_option(CLI::App* command, cl::EntryChoice& entries) {
  return command
      ->add_option_function<std::string>(
          "--entry", [&entries](const std::string& text) { entries = cl::EntryChoice::parse(text); },
          "Kernel entry per device: auto (single work-item on FPGA boards, NDRange on CPUs and GPUs), ndrange or "
          "single for every device, or one of them per selected device, comma-separated in the order of "
          "`rfrecon devices`")
      ->check(CLI::Validator(
          [](const std::string& text) {
            try {
              cl::EntryChoice::parse(text);
              return std::string();
            } catch (const UsageError& error) {
              return std::string(error.what());
            }
          },
          "auto|ndrange|single|LIST"))
      ->default_str("auto");
}

}  // namespace rfrecon::cli
