// Reads a reconstruction and its truth, evaluates, writes the report.
#include "host/evaluation/evaluate_directory.h"

#include "host/outputs/reconstruction_files.h"

namespace rfrecon::evaluation {

EvaluationRun evaluate_directory(const EvaluationRequest& request) {
  const auto truth = read_evaluation_truth(request.truth_dir, request.object);
  const auto reconstruction = outputs::read_reconstruction(request.reconstruction_dir);
  EvaluationRun run;
  run.evaluation = evaluate(reconstruction, truth, (request.reconstruction_dir / "depth.tiff").string());
  run.report = request.report.empty() ? request.reconstruction_dir / "evaluation.json" : request.report;
  run.error_map = request.error_map.empty() ? request.reconstruction_dir / "error_map.png" : request.error_map;
  write_evaluation(run.evaluation, run.report, run.error_map);
  return run;
}

}  // namespace rfrecon::evaluation
