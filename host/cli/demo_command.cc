// `rfrecon demo`: the whole pipeline on the synthetic rig, in one command: render the checkerboard poses and the
// anisotropic cube, build T, calibrate from the poses (not from the true rig), reconstruct with the three methods,
// evaluate them against the truth and print one row per method. Each step runs the same subcommand a user would.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <vector>

#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "host/cli/commands.h"
#include "host/common/atomic_file.h"
#include "host/common/errors.h"

namespace rfrecon::cli {

namespace {
namespace fs = std::filesystem;

struct DemoOptions {
  fs::path out = "out/demo";
  std::string devices;
};

// Runs one `rfrecon` subcommand in this process, as if typed on the command line.
void run_step(const std::string& title, std::vector<std::string> arguments) {
  spdlog::info("demo: {}: rfrecon {}", title, fmt::format("{}", fmt::join(arguments, " ")));
  CLI::App app;
  app.require_subcommand(1);
  for (const auto add : {add_simulate_command, add_transport_command, add_calibrate_commands, add_reconstruct_command,
                         add_evaluate_command}) {
    add(app);
  }
  std::reverse(arguments.begin(), arguments.end());  // CLI11 takes the arguments last first
  app.parse(arguments);
}

std::vector<std::string> with_devices(std::vector<std::string> arguments, const std::string& devices) {
  if (!devices.empty()) arguments.insert(arguments.end(), {"--devices", devices});
  return arguments;
}

void run_demo(const DemoOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path poses = options.out / "checkerboard-poses", cube = options.out / "cube-anisotropic";
  const fs::path rig = options.out / "rig.yaml";
  run_step("render the calibration poses",
           {"simulate", "--scene", "checkerboard-poses", "--out", poses.string(), "--force"});
  std::vector<std::string> calibrate{"calibrate"};
  for (int pose = 0;; ++pose) {
    const fs::path dir = poses / "capture" / fmt::format("pose_{:02d}", pose);
    if (!fs::exists(dir)) break;
    calibrate.push_back(dir.string());
  }
  calibrate.insert(calibrate.end(), {"--board", "9x6", "--square", "30", "-o", rig.string()});
  run_step("calibrate camera and projector from the poses", with_devices(calibrate, options.devices));
  run_step("render the cube", {"simulate", "--scene", "cube-anisotropic", "--out", cube.string(), "--force"});
  run_step("light transport of the cube",
           with_devices({"transport", (cube / "capture").string(), "-o", (cube / "T.h5").string()}, options.devices));

  nlohmann::json table = nlohmann::json::array();
  for (const std::string method : {"triangulate", "integrate", "fused"}) {
    const fs::path result = options.out / method;
    run_step("reconstruct (" + method + ")",
             with_devices({"reconstruct", (cube / "T.h5").string(), "--calib", rig.string(), "--method", method, "-o",
                           result.string(), "--force"},
                          options.devices));
    run_step("evaluate (" + method + ")", {"evaluate", result.string(), "--truth", cube.string()});
    std::ifstream report(result / "evaluation.json");
    const auto evaluation = nlohmann::json::parse(report);
    const auto& pixels = evaluation.at("object_pixels");
    table.push_back({{"method", method},
                     {"rms_mm", pixels.at("depth_error_mm").at("rms")},
                     {"rms_percent", pixels.at("depth_error_percent_of_size").at("rms")},
                     {"mean_abs_mm", pixels.at("depth_error_mm").at("mean_abs")},
                     {"max_abs_mm", pixels.at("depth_error_mm").at("max_abs")},
                     {"coverage_percent", pixels.at("coverage_percent")},
                     {"object_size_mm", evaluation.at("object").at("size_mm")}});
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_file_atomically(
      options.out / "demo.json",
      nlohmann::json{
          {"scene", "cube-anisotropic"}, {"calibration", rig.string()}, {"seconds", seconds}, {"methods", table}}
          .dump(2));

  std::printf("\ncube-anisotropic, calibrated from the simulated checkerboard poses (%.0f s in all):\n", seconds);
  std::printf("%-12s %10s %12s %11s %11s\n", "method", "RMS mm", "% of side", "max mm", "coverage %");
  for (const auto& row : table) {
    std::printf("%-12s %10.4f %12.3f %11.3f %11.1f\n", row["method"].get<std::string>().c_str(),
                row["rms_mm"].get<double>(), row["rms_percent"].get<double>(), row["max_abs_mm"].get<double>(),
                row["coverage_percent"].get<double>());
  }
  std::printf("(side %.0f mm; outputs, error maps and demo.json in %s)\n", table[0]["object_size_mm"].get<double>(),
              options.out.string().c_str());
}
}  // namespace

void add_demo_command(CLI::App& app) {
  auto options = std::make_shared<DemoOptions>();
  auto* command = app.add_subcommand("demo", "Simulate, calibrate, reconstruct and evaluate the built-in cube");
  command->add_option("--out", options->out, "Directory for every output (its demo files are replaced)")
      ->capture_default_str();
  add_devices_option(command, options->devices);
  command->callback([options] { run_demo(*options); });
}

}  // namespace rfrecon::cli
