// `rfrecon evaluate` as a library call: a reconstruction directory against a truth folder, report and error map.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "host/evaluation/evaluation.h"

namespace rfrecon::evaluation {

struct EvaluationRequest {
  std::filesystem::path reconstruction_dir;  // written by outputs::write_reconstruction
  std::filesystem::path truth_dir;           // truth::read_truth
  std::string object;                        // empty: the first object
  std::filesystem::path report;              // default: reconstruction_dir / evaluation.json
  std::filesystem::path error_map;           // default: reconstruction_dir / error_map.png
  bool force = false;                        // replace an existing report and error map
  // Other reconstructions of the same scene: only the pixels every one of them reconstructed count, so that methods
  // or captures are compared on the same pixels.
  std::vector<std::filesystem::path> same_pixels_as;
};

struct EvaluationRun {
  Evaluation evaluation;
  std::filesystem::path report;
  std::filesystem::path error_map;
};

// Reads both, evaluates and writes the report and the error map (each atomically). Throws UsageError before reading
// for outputs that host/core/output_path.h refuses (an input, an existing file without force), InputError naming the
// file for a missing or mis-sized map (of a same_pixels_as reconstruction too), ProcessingError when the object is not
// visible.
EvaluationRun evaluate_directory(const EvaluationRequest& request);

}  // namespace rfrecon::evaluation
