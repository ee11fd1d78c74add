// Robust gating of a stereo calibration's observations: a pose whose residuals as a whole, or a corner whose residual,
// stand out against all the residuals of its series (robust z-score: median and MAD) is down-weighted (a pose) or
// dropped (a corner), and every such decision is kept with the numbers behind it for the report.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "calib/joint_problem.h"

namespace rfrecon::calib {

struct GatingThresholds {
  double corner_z = 5.0;       // a corner whose residual length has a robust z-score above this is dropped
  double pose_z = 3.0;         // a pose whose RMS has a robust z-score above this is down-weighted
  double min_sigma_px = 0.02;  // the robust sigma's floor: a corner within median + 0.1 px is never dropped
};

// The robust spread of one series' residual lengths (px): median, and the MAD scaled to a Gaussian's sigma
// (1.4826 MAD, at least min_sigma_px).
struct ResidualSpread {
  double median_px = 0.0;
  double sigma_px = 0.0;
  double z(double length_px) const { return (length_px - median_px) / sigma_px; }
};

// One decision: a corner dropped (corner >= 0, weight 0) or a pose's series down-weighted (corner -1).
struct GatingDecision {
  int round = 1;           // the gating round that made it (each round follows an adjustment)
  std::string view;        // the pose's name
  std::string series;      // "camera", "projector" or "dense"
  int corner = -1;         // the corner's index in OpenCV's order; -1 for the whole pose
  double residual_px = 0;  // the corner's residual length, or the pose's median length over its kept points
  double z = 0;            // its robust z-score against the series' spread
  ResidualSpread spread;   // the series' median and sigma it was judged against
  double weight = 0;       // 0: dropped; otherwise the pose's new weight
  std::string describe() const;
};

// Gates one series (one device's corners, or the dense correspondences with corners = false) of every view: the
// residual lengths of the points not yet dropped give the spread. A pose whose median length over its kept points is
// above thresholds.pose_z gets weight (series median / pose median)^2, the ratio of the noise variances (replacing,
// never compounding, an earlier weight; a decision when it falls by more than 1 %). Then, with `corners`, a point
// whose length times the square root of its pose's weight (as the adjustment weighs it) is above thresholds.corner_z
// is marked dropped. Returns the new decisions.
std::vector<GatingDecision> gate_series(const std::vector<std::string>& view_names, const std::string& series,
                                        const std::vector<std::vector<cv::Point2d>>& residuals_px, bool corners,
                                        const GatingThresholds& thresholds, int round,
                                        std::vector<ObservationWeights*>& weights);

nlohmann::json gating_json(const GatingThresholds& thresholds, const std::vector<GatingDecision>& decisions);

}  // namespace rfrecon::calib
