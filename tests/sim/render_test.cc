// Physical checks of the rendered transport matrix and ground truth: exact plane depth, the Lambertian closed form,
// Helmholtz reciprocity against the swapped rig, hard shadows, correspondence centroids and determinism.
#include "sim/render.h"

#include <cmath>
#include <cstring>
#include <functional>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/sim/test_scenes.h"

namespace rfrecon::sim {
namespace {

using testing::kLambert;
using testing::make_scene;
using testing::small_rig;
using testing::tilted_plane;

const nlohmann::json kWard{{"brdf", "ward"}, {"diffuse", 0.2}, {"specular", 0.5}, {"alpha_x", 0.08}, {"alpha_y", 0.3}};

TEST(RenderTest, PlaneDepthIsExact) {
  // Depth of a plane n.X = d along the ray (x, y, 1) of each pixel centre is d / n.(x, y, 1), with (x, y) from
  // cv::undistortPoints on a distorted camera. Stored as float32: 1e-6 relative is ~10 ulps at 600 mm.
  auto json = small_rig({tilted_plane(kLambert)});
  json["camera"]["distortion"] = {-0.1, 0.05, 0.001, 0.0, 0.0};
  const Scene scene = make_scene(json);
  RenderOptions options;
  options.supersample = 1;
  const auto truth = render_transport(scene, options).truth;
  const Eigen::Vector3d n = scene.objects[0].world_from_object.linear().col(2);
  const double d = n.dot(scene.objects[0].world_from_object.translation());
  std::vector<cv::Point2d> pixels, normalized;
  for (int y = 0; y < 60; ++y) {
    for (int x = 0; x < 80; ++x) pixels.emplace_back(x, y);
  }
  cv::undistortPoints(pixels, normalized, scene.camera.camera_matrix(), scene.camera.dist_coeffs(), cv::noArray(),
                      cv::noArray(), cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-15));
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const double expected = d / n.dot(Eigen::Vector3d(normalized[i].x, normalized[i].y, 1.0));
    const float got = truth.depth_mm.at<float>(static_cast<int>(pixels[i].y), static_cast<int>(pixels[i].x));
    ASSERT_NEAR(got, expected, 1e-6 * expected) << "pixel " << pixels[i];
  }
}

TEST(RenderTest, LambertianPlaneMatchesClosedForm) {
  // With every projector pixel lit, a fully lit camera pixel reads gain * intensity * (rho / pi) * cos_p / d_p^2
  // averaged over the pixel. Evaluated at the pixel centre's surface point, the average differs only by the
  // curvature of that function over one pixel (relative (1 px / 100 px)^2 ~ 1e-4), so 1e-3 relative.
  const Scene scene = make_scene(small_rig({tilted_plane(kLambert)}));
  const auto transport = render_transport(scene);
  const Eigen::VectorXf row_sums = transport.T * Eigen::VectorXf::Ones(transport.T.cols());
  const Eigen::Vector3d o_p = scene.projector.centre_world();
  int checked = 0;
  for (int y = 1; y < 59; ++y) {
    for (int x = 1; x < 79; ++x) {
      const cv::Vec2f u = transport.truth.correspondence.at<cv::Vec2f>(y, x);
      if (!(u[0] > 3 && u[1] > 3 && u[0] < 76 && u[1] < 56)) continue;  // whole footprint inside the projector
      const cv::Vec3f p = transport.truth.points_mm.at<cv::Vec3f>(y, x);
      const cv::Vec3f nv = transport.truth.normals.at<cv::Vec3f>(y, x);
      const Eigen::Vector3d X(p[0], p[1], p[2]), n(nv[0], nv[1], nv[2]);
      const double d_p = (o_p - X).norm();
      const double expected = scene.gain * scene.intensity * 0.6 / EIGEN_PI * n.dot((o_p - X) / d_p) / (d_p * d_p);
      ASSERT_NEAR(row_sums[y * 80 + x], expected, 1e-3 * expected) << "pixel " << x << "," << y;
      ++checked;
    }
  }
  EXPECT_GT(checked, 2000);
}

// Block sums of a camera x projector matrix over b x b pixel blocks on both sides.
Eigen::MatrixXd block_sums(const TransportMatrix& T, cv::Size camera, cv::Size projector, int b,
                           const std::function<double(int, int, double)>& value) {
  const int cam_bx = camera.width / b, cam_by = camera.height / b;
  const int proj_bx = projector.width / b, proj_by = projector.height / b;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(cam_bx * cam_by, proj_bx * proj_by);
  for (int c = 0; c < T.outerSize(); ++c) {
    for (TransportMatrix::InnerIterator it(T, c); it; ++it) {
      const int p = static_cast<int>(it.col());
      const int cb = (c / camera.width / b) * cam_bx + (c % camera.width) / b;
      const int pb = (p / projector.width / b) * proj_bx + (p % projector.width) / b;
      out(cb, pb) += value(c, p, it.value());
    }
  }
  return out;
}

double pixel_solid_angle_at(const Device& d, int index) {
  const Eigen::Vector2d xy(((index % d.size.width) - d.cx) / d.fx, ((index / d.size.width) - d.cy) / d.fy);
  return pixel_solid_angle(d, xy);
}

TEST(RenderTest, SwappedRigTransportIsTransposeScaledBySolidAngles) {
  // Helmholtz reciprocity: for the rig with camera and projector exchanged, T_swapped[p, c] = T[c, p] *
  // Omega_c / Omega_p (pixel solid angles; docs/sim.md derives it). Entry by entry the two renders discretise
  // differently (camera sub-pixels vs projector sub-pixels, box footprints), so compare 4x4-pixel blocks on both
  // sides, where only block-boundary pixels differ: measured relative Frobenius error 0.09% with 4x4 supersampling;
  // 0.5% bounds it with margin while still failing for any missing cosine, distance or solid-angle factor (>5%). An
  // anisotropic Ward plane checks that the BRDF's tangent frame is reciprocal too.
  const Scene scene = make_scene(small_rig({tilted_plane(kWard)}));
  const Scene swapped = swap_devices(scene);
  const auto T = render_transport(scene).T;
  const auto T_swapped = render_transport(swapped).T;
  const int b = 4;
  const Eigen::MatrixXd scaled = block_sums(T, scene.camera.size, scene.projector.size, b, [&](int c, int p, double v) {
    return v * pixel_solid_angle_at(scene.camera, c) / pixel_solid_angle_at(scene.projector, p);
  });
  const Eigen::MatrixXd reciprocal =
      block_sums(T_swapped, swapped.camera.size, swapped.projector.size, b, [](int, int, double v) { return v; });
  const double error = (scaled - reciprocal.transpose()).norm() / scaled.norm();
  RecordProperty("relative_block_error", std::to_string(error));
  EXPECT_LT(error, 0.005);
  EXPECT_GT(scaled.norm(), 0.0);
}

TEST(RenderTest, ShadowedPixelsReceiveNoLight) {
  // A box in front of a wall casts a projector shadow; a camera pixel whose neighbourhood is all in shadow (so its
  // whole footprint is) must have an empty row: no direct light can reach it.
  const nlohmann::json box{{"name", "box"},
                           {"shape", "box"},
                           {"size", {60.0, 60.0, 60.0}},
                           {"pose", {{"position", {0.0, 0.0, 550.0}}, {"rotation_deg", {20.0, 30.0, 0.0}}}},
                           {"material", kWard}};
  const nlohmann::json wall{
      {"name", "wall"}, {"shape", "plane"}, {"pose", {{"position", {0.0, 0.0, 700.0}}}}, {"material", kLambert}};
  const Scene scene = make_scene(small_rig({box, wall}));
  const auto transport = render_transport(scene);
  cv::Mat fully_shadowed;
  cv::erode(transport.truth.shadow, fully_shadowed, cv::Mat::ones(3, 3, CV_8U));
  int shadowed = 0;
  for (int y = 0; y < 60; ++y) {
    for (int x = 0; x < 80; ++x) {
      if (fully_shadowed.at<uchar>(y, x) == 0 || transport.truth.visible.at<uchar>(y, x) == 0) continue;
      EXPECT_EQ(transport.T.row(y * 80 + x).nonZeros(), 0) << "pixel " << x << "," << y;
      ++shadowed;
    }
  }
  EXPECT_GT(shadowed, 20);
}

TEST(RenderTest, RowCentroidMatchesCorrespondence) {
  // The weighted centroid of a lit row, in projector pixel indices, is the footprint centre up to pixel
  // quantisation: for a box of width w px the index-weighted mean differs from the box centre by at most
  // frac(w)(1 - frac(w)) / (2w) per axis: <= 1/8 px for w >= 1, 0.16 px for w = 0.7 (the narrowest footprint here,
  // toe-in and tilt make them 0.7-1.5 px); 0.2 px adds margin for the supersampled footprint.
  // The quantisation error averages out over many pixels, so the mean offset must be ~0: 0.01 px catches any
  // half-pixel convention error (pixel x covers [x - 0.5, x + 0.5] on both devices).
  const Scene scene = make_scene(small_rig({tilted_plane(kLambert)}));
  const auto transport = render_transport(scene);
  Eigen::Vector2d mean_offset = Eigen::Vector2d::Zero();
  int checked = 0;
  for (int y = 0; y < 60; ++y) {
    for (int x = 0; x < 80; ++x) {
      const cv::Vec2f u = transport.truth.correspondence.at<cv::Vec2f>(y, x);
      if (!(u[0] > 3 && u[1] > 3 && u[0] < 76 && u[1] < 56)) continue;
      double sum = 0, sx = 0, sy = 0;
      for (TransportMatrix::InnerIterator it(transport.T, y * 80 + x); it; ++it) {
        sum += it.value();
        sx += it.value() * static_cast<double>(it.col() % 80);
        sy += it.value() * static_cast<double>(it.col() / 80);
      }
      const Eigen::Vector2d offset(sx / sum - u[0], sy / sum - u[1]);
      ASSERT_LT(offset.cwiseAbs().maxCoeff(), 0.2) << "pixel " << x << "," << y;
      mean_offset += offset;
      ++checked;
    }
  }
  ASSERT_GT(checked, 2000);
  mean_offset /= checked;
  RecordProperty("mean_offset_px", std::to_string(mean_offset.cwiseAbs().maxCoeff()));
  EXPECT_LT(mean_offset.cwiseAbs().maxCoeff(), 0.01) << mean_offset.transpose();
}

TEST(RenderTest, DeterministicAcrossThreadCounts) {
  // Rows are independent and interreflection samples are seeded per pixel: 1 and 3 threads give identical bits.
  auto json = small_rig({tilted_plane(kWard)});
  json["render"] = {{"interreflection_samples", 2}, {"projector_defocus_px", 0.7}};
  const Scene scene = make_scene(json);
  RenderOptions one = scene.render, three = scene.render;
  one.threads = 1;
  three.threads = 3;
  const auto a = render_transport(scene, one).T, b = render_transport(scene, three).T;
  ASSERT_EQ(a.nonZeros(), b.nonZeros());
  EXPECT_EQ(0, std::memcmp(a.valuePtr(), b.valuePtr(), sizeof(float) * a.nonZeros()));
  EXPECT_EQ(0, std::memcmp(a.innerIndexPtr(), b.innerIndexPtr(), sizeof(int) * a.nonZeros()));
}

TEST(RenderTest, DefocusSpreadsButKeepsEnergy) {
  // A Gaussian PSF redistributes light: row sums of fully lit interior pixels stay within 1% (the plane's reading
  // varies slowly across the PSF), while rows get wider (more non-zeros).
  auto json = small_rig({tilted_plane(kLambert)});
  const Scene sharp_scene = make_scene(json);
  json["render"] = {{"projector_defocus_px", 1.0}, {"camera_defocus_px", 0.8}};
  const Scene blurred_scene = make_scene(json);
  const auto sharp = render_transport(sharp_scene), blurred = render_transport(blurred_scene);
  const Eigen::VectorXf ones = Eigen::VectorXf::Ones(sharp.T.cols());
  const Eigen::VectorXf a = sharp.T * ones, b = blurred.T * ones;
  for (int y = 10; y < 50; ++y) {
    for (int x = 10; x < 70; ++x) {
      const cv::Vec2f u = sharp.truth.correspondence.at<cv::Vec2f>(y, x);
      if (!(u[0] > 8 && u[1] > 8 && u[0] < 71 && u[1] < 51)) continue;
      ASSERT_NEAR(b[y * 80 + x], a[y * 80 + x], 0.01 * a[y * 80 + x]);
    }
  }
  EXPECT_GT(blurred.T.nonZeros(), 4 * sharp.T.nonZeros());
}

}  // namespace
}  // namespace rfrecon::sim
