// Entry point of the `rfrecon` command-line tool: parses the command line and maps errors to exit codes.
#include <cstdlib>
#include <iostream>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "host/cl/error.h"
#include "host/cli/commands.h"
#include "host/cli/exit_codes.h"
#include "host/core/errors.h"
#include "host/core/temporaries.h"

namespace rfrecon::cli {

namespace {
int fail(int code, const char* kind, const std::exception& error) {
  spdlog::error("{}: {}", kind, error.what());
  return code;
}
}  // namespace

}  // namespace rfrecon::cli

int main(int argc, char** argv) {
  using namespace rfrecon::cli;
  rfrecon::install_signal_cleanup();
  spdlog::set_default_logger(spdlog::stderr_color_mt("rfrecon"));
  spdlog::set_pattern("[%H:%M:%S] %^%l%$: %v");

  CLI::App app{"rfrecon: 3D reconstruction of shiny and anisotropic objects from projector-camera reflectance fields"};
  app.set_version_flag("--version", std::string("rfrecon ") + RFRECON_VERSION);
  app.require_subcommand(1);
  bool verbose = false;
  bool quiet = false;
  app.add_flag("-v,--verbose", verbose, "Log debug details");
  app.add_flag("-q,--quiet", quiet, "Log warnings and errors only");
  app.parse_complete_callback([&] {
    spdlog::set_level(verbose ? spdlog::level::debug : quiet ? spdlog::level::warn : spdlog::level::info);
  });

  add_devices_command(app);
  add_selfcheck_command(app);
  add_simulate_command(app);
  add_patterns_command(app);
  add_capture_command(app);
  add_transport_command(app);
  add_check_command(app);
  add_dual_command(app);
  add_calibrate_commands(app);
  add_reconstruct_command(app);
  add_evaluate_command(app);
  add_evaluate_rig_command(app);
  add_demo_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error) == 0 ? kExitOk : kExitUsage;
  } catch (const CommandFailed& error) {
    return fail(error.exit_code(), "failed", error);
  } catch (const rfrecon::UsageError& error) {
    return fail(kExitUsage, "usage error", error);
  } catch (const rfrecon::OutputError& error) {
    return fail(kExitOutput, "cannot write output", error);
  } catch (const rfrecon::InputError& error) {
    return fail(kExitInput, "input error", error);
  } catch (const rfrecon::HardwareError& error) {
    return fail(kExitHardware, "capture hardware", error);
  } catch (const rfrecon::ProcessingError& error) {
    return fail(kExitProcessing, "cannot process", error);
  } catch (const rfrecon::cl::DeviceSelectionError& error) {
    return fail(kExitNoDevice, "device selection", error);
  } catch (const rfrecon::cl::ClError& error) {
    return fail(kExitOpenCl, "OpenCL error", error);
  } catch (const std::exception& error) {
    return fail(kExitInternal, "internal error", error);
  }
  return kExitOk;
}
