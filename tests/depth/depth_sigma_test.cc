// Each point's predicted depth uncertainty against what it predicts: the calibration's part against the spread of the
// rectified triangulation over rigs drawn from the covariance and against the baseline's closed form, the
// observation's against the spread of dot centroids drawn with the camera noise, and the camera noise fit against the
// line it was drawn from.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "calib/rig.h"
#include "host/capture/camera_noise.h"
#include "host/depth/calibration_sigma.h"
#include "host/depth/camera_grid.h"
#include "host/depth/observation_sigma.h"
#include "host/depth/rectification.h"
#include "host/transport/transport_types.h"

namespace rfrecon::depth {
namespace {

// A projector 170 mm above a small camera, tilted toward the scene, both with lens distortion.
calib::StereoRig small_rig(double baseline_x_mm = 20.0, double baseline_y_mm = -170.0) {
  calib::StereoRig rig;
  rig.camera_size = {64, 48};
  rig.projector_size = {80, 60};
  rig.camera_matrix = (cv::Mat_<double>(3, 3) << 110, 0, 33, 0, 111, 24, 0, 0, 1);
  rig.dist_coeffs = (cv::Mat_<double>(1, 5) << -0.08, 0.05, 0.0005, -0.0003, 0.0);
  rig.projector_matrix = (cv::Mat_<double>(3, 3) << 150, 0, 40, 0, 150, 4, 0, 0, 1);
  rig.projector_dist_coeffs = (cv::Mat_<double>(1, 5) << -0.15, 0.08, 0.001, -0.0008, 0.0);
  const double tilt = 15.0 * CV_PI / 180.0;
  rig.proj_from_cam_rotation =
      (cv::Mat_<double>(3, 3) << 1, 0, 0, 0, std::cos(tilt), -std::sin(tilt), 0, std::sin(tilt), std::cos(tilt));
  rig.proj_from_cam_translation_mm =
      -rig.proj_from_cam_rotation * (cv::Mat_<double>(3, 1) << baseline_x_mm, baseline_y_mm, 0);
  calib::compute_stereo_geometry(rig);
  return rig;
}

// The rig with parameter vector p (calib::RigUncertainty::parameter_covariance's order).
calib::StereoRig rig_of(calib::StereoRig rig, const std::vector<double>& p) {
  calib::set_rig_parameters(rig, p, 5);
  calib::compute_stereo_geometry(rig);
  return rig;
}

// T of the plane z = depth_mm(x) seen through `rig`: each camera pixel's correspondence is the projector point of its
// surface point.
transport::CompressedTransport plane_transport(const calib::StereoRig& rig, const cv::Mat& depth_mm) {
  transport::TransportSetup setup;
  setup.camera_size = rig.camera_size;
  setup.projector_size = rig.projector_size;
  setup.dot_spacing = 8;
  transport::CompressedTransport t = transport::make_empty_transport(setup);
  std::vector<cv::Point2f> pixels;
  for (int y = 0; y < rig.camera_size.height; ++y) {
    for (int x = 0; x < rig.camera_size.width; ++x) pixels.emplace_back(static_cast<float>(x), static_cast<float>(y));
  }
  std::vector<cv::Point2f> rays;
  cv::undistortPoints(pixels, rays, rig.camera_matrix, rig.dist_coeffs);
  std::vector<cv::Point3d> points;
  for (std::size_t c = 0; c < rays.size(); ++c) {
    const double z =
        depth_mm.at<float>(static_cast<int>(c) / rig.camera_size.width, static_cast<int>(c) % rig.camera_size.width);
    points.emplace_back(z * rays[c].x, z * rays[c].y, z);
  }
  std::vector<cv::Point2d> projected;
  cv::Vec3d om;
  cv::Rodrigues(rig.proj_from_cam_rotation, om);
  cv::projectPoints(points, om, cv::Vec3d(rig.proj_from_cam_translation_mm), rig.projector_matrix,
                    rig.projector_dist_coeffs, projected);
  for (std::size_t c = 0; c < projected.size(); ++c) {
    t.correspondence[2 * c] = static_cast<float>(projected[c].x);
    t.correspondence[2 * c + 1] = static_cast<float>(projected[c].y);
    t.flags[c] = transport::kFlagValid;
  }
  return t;
}

// Camera-frame depth of T's correspondences triangulated along the rectified rows of `rig`.
cv::Mat triangulated_depth(const transport::CompressedTransport& t, const calib::StereoRig& rig) {
  const Rectification rectification = depth_rectification(rig, "test rig", false);
  RectificationOptions options;
  options.epipolar_tolerance_px = 5.0f;
  options.boundary_relative = 1.0f;
  options.edge_relative = 1e9f;
  const CameraGridTriangulation triangulation = triangulate_camera_grid(t, rig, rectification, options);
  return camera_frame_maps(triangulation.z_rect_mm, triangulation.rect_cam, rectification.rig,
                           rectification.rect_from_cam)
      .depth_mm;
}

// A depth map that slopes from 450 to 750 mm across the image.
cv::Mat slanted_depth(cv::Size size) {
  cv::Mat depth(size, CV_32F);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) depth.at<float>(y, x) = 450.0f + 300.0f * x / (size.width - 1);
  }
  return depth;
}

TEST(CalibrationSigmaTest, PredictsTheSpreadOfTheTriangulationOverRigsDrawnFromTheCovariance) {
  const calib::StereoRig rig = small_rig();
  const std::vector<double> p0 = calib::rig_parameters(rig, 5);
  const int g = calib::rig_parameter_count(rig);
  ASSERT_EQ(g, static_cast<int>(p0.size()));
  // Standard deviations like a calibration's (focal lengths 0.1 %, principal points 0.3 px, distortion, angles 0.2
  // mrad, translation 0.1 mm), correlated through a random rotation of their whitened space.
  const std::vector<double> sigma = {0.1, 0.1,  0.3,  0.3,  2e-3, 5e-3, 1e-4, 1e-4, 0,    0.15, 0.15, 0.3,
                                     0.3, 2e-3, 5e-3, 1e-4, 1e-4, 0,    2e-4, 2e-4, 2e-4, 0.1,  0.1,  0.1};
  std::mt19937 random(5);
  std::normal_distribution<double> normal;
  cv::Mat mix(g, g, CV_64F);
  for (int i = 0; i < g; ++i) {
    for (int j = 0; j < g; ++j) mix.at<double>(i, j) = normal(random);
  }
  cv::Mat singular_values, q, vt;
  cv::SVD::compute(mix, singular_values, q, vt);  // q: an orthonormal basis
  cv::Mat lambda = cv::Mat::diag(
      (cv::Mat_<double>(1, g) << 0.2, 0.5, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1.5, 1.5, 1.5, 1.5, 2, 2, 2, 2, 3, 3, 3, 4));
  cv::Mat correlation = q * lambda * q.t() / 1.6;
  cv::Mat covariance(g, g, CV_64F);
  for (int i = 0; i < g; ++i) {
    for (int j = 0; j < g; ++j) covariance.at<double>(i, j) = correlation.at<double>(i, j) * sigma[i] * sigma[j];
  }
  const cv::Mat depth = slanted_depth(rig.camera_size);
  const cv::Mat predicted = calibration_depth_sigma(rig, covariance, depth);

  // Rigs drawn from the covariance: sigma_i (q sqrt(lambda / 1.6))_ij times unit normals, each triangulating the
  // same T.
  const transport::CompressedTransport t = plane_transport(rig, depth);
  cv::Mat root_lambda;
  cv::sqrt(lambda / 1.6, root_lambda);
  cv::Mat factor = q * root_lambda;
  for (int i = 0; i < g; ++i) factor.row(i) *= sigma[i];
  constexpr int kDraws = 400;
  cv::Mat sum = cv::Mat::zeros(depth.size(), CV_64F), sum_sq = sum.clone();
  for (int draw = 0; draw < kDraws; ++draw) {
    cv::Mat unit(g, 1, CV_64F);
    for (int i = 0; i < g; ++i) unit.at<double>(i) = normal(random);
    const cv::Mat step = factor * unit;
    std::vector<double> p = p0;
    for (int i = 0; i < g; ++i) p[i] += step.at<double>(i);
    cv::Mat z;
    triangulated_depth(t, rig_of(rig, p)).convertTo(z, CV_64F);
    z -= depth;  // the change, for precision
    sum += z;
    sum_sq += z.mul(z);
  }
  // Over the pixels away from the border: the observed standard deviation over 400 draws has a relative standard error
  // of 1 / sqrt(2 * 399) = 3.5 %; the prediction is first order and interpolated.
  int checked = 0;
  for (int y = 4; y < depth.rows - 4; y += 3) {
    for (int x = 4; x < depth.cols - 4; x += 3) {
      const double mean = sum.at<double>(y, x) / kDraws;
      const double observed = std::sqrt((sum_sq.at<double>(y, x) - kDraws * mean * mean) / (kDraws - 1));
      ASSERT_TRUE(std::isfinite(observed)) << x << ", " << y;
      EXPECT_NEAR(predicted.at<float>(y, x) / observed, 1.0, 0.12) << x << ", " << y << ": " << observed << " mm";
      ++checked;
    }
  }
  EXPECT_GT(checked, 150);
}

TEST(CalibrationSigmaTest, BaselineAloneScalesDepthByItsRelativeError) {
  // Parallel devices side by side: z = f b / d, so a baseline b known to sigma_b gives sigma_z = z sigma_b / b.
  calib::StereoRig rig = small_rig();
  rig.dist_coeffs = cv::Mat::zeros(1, 5, CV_64F);
  rig.projector_dist_coeffs = cv::Mat::zeros(1, 5, CV_64F);
  rig.proj_from_cam_rotation = cv::Mat::eye(3, 3, CV_64F);
  rig.proj_from_cam_translation_mm = (cv::Mat_<double>(3, 1) << -150, 0, 0);
  calib::compute_stereo_geometry(rig);
  const int g = calib::rig_parameter_count(rig);
  cv::Mat covariance = cv::Mat::zeros(g, g, CV_64F);
  const double sigma_b = 0.3;
  covariance.at<double>(g - 3, g - 3) = sigma_b * sigma_b;
  const cv::Mat depth = slanted_depth(rig.camera_size);
  const cv::Mat predicted = calibration_depth_sigma(rig, covariance, depth);
  for (int y = 0; y < depth.rows; y += 7) {
    for (int x = 0; x < depth.cols; x += 7) {
      EXPECT_NEAR(predicted.at<float>(y, x), depth.at<float>(y, x) * sigma_b / 150.0, 1e-3 * predicted.at<float>(y, x))
          << x << ", " << y;
    }
  }
}

TEST(ObservationSigmaTest, PredictsTheSpreadOfDotCentroidsUnderCameraNoise) {
  // Side-by-side devices of equal focal length: the rectified projector column moves one for one with the projector's
  // x, so the column's sigma is the centroid's x sigma.
  calib::StereoRig rig = small_rig();
  rig.dist_coeffs = cv::Mat::zeros(1, 5, CV_64F);
  rig.projector_dist_coeffs = cv::Mat::zeros(1, 5, CV_64F);
  rig.projector_matrix = rig.camera_matrix.clone();
  rig.proj_from_cam_rotation = cv::Mat::eye(3, 3, CV_64F);
  rig.proj_from_cam_translation_mm = (cv::Mat_<double>(3, 1) << -150, 0, 0);
  calib::compute_stereo_geometry(rig);
  const Rectification rectification = depth_rectification(rig, "test rig", false);

  transport::TransportSetup setup;
  setup.camera_size = rig.camera_size;
  setup.projector_size = rig.projector_size;
  setup.dot_spacing = 8;
  transport::CompressedTransport t = transport::make_empty_transport(setup);
  t.camera_noise = {2e-5, 5e-4};  // read sigma 0.0045, shot: 2000 electrons at full scale
  // One camera pixel's spot: the dots around (40.3, 30.6), weights falling off with distance, K of them.
  const std::size_t c = 20 * static_cast<std::size_t>(setup.camera_size.width) + 30;
  const int width = setup.projector_size.width;
  std::vector<int> xs, ys;
  std::vector<double> truth;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      if (static_cast<int>(xs.size()) == t.k()) break;
      xs.push_back(40 + 8 * dx);
      ys.push_back(32 + 8 * dy);
      truth.push_back(
          0.4 * std::exp(-0.02 * ((xs.back() - 40.3) * (xs.back() - 40.3) + (ys.back() - 30.6) * (ys.back() - 30.6))));
    }
  }
  std::mt19937 random(11);
  std::normal_distribution<double> normal;
  constexpr int kDraws = 20000;
  double sum = 0.0, sum_sq = 0.0;
  std::vector<float> first_weights;
  for (int draw = 0; draw < kDraws; ++draw) {
    const double black = std::sqrt(t.camera_noise.variance(0.0)) * normal(random);
    double w_sum = 0.0, x_sum = 0.0;
    std::vector<float> weights;
    for (std::size_t i = 0; i < truth.size(); ++i) {
      const double frame = truth[i] + std::sqrt(t.camera_noise.variance(truth[i])) * normal(random);
      weights.push_back(static_cast<float>(frame - black));
      w_sum += frame - black;
      x_sum += (frame - black) * xs[i];
    }
    if (draw == 0) first_weights = weights;
    sum += x_sum / w_sum;
    sum_sq += (x_sum / w_sum) * (x_sum / w_sum);
  }
  const double mean = sum / kDraws;
  const double observed = std::sqrt((sum_sq - kDraws * mean * mean) / (kDraws - 1));
  // The prediction from one noisy draw's row, as T holds it.
  double w_sum = 0.0, x_sum = 0.0, y_sum = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    t.indices[c * t.k() + i] = ys[i] * width + xs[i];
    t.weights[c * t.k() + i] = first_weights[i];
    w_sum += first_weights[i];
    x_sum += first_weights[i] * xs[i];
    y_sum += first_weights[i] * ys[i];
  }
  t.correspondence[2 * c] = static_cast<float>(x_sum / w_sum);
  t.correspondence[2 * c + 1] = static_cast<float>(y_sum / w_sum);
  const cv::Mat column_sigma = rectified_column_sigma_px(t, rectification);
  ASSERT_FALSE(column_sigma.empty());
  // 20000 draws: 0.5 % standard error; one draw's weights stand in for the true ones (noise 1 to 3 % of them).
  EXPECT_NEAR(column_sigma.at<float>(20, 30) / observed, 1.0, 0.06) << observed << " px";
  EXPECT_TRUE(std::isnan(column_sigma.at<float>(0, 0)));  // no correspondence

  t.camera_noise = {};
  EXPECT_TRUE(rectified_column_sigma_px(t, rectification).empty()) << "no noise model: not known";
}

TEST(CameraNoiseTest, FitRecoversThePhotonTransferLine) {
  const double read = 3e-6, per_signal = 5e-5;
  std::mt19937 random(2);
  std::uniform_real_distribution<double> level(0.2, 3.8);
  std::normal_distribution<double> normal;
  std::vector<capture::NoiseSample> samples;
  for (int i = 0; i < 50000; ++i) {
    const double l = level(random);
    samples.push_back({l, std::sqrt(4 * read + per_signal * l) * normal(random)});
  }
  const capture::CameraNoise noise = capture::fit_camera_noise(samples, 4, 1e-7);
  ASSERT_TRUE(noise.known());
  EXPECT_NEAR(noise.read_variance, read, 0.15 * read);
  EXPECT_NEAR(noise.variance_per_signal, per_signal, 0.05 * per_signal);
  samples.resize(10);
  EXPECT_FALSE(capture::fit_camera_noise(samples, 4, 1e-7).known()) << "too few samples";
}

}  // namespace
}  // namespace rfrecon::depth
