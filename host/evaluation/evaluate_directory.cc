// Reads a reconstruction and its truth, evaluates, writes the report.
#include "host/evaluation/evaluate_directory.h"

#include "host/core/output_path.h"
#include "host/outputs/reconstruction_files.h"

namespace rfrecon::evaluation {

EvaluationRun evaluate_directory(const EvaluationRequest& request) {
  EvaluationRun run;
  run.report = request.report.empty() ? request.reconstruction_dir / "evaluation.json" : request.report;
  run.error_map = request.error_map.empty() ? request.reconstruction_dir / "error_map.png" : request.error_map;
  std::vector<std::filesystem::path> inputs{request.truth_dir};
  for (const auto& name : outputs::kReconstructionMaps) inputs.push_back(request.reconstruction_dir / name);
  const OutputPath report{run.report, "--output", request.force};
  const OutputPath error_map{run.error_map, "--error-map", request.force};
  check_output_file(report, inputs);
  check_output_file(error_map, inputs);
  check_distinct_outputs({report, error_map});
  const auto truth = read_evaluation_truth(request.truth_dir, request.object);
  const auto reconstruction = outputs::read_reconstruction(request.reconstruction_dir);
  run.evaluation = evaluate(reconstruction, truth, (request.reconstruction_dir / "depth.tiff").string());
  write_evaluation(run.evaluation, run.report, run.error_map);
  return run;
}

}  // namespace rfrecon::evaluation
