// `rfrecon evaluate`: accuracy of a reconstruction directory against the ground truth of `rfrecon simulate`.
#include <iostream>

#include <spdlog/spdlog.h>

#include "host/cli/commands.h"
#include "host/evaluation/evaluate_directory.h"

namespace rfrecon::cli {

namespace {
void run_evaluate(const evaluation::EvaluationRequest& request) {
  const auto run = evaluation::evaluate_directory(request);
  std::cout << evaluation::evaluation_table(run.evaluation) << std::flush;
  spdlog::info("evaluate: wrote {} and {} (|error| 0 to {:.4g} mm, 1 % of the object size)", run.report.string(),
               run.error_map.string(), evaluation::error_map_full_scale_mm(run.evaluation));
}
}  // namespace

void add_evaluate_command(CLI::App& app) {
  auto options = std::make_shared<evaluation::EvaluationRequest>();
  auto* command = app.add_subcommand("evaluate", "Compare a reconstruction with the ground truth of `simulate`");
  command->add_option("reconstruction", options->reconstruction_dir, "Output directory of `rfrecon reconstruct`")
      ->required();
  command->add_option("--truth", options->truth_dir, "Output directory of `rfrecon simulate` (or its truth/ folder)")
      ->required();
  command->add_option("--object", options->object, "Object to evaluate (default: the scene's first object)");
  command->add_option("-o,--output", options->report, "Report JSON (default: RECONSTRUCTION/evaluation.json)");
  command->add_option("--error-map", options->error_map, "Error-map PNG (default: RECONSTRUCTION/error_map.png)");
  command->add_option("--same-pixels-as", options->same_pixels_as,
                      "Other reconstructions of the scene: count only the pixels they all reconstructed");
  command->add_flag("--force", options->force, "Replace an existing report and error map");
  command->callback([options] { run_evaluate(*options); });
}

}  // namespace rfrecon::cli
