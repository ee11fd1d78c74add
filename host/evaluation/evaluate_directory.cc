// Reads a reconstruction and its truth, evaluates, writes the report.
#include "host/evaluation/evaluate_directory.h"

#include <cmath>
#include <limits>

#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/output_path.h"
#include "host/outputs/reconstruction_files.h"

namespace rfrecon::evaluation {

EvaluationRun evaluate_directory(const EvaluationRequest& request) {
  EvaluationRun run;
  run.report = request.report.empty() ? request.reconstruction_dir / "evaluation.json" : request.report;
  run.error_map = request.error_map.empty() ? request.reconstruction_dir / "error_map.png" : request.error_map;
  std::vector<std::filesystem::path> inputs{request.truth_dir};
  for (const auto& name : outputs::kReconstructionMaps) inputs.push_back(request.reconstruction_dir / name);
  for (const auto& other : request.same_pixels_as) inputs.push_back(other / "depth.tiff");
  const OutputPath report{run.report, "--output", request.force};
  const OutputPath error_map{run.error_map, "--error-map", request.force};
  check_output_file(report, inputs);
  check_output_file(error_map, inputs);
  check_distinct_outputs({report, error_map});
  const auto truth = read_evaluation_truth(request.truth_dir, request.object);
  auto reconstruction = outputs::read_reconstruction(request.reconstruction_dir);
  for (const auto& other_dir : request.same_pixels_as) {
    const auto other = outputs::read_reconstruction(other_dir);
    if (other.depth_mm.size() != reconstruction.depth_mm.size()) {
      throw InputError((other_dir / "depth.tiff").string() + " is " + size_text(other.depth_mm.size()) + " but " +
                       (request.reconstruction_dir / "depth.tiff").string() + " is " +
                       size_text(reconstruction.depth_mm.size()));
    }
    for (int y = 0; y < other.depth_mm.rows; ++y) {
      for (int x = 0; x < other.depth_mm.cols; ++x) {
        if (!std::isfinite(other.depth_mm.at<float>(y, x))) {
          reconstruction.depth_mm.at<float>(y, x) = std::numeric_limits<float>::quiet_NaN();
        }
      }
    }
  }
  run.evaluation = evaluate(reconstruction, truth, (request.reconstruction_dir / "depth.tiff").string());
  for (const auto& other : request.same_pixels_as) run.evaluation.same_pixels_as.push_back(other.string());
  write_evaluation(run.evaluation, run.report, run.error_map);
  return run;
}

}  // namespace rfrecon::evaluation
