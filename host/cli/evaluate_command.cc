// `rfrecon evaluate`: accuracy of a reconstruction directory against the ground truth of `rfrecon simulate`.
#include <iostream>

#include <spdlog/spdlog.h>

#include "host/cli/commands.h"
#include "host/reconstruct/evaluation.h"
#include "host/reconstruct/outputs.h"

namespace rfrecon::cli {

namespace {
struct EvaluateOptions {
  std::filesystem::path reconstruction_dir;
  std::filesystem::path truth_dir;
  std::string object;
  std::filesystem::path report;     // default: reconstruction_dir / evaluation.json
  std::filesystem::path error_map;  // default: reconstruction_dir / error_map.png
};

void run_evaluate(const EvaluateOptions& options) {
  const auto truth = reconstruct::read_evaluation_truth(options.truth_dir, options.object);
  const auto reconstruction = reconstruct::read_reconstruction(options.reconstruction_dir);
  const auto evaluation =
      reconstruct::evaluate(reconstruction, truth, (options.reconstruction_dir / "depth.tiff").string());
  const auto report = options.report.empty() ? options.reconstruction_dir / "evaluation.json" : options.report;
  const auto map = options.error_map.empty() ? options.reconstruction_dir / "error_map.png" : options.error_map;
  reconstruct::write_evaluation(evaluation, report, map);
  std::cout << reconstruct::evaluation_table(evaluation) << std::flush;
  spdlog::info("evaluate: wrote {} and {} (|error| 0 to {:.4g} mm, 1 % of the object size)", report.string(),
               map.string(), reconstruct::error_map_full_scale_mm(evaluation));
}
}  // namespace

void add_evaluate_command(CLI::App& app) {
  auto options = std::make_shared<EvaluateOptions>();
  auto* command = app.add_subcommand("evaluate", "Compare a reconstruction with the ground truth of `simulate`");
  command->add_option("reconstruction", options->reconstruction_dir, "Output directory of `rfrecon reconstruct`")
      ->required();
  command->add_option("--truth", options->truth_dir, "Output directory of `rfrecon simulate` (or its truth/ folder)")
      ->required();
  command->add_option("--object", options->object, "Object to evaluate (default: the scene's first object)");
  command->add_option("-o,--output", options->report, "Report JSON (default: RECONSTRUCTION/evaluation.json)");
  command->add_option("--error-map", options->error_map, "Error-map PNG (default: RECONSTRUCTION/error_map.png)");
  command->callback([options] { run_evaluate(*options); });
}

}  // namespace rfrecon::cli
