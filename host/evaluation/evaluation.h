// Accuracy of a reconstruction against the ground truth of `rfrecon simulate`: coverage, depth and normal errors of
// one object (the subject) and of every pixel with truth, an error-map image and the evaluation.json report.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "host/outputs/reconstruction.h"
#include "host/truth/ground_truth.h"

namespace rfrecon::evaluation {

// The truth maps of a single view and the object being evaluated.
struct EvaluationTruth {
  std::filesystem::path truth_dir;  // holds depth.tiff, normals.tiff, object_id.png, objects.json
  cv::Mat depth_mm;                 // CV_32F, NaN where no surface
  cv::Mat normals;                  // CV_32FC3, NaN where no surface
  cv::Mat object_id;                // CV_16U: the object's label, 0 where none
  truth::TruthObject object;
};

// Reads the truth of `dir` (truth::read_truth: a truth folder or a single-view `rfrecon simulate` output).
// `object_name` selects the object; empty: the first object (the subject of the built-in scenes). Throws InputError
// naming the file when a file is missing, malformed or mis-sized, when no object has that name, and when the object
// has no size to express errors in (an infinite plane).
EvaluationTruth read_evaluation_truth(const std::filesystem::path& dir, const std::string& object_name = "");

// Error statistics over one set of pixels with truth depth. Depth error = reconstructed - truth z (mm); the error
// figures cover the reconstructed pixels of the set and are NaN when there are none.
struct ErrorStats {
  std::size_t truth_pixels = 0;          // pixels in the set
  std::size_t reconstructed_pixels = 0;  // of those, with finite reconstructed depth
  double coverage_percent = 0.0;         // 100 reconstructed / truth pixels (NaN for an empty set)
  double rms_mm = 0.0;
  double mean_abs_mm = 0.0;
  double max_abs_mm = 0.0;
  double bias_mm = 0.0;           // mean signed error
  std::size_t normal_pixels = 0;  // pixels of the set where both normals are finite
  double normal_rms_deg = 0.0;    // RMS angle between the normals
  // Of the reconstructed pixels, those with a depth sigma (the reconstruction's depth_sigma_mm), the RMS of that sigma
  // and of error / sigma: about 1 where the error bar is honest and the error is noise, above 1 where the error has a
  // part the sigma does not model (NaN without sigma).
  std::size_t sigma_pixels = 0;
  double sigma_rms_mm = 0.0;
  double error_over_sigma_rms = 0.0;
};

struct Evaluation {
  std::string reconstruction_name;  // for reports: e.g. the reconstruction directory
  std::filesystem::path truth_dir;
  std::string object_name;
  std::string object_shape;
  int object_label = 0;
  double object_size_mm = 0.0;
  std::string size_rule;
  ErrorStats object;                        // truth object_id == object_label and finite truth depth
  ErrorStats all;                           // every pixel with finite truth depth (every object)
  cv::Mat depth_error_mm;                   // CV_32F: reconstructed - truth where both finite, NaN elsewhere
  cv::Mat object_mask;                      // CV_8U: 255 on the object's pixels
  std::vector<std::string> same_pixels_as;  // reconstructions whose pixels alone counted (none: every pixel)
};

// Compares the reconstruction's depth_mm and normals with the truth. Throws InputError when the sizes differ
// (naming `reconstruction_name` and the truth's depth.tiff), ProcessingError when the object is not visible.
Evaluation evaluate(const outputs::Reconstruction& reconstruction, const EvaluationTruth& truth,
                    const std::string& reconstruction_name = "the reconstruction");

// The error map's full scale: 1 % of the object's size.
double error_map_full_scale_mm(const Evaluation& evaluation);

// 8-bit BGR: on the object, |depth error| through COLORMAP_TURBO from 0 (dark blue) to error_map_full_scale_mm
// (dark red, saturating above); object pixels without reconstruction black; pixels outside the object grey (128).
cv::Mat error_map(const Evaluation& evaluation);

// The evaluation.json report (docs/formats.md), keys in document order; `error_map_file` is recorded as given.
nlohmann::ordered_json evaluation_report(const Evaluation& evaluation, const std::string& error_map_file);

// A short human-readable table of the report's figures.
std::string evaluation_table(const Evaluation& evaluation);

// Writes the report (evaluation_report, pretty-printed) and the error-map PNG (error_map with its legend to the
// right, outputs::with_legend), each atomically.
void write_evaluation(const Evaluation& evaluation, const std::filesystem::path& report_file,
                      const std::filesystem::path& error_map_file);

}  // namespace rfrecon::evaluation
