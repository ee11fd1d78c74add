// Reads the ground truth, accumulates depth and normal errors per pixel set, renders the error map and report.
#include "host/evaluation/evaluation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string_view>
#include <tuple>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <spdlog/fmt/fmt.h>

#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/message_text.h"
#include "host/outputs/legend.h"

namespace rfrecon::evaluation {

namespace fs = std::filesystem;

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kErrorMapFullScaleFraction = 0.01;  // of the object's size

// Sums over one pixel set, turned into ErrorStats at the end.
struct Accumulator {
  std::size_t truth_pixels = 0, reconstructed = 0, normal_pixels = 0, sigma_pixels = 0;
  double sum = 0.0, sum_abs = 0.0, sum_squares = 0.0, max_abs = 0.0, sum_angle_squares = 0.0;
  double sum_sigma_squares = 0.0, sum_normalized_squares = 0.0;

  void add(double error_mm, double angle_deg, double sigma_mm) {
    ++truth_pixels;
    if (std::isfinite(error_mm)) {
      ++reconstructed;
      sum += error_mm;
      sum_abs += std::abs(error_mm);
      sum_squares += error_mm * error_mm;
      max_abs = std::max(max_abs, std::abs(error_mm));
      if (sigma_mm > 0.0) {  // also rejects NaN
        ++sigma_pixels;
        sum_sigma_squares += sigma_mm * sigma_mm;
        sum_normalized_squares += (error_mm / sigma_mm) * (error_mm / sigma_mm);
      }
    }
    if (std::isfinite(angle_deg)) {
      ++normal_pixels;
      sum_angle_squares += angle_deg * angle_deg;
    }
  }

  ErrorStats stats() const {
    ErrorStats s;
    s.truth_pixels = truth_pixels;
    s.reconstructed_pixels = reconstructed;
    s.coverage_percent = truth_pixels > 0 ? 100.0 * static_cast<double>(reconstructed) / truth_pixels : kNaN;
    const double n = static_cast<double>(reconstructed);
    s.rms_mm = reconstructed > 0 ? std::sqrt(sum_squares / n) : kNaN;
    s.mean_abs_mm = reconstructed > 0 ? sum_abs / n : kNaN;
    s.max_abs_mm = reconstructed > 0 ? max_abs : kNaN;
    s.bias_mm = reconstructed > 0 ? sum / n : kNaN;
    s.normal_pixels = normal_pixels;
    s.normal_rms_deg = normal_pixels > 0 ? std::sqrt(sum_angle_squares / static_cast<double>(normal_pixels)) : kNaN;
    s.sigma_pixels = sigma_pixels;
    const double m = static_cast<double>(sigma_pixels);
    s.sigma_rms_mm = sigma_pixels > 0 ? std::sqrt(sum_sigma_squares / m) : kNaN;
    s.error_over_sigma_rms = sigma_pixels > 0 ? std::sqrt(sum_normalized_squares / m) : kNaN;
    return s;
  }
};

// Angle between two normals in degrees (atan2 of |cross| and dot: accurate for small angles); NaN if either is not
// finite or is zero.
double angle_deg(const cv::Vec3f& a, const cv::Vec3f& b) {
  const cv::Vec3d u(a), v(b);
  const double cross = cv::norm(u.cross(v)), dot = u.dot(v);
  if (!std::isfinite(cross) || !std::isfinite(dot) || (cross == 0.0 && dot == 0.0)) return kNaN;
  return std::atan2(cross, dot) * 180.0 / CV_PI;
}

nlohmann::ordered_json stats_json(const ErrorStats& s, double size_mm) {
  const auto percent = [&](double mm) { return 100.0 * mm / size_mm; };
  return {{"truth_pixels", s.truth_pixels},
          {"reconstructed_pixels", s.reconstructed_pixels},
          {"coverage_percent", s.coverage_percent},
          {"depth_error_mm",
           {{"rms", s.rms_mm}, {"mean_abs", s.mean_abs_mm}, {"max_abs", s.max_abs_mm}, {"bias", s.bias_mm}}},
          {"depth_error_percent_of_size",
           {{"rms", percent(s.rms_mm)}, {"mean_abs", percent(s.mean_abs_mm)}, {"max_abs", percent(s.max_abs_mm)}}},
          {"normal_pixels", s.normal_pixels},
          {"normal_error_deg_rms", s.normal_rms_deg},
          {"depth_sigma",
           {{"pixels", s.sigma_pixels},
            {"predicted_rms_mm", s.sigma_rms_mm},
            {"error_over_sigma_rms", s.error_over_sigma_rms}}}};
}
// The objects' names for a message: each quoted through excerpt(), the first kListedObjects of them.
std::string object_names(const std::vector<truth::TruthObject>& objects) {
  constexpr std::size_t kListedObjects = 10;
  std::string names;
  for (std::size_t i = 0; i < std::min(objects.size(), kListedObjects); ++i) {
    names += (i > 0 ? ", " : "") + excerpt(objects[i].name, 40);
  }
  if (objects.size() > kListedObjects) names += " and " + std::to_string(objects.size() - kListedObjects) + " more";
  return names;
}
}  // namespace

EvaluationTruth read_evaluation_truth(const fs::path& dir, const std::string& object_name) {
  auto view = truth::read_truth(dir);
  const fs::path objects_file = view.dir / "objects.json";
  if (view.objects.empty()) throw InputError(objects_file.string() + ": the scene has no objects");
  auto found = view.objects.begin();
  if (!object_name.empty()) {
    found = std::find_if(view.objects.begin(), view.objects.end(),
                         [&](const truth::TruthObject& o) { return o.name == object_name; });
    if (found == view.objects.end()) {
      throw InputError(objects_file.string() + ": no object named '" + excerpt(object_name) +
                       "' (objects: " + object_names(view.objects) + ")");
    }
  }
  if (!(found->size_mm > 0.0)) {
    throw InputError(objects_file.string() + ": object '" + excerpt(found->name) +
                     "' has no size to express errors in (" + excerpt(found->size_rule) + ")");
  }
  EvaluationTruth truth;
  truth.truth_dir = view.dir;
  truth.depth_mm = std::move(view.maps.depth_mm);
  truth.normals = std::move(view.maps.normals);
  truth.object_id = std::move(view.maps.object_id);
  truth.object = *found;
  return truth;
}

Evaluation evaluate(const outputs::Reconstruction& reconstruction, const EvaluationTruth& truth,
                    const std::string& reconstruction_name) {
  const cv::Size size = truth.depth_mm.size();
  if (reconstruction.depth_mm.size() != size || reconstruction.normals.size() != size) {
    throw InputError(reconstruction_name + " is " + size_text(reconstruction.depth_mm.size()) + " but the truth " +
                     (truth.truth_dir / "depth.tiff").string() + " is " + size_text(size));
  }
  Evaluation e;
  e.reconstruction_name = reconstruction_name;
  e.truth_dir = truth.truth_dir;
  e.object_name = truth.object.name;
  e.object_shape = truth.object.shape;
  e.object_label = truth.object.label;
  e.object_size_mm = truth.object.size_mm;
  e.size_rule = truth.object.size_rule;
  e.depth_error_mm = cv::Mat(size, CV_32F, cv::Scalar(kNaN));
  e.object_mask = cv::Mat::zeros(size, CV_8U);
  Accumulator object, all;
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const float z_truth = truth.depth_mm.at<float>(y, x);
      if (!std::isfinite(z_truth)) continue;
      const double error_mm = static_cast<double>(reconstruction.depth_mm.at<float>(y, x)) - z_truth;
      e.depth_error_mm.at<float>(y, x) = static_cast<float>(error_mm);
      const double angle = angle_deg(reconstruction.normals.at<cv::Vec3f>(y, x), truth.normals.at<cv::Vec3f>(y, x));
      const double sigma_mm =
          reconstruction.depth_sigma_mm.empty() ? kNaN : reconstruction.depth_sigma_mm.at<float>(y, x);
      all.add(error_mm, angle, sigma_mm);
      if (truth.object_id.at<std::uint16_t>(y, x) == truth.object.label) {
        e.object_mask.at<std::uint8_t>(y, x) = 255;
        object.add(error_mm, angle, sigma_mm);
      }
    }
  }
  if (object.truth_pixels == 0) {
    throw ProcessingError("object '" + truth.object.name + "' is not visible in " +
                          (truth.truth_dir / "object_id.png").string());
  }
  e.object = object.stats();
  e.all = all.stats();
  return e;
}

double error_map_full_scale_mm(const Evaluation& evaluation) {
  return kErrorMapFullScaleFraction * evaluation.object_size_mm;
}

cv::Mat error_map(const Evaluation& evaluation) {
  cv::Mat abs_error = cv::abs(evaluation.depth_error_mm), scaled, coloured;
  abs_error.convertTo(scaled, CV_8U, 255.0 / error_map_full_scale_mm(evaluation));  // saturates above full scale
  cv::applyColorMap(scaled, coloured, cv::COLORMAP_TURBO);
  cv::Mat map(coloured.size(), CV_8UC3, cv::Scalar::all(128));
  for (int y = 0; y < map.rows; ++y) {
    for (int x = 0; x < map.cols; ++x) {
      if (evaluation.object_mask.at<std::uint8_t>(y, x) == 0) continue;
      map.at<cv::Vec3b>(y, x) =
          std::isfinite(evaluation.depth_error_mm.at<float>(y, x)) ? coloured.at<cv::Vec3b>(y, x) : cv::Vec3b(0, 0, 0);
    }
  }
  return map;
}

nlohmann::ordered_json evaluation_report(const Evaluation& e, const std::string& error_map_file) {
  nlohmann::ordered_json report{{"format", "rfrecon-evaluation"},
                                {"version", 1},
                                {"reconstruction", e.reconstruction_name},
                                {"truth", e.truth_dir.string()},
                                {"object",
                                 {{"name", e.object_name},
                                  {"shape", e.object_shape},
                                  {"id", e.object_label},
                                  {"size_mm", e.object_size_mm},
                                  {"size_rule", e.size_rule}}},
                                {"object_pixels", stats_json(e.object, e.object_size_mm)},
                                {"all_pixels", stats_json(e.all, e.object_size_mm)},
                                {"error_map",
                                 {{"file", error_map_file},
                                  {"colormap", "turbo"},
                                  {"full_scale_mm", error_map_full_scale_mm(e)},
                                  {"no_reconstruction", "black"},
                                  {"outside_object", "grey"}}}};
  if (!e.same_pixels_as.empty()) report["same_pixels_as"] = e.same_pixels_as;
  return report;
}

std::string evaluation_table(const Evaluation& e) {
  std::string table =
      fmt::format("object '{}' ({}, {:.6g} mm = {})\n", e.object_name, e.object_shape, e.object_size_mm, e.size_rule);
  table += fmt::format("{:<8} {:>9} {:>11} {:>9} {:>9} {:>9} {:>9} {:>10} {:>14}\n", "pixels", "truth", "coverage %",
                       "rms mm", "mean mm", "max mm", "bias mm", "rms % size", "normal rms deg");
  for (const auto& [name, s] : {std::pair<const char*, const ErrorStats&>{"object", e.object},
                                std::pair<const char*, const ErrorStats&>{"all", e.all}}) {
    table += fmt::format("{:<8} {:>9} {:>11.2f} {:>9.4f} {:>9.4f} {:>9.4f} {:>9.4f} {:>10.4f} {:>14.3f}\n", name,
                         s.truth_pixels, s.coverage_percent, s.rms_mm, s.mean_abs_mm, s.max_abs_mm, s.bias_mm,
                         100.0 * s.rms_mm / e.object_size_mm, s.normal_rms_deg);
  }
  if (e.object.sigma_pixels > 0) {
    table += fmt::format("object error / depth sigma: RMS {:.3f} over {} pixels (predicted sigma RMS {:.4f} mm)\n",
                         e.object.error_over_sigma_rms, e.object.sigma_pixels, e.object.sigma_rms_mm);
  }
  return table;
}

void write_evaluation(const Evaluation& evaluation, const fs::path& report_file, const fs::path& error_map_file) {
  const fs::path relative = error_map_file.lexically_relative(report_file.parent_path());
  const std::string recorded =
      !relative.empty() && relative.begin()->string() != ".." ? relative.string() : error_map_file.string();
  std::vector<unsigned char> png;
  const double full_scale_mm = error_map_full_scale_mm(evaluation);
  const outputs::Legend legend{"|depth error| (mm)",
                               outputs::colour_bar_key(cv::COLORMAP_TURBO),
                               outputs::bar_ticks(0.0, full_scale_mm, full_scale_mm < 1.0 ? 3 : 2, ">= "),
                               {"1 % of the object's size", "black: not reconstructed", "grey: not the object"}};
  if (!cv::imencode(".png", outputs::with_legend(error_map(evaluation), legend), png)) {
    throw std::runtime_error("cannot encode the error map");
  }
  // Both written before either is renamed: an output that cannot be written, or that appeared meanwhile, leaves
  // neither.
  AtomicFile error_map_output(error_map_file);
  error_map_output.write(std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
  AtomicFile report_output(report_file);
  report_output.write(evaluation_report(evaluation, recorded).dump(2) + "\n");
  error_map_output.commit();
  report_output.commit();
}

}  // namespace rfrecon::evaluation
