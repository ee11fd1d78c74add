// Robust z-scores of calibration residuals and the gating decisions taken on them.
#include "calib/residual_gating.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "host/core/percentile.h"

namespace rfrecon::calib {

namespace {
double median_of(const std::vector<double>& values) { return percentile_of(values, 0.5); }

ResidualSpread spread_of(const std::vector<double>& lengths_px, double min_sigma_px) {
  ResidualSpread spread;
  spread.median_px = median_of(lengths_px);
  std::vector<double> deviations;
  deviations.reserve(lengths_px.size());
  for (const double length : lengths_px) deviations.push_back(std::abs(length - spread.median_px));
  spread.sigma_px = std::max(1.4826 * median_of(deviations), min_sigma_px);
  return spread;
}

double length(const cv::Point2d& r) { return std::hypot(r.x, r.y); }
}  // namespace

std::string GatingDecision::describe() const {
  char text[256];
  if (corner >= 0) {
    std::snprintf(text, sizeof(text),
                  "%s %s corner %d: residual %.3f px, z %.1f (median %.3f px, sigma %.3f px): dropped", view.c_str(),
                  series.c_str(), corner, residual_px, z, spread.median_px, spread.sigma_px);
  } else {
    std::snprintf(text, sizeof(text),
                  "%s %s: median residual %.3f px, z %.1f (median %.3f px, sigma %.3f px): down-weighted to %.3f",
                  view.c_str(), series.c_str(), residual_px, z, spread.median_px, spread.sigma_px, weight);
  }
  return text;
}

std::vector<GatingDecision> gate_series(const std::vector<std::string>& view_names, const std::string& series,
                                        const std::vector<std::vector<cv::Point2d>>& residuals_px, bool corners,
                                        const GatingThresholds& thresholds, int round,
                                        std::vector<ObservationWeights*>& weights) {
  std::vector<double> lengths;
  for (std::size_t v = 0; v < residuals_px.size(); ++v) {
    for (std::size_t i = 0; i < residuals_px[v].size(); ++i) {
      if (weights[v]->kept(i)) lengths.push_back(length(residuals_px[v][i]));
    }
  }
  std::vector<GatingDecision> decisions;
  if (lengths.empty()) return decisions;
  const ResidualSpread spread = spread_of(lengths, thresholds.min_sigma_px);
  for (std::size_t v = 0; v < residuals_px.size(); ++v) {
    ObservationWeights& view = *weights[v];
    std::vector<double> pose_lengths;
    for (std::size_t i = 0; i < residuals_px[v].size(); ++i) {
      if (view.kept(i)) pose_lengths.push_back(length(residuals_px[v][i]));
    }
    if (pose_lengths.empty()) continue;
    const double pose_median = median_of(pose_lengths);
    if (spread.z(pose_median) > thresholds.pose_z) {
      const double weight = (spread.median_px / pose_median) * (spread.median_px / pose_median);
      if (weight < 0.99 * view.pose) {
        view.pose = weight;
        decisions.push_back({round, view_names[v], series, -1, pose_median, spread.z(pose_median), spread, weight});
      }
    }
    if (!corners) continue;
    for (std::size_t i = 0; i < residuals_px[v].size(); ++i) {
      const double r = length(residuals_px[v][i]);
      const double z = spread.z(r * std::sqrt(view.pose));
      if (!view.kept(i) || z <= thresholds.corner_z) continue;
      view.dropped.resize(residuals_px[v].size(), 0);
      view.dropped[i] = 1;
      decisions.push_back({round, view_names[v], series, static_cast<int>(i), r, z, spread, 0.0});
    }
  }
  return decisions;
}

nlohmann::json gating_json(const GatingThresholds& thresholds, const std::vector<GatingDecision>& decisions) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& d : decisions) {
    nlohmann::json entry = {{"round", d.round},
                            {"view", d.view},
                            {"series", d.series},
                            {"action", d.corner >= 0 ? "dropped" : "down-weighted"},
                            {"z", d.z},
                            {"median_px", d.spread.median_px},
                            {"sigma_px", d.spread.sigma_px},
                            {"weight", d.weight}};
    if (d.corner >= 0) {
      entry["corner"] = d.corner;
      entry["residual_px"] = d.residual_px;
    } else {
      entry["pose_median_px"] = d.residual_px;
    }
    list.push_back(std::move(entry));
  }
  return {{"corner_z_max", thresholds.corner_z},
          {"pose_z_max", thresholds.pose_z},
          {"min_sigma_px", thresholds.min_sigma_px},
          {"decisions", list}};
}

}  // namespace rfrecon::calib
