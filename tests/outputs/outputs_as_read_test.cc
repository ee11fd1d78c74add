// Outputs as users read them, on a scan rendered through a distorting lens (k1 = -0.08, the built-in rigs' camera):
// points.tiff, depth.tiff back-projected with summary.json's intrinsics and distortion, and the PLY give the same
// points; a pinhole back-projection does not; normals.tiff holds nx first; the PLY's colours follow the white frame;
// summary.json records every option.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <regex>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>

#include "calib/rig.h"
#include "host/capture/manifest.h"
#include "host/pipeline/reconstruct_scan.h"
#include "host/transport/compute_transport.h"
#include "host/transport/graycode_accumulator.h"
#include "host/transport/transport_file.h"
#include "sim/frames.h"
#include "sim/render.h"
#include "sim/truth_io.h"
#include "tests/common/devices.h"
#include "tests/common/ply_reader.h"
#include "tests/common/run_cli.h"
#include "tests/common/temp_dir.h"
#include "tests/common/tiff_reader.h"
#include "tests/sim/test_scenes.h"

namespace rfrecon {
namespace {

namespace fs = std::filesystem;

// The three readings of a point agree to float32 rounding: coordinates of ~600 mm hold 6e-5 mm, and the depth stage
// keeps each pixel's undistorted position in float32 (1e-5 px, 6e-5 mm at f = 100 px): 1e-3 mm leaves a margin.
constexpr double kSamePointMm = 1e-3;

// The small test rig (80x60, f = 100 px) with the built-in rigs' camera distortion: 1 px at the image corners.
sim::Scene distorted_scene() {
  nlohmann::json json = sim::testing::small_rig({sim::testing::tilted_plane(sim::testing::kLambert)});
  json["camera"]["distortion"] = {-0.08, 0.05, 0.0005, -0.0003, 0.0};
  sim::Scene scene = sim::testing::make_scene(json);
  scene.capture.dot_spacing = 5;
  return scene;
}

// Rendered, turned into T.h5 and reconstructed (triangulation, the true rig) once for the suite.
struct Scan {
  rfrecon::testing::TempDir dir{"outputs_as_read"};
  cv::Mat truth_normals;
  fs::path out() const { return dir.path() / "out"; }
};

class OutputsAsReadTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scan_ = std::make_unique<Scan>();
    const fs::path& dir = scan_->dir.path();
    const sim::Scene scene = distorted_scene();
    const auto rendered = sim::render_transport(scene);
    scan_->truth_normals = rendered.truth.normals;
    fs::create_directories(dir / "capture");
    sim::write_capture(rendered.T, scene.capture, scene.camera.size, scene.projector.size, 1, 2, dir / "capture");
    const auto transport =
        transport::compute_transport(dir / "capture", capture::read_manifest(dir / "capture"), {},
                                     [](const auto& setup) { return transport::make_reference_accumulator(setup); })
            .transport;
    transport::write_transport(transport, dir / "T.h5");
    calib::write_rig(sim::true_rig(scene), dir / "rig.yaml");
    pipeline::ReconstructRequest request;
    request.transport = dir / "T.h5";
    request.rig = dir / "rig.yaml";
    request.out_dir = scan_->out();
    request.depth.method = "triangulate";
    std::vector<cl::DeviceContext> devices{rfrecon::testing::first_device()};
    cl::ProgramCache programs;
    pipeline::reconstruct_scan(request, devices, programs);
  }
  static void TearDownTestSuite() { scan_.reset(); }

  static std::unique_ptr<Scan> scan_;
};

std::unique_ptr<Scan> OutputsAsReadTest::scan_;

nlohmann::json read_summary(const fs::path& dir) {
  std::ifstream in(dir / "summary.json");
  return nlohmann::json::parse(in);
}

double largest_difference(const cv::Vec3d& a, const cv::Vec3d& b) {
  return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

TEST_F(OutputsAsReadTest, PointsTiffDepthTiffAndPlyGiveTheSamePoints) {
  const nlohmann::json camera = read_summary(scan_->out()).at("camera");
  ASSERT_EQ(camera.at("image_size"), nlohmann::json({80, 60}));
  ASSERT_EQ(camera.at("dist_coeffs_names"), nlohmann::json({"k1", "k2", "p1", "p2", "k3"}));
  cv::Matx33d K;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) K(row, col) = camera.at("camera_matrix").at(row).at(col).get<double>();
  }
  const auto dist = camera.at("dist_coeffs").get<std::vector<double>>();
  EXPECT_EQ(dist[0], -0.08);

  const auto points = testing::read_float_tiff(scan_->out() / "points.tiff");
  const auto depth = testing::read_float_tiff(scan_->out() / "depth.tiff");
  ASSERT_EQ(points.samples, 3);
  ASSERT_EQ(depth.samples, 1);
  ASSERT_EQ(points.width, 80u);
  ASSERT_EQ(depth.height, 60u);

  // depth.tiff back-projected: each pixel undistorted to convergence, its ray scaled to the depth.
  std::vector<cv::Point2d> pixels;
  for (std::uint32_t y = 0; y < depth.height; ++y) {
    for (std::uint32_t x = 0; x < depth.width; ++x) {
      if (std::isfinite(depth.at(x, y, 0))) pixels.emplace_back(x, y);
    }
  }
  ASSERT_GT(pixels.size(), 2000u) << "most of the plane is reconstructed";
  std::vector<cv::Point2d> rays;
  cv::undistortPoints(pixels, rays, K, dist, cv::noArray(), cv::noArray(),
                      {cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-12});
  double depth_off = 0.0, pinhole_off = 0.0;
  std::size_t points_finite = 0;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const auto x = static_cast<std::uint32_t>(pixels[i].x), y = static_cast<std::uint32_t>(pixels[i].y);
    const double z = depth.at(x, y, 0);
    const cv::Vec3d from_tiff(points.at(x, y, 0), points.at(x, y, 1), points.at(x, y, 2));
    const cv::Vec3d from_depth(z * rays[i].x, z * rays[i].y, z);
    const cv::Vec3d pinhole(z * (x - K(0, 2)) / K(0, 0), z * (y - K(1, 2)) / K(1, 1), z);
    depth_off = std::max(depth_off, largest_difference(from_tiff, from_depth));
    pinhole_off = std::max(pinhole_off, largest_difference(from_tiff, pinhole));
    points_finite += std::isfinite(from_tiff[0]) ? 1 : 0;
  }
  EXPECT_EQ(points_finite, pixels.size()) << "a point wherever there is depth";
  std::printf("points.tiff against depth.tiff back-projected: %.2e mm; against a pinhole back-projection: %.3f mm\n",
              depth_off, pinhole_off);
  EXPECT_LT(depth_off, kSamePointMm);
  EXPECT_GT(pinhole_off, 1.0) << "a pinhole back-projection ignores the lens: mm off at the image's edges";

  // The PLY: one vertex per point, at its pixel (u, v).
  const auto ply = testing::read_ply_vertices(scan_->out() / "points.ply");
  ASSERT_EQ(ply.count, pixels.size());
  double ply_off = 0.0;
  for (std::size_t v = 0; v < ply.count; ++v) {
    const auto x = static_cast<std::uint32_t>(ply.at(v, 6)), y = static_cast<std::uint32_t>(ply.at(v, 7));
    ply_off = std::max(ply_off, largest_difference({ply.at(v, 0), ply.at(v, 1), ply.at(v, 2)},
                                                   {points.at(x, y, 0), points.at(x, y, 1), points.at(x, y, 2)}));
  }
  EXPECT_LT(ply_off, kSamePointMm);
}

// summary.json's options name every option of `rfrecon reconstruct --help`, each with the value the run used.
TEST_F(OutputsAsReadTest, SummaryRecordsEveryCommandLineOption) {
  const nlohmann::json options = read_summary(scan_->out()).at("options");
  const auto help = testing::run_cli("reconstruct --help");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  const std::regex option_name("--([a-z][a-z-]*)");
  std::size_t named = 0;
  for (auto match = std::sregex_iterator(help.output.begin(), help.output.end(), option_name);
       match != std::sregex_iterator(); ++match) {
    if ((*match)[1] == "help") continue;
    EXPECT_TRUE(options.contains((*match)[1].str())) << (*match)[1];
    ++named;
  }
  EXPECT_GT(named, 15u);
  EXPECT_EQ(options.at("method"), "triangulate");
  EXPECT_EQ(options.at("saturation"), 0.97);  // the default, as typed, not as float32 rounds it
  EXPECT_EQ(options.at("devices").size(), 1u);
}

// normals.tiff as libtiff reads it: (nx, ny, nz) in samples 0, 1, 2, within a few degrees of the rendered plane's
// normal (median over the pixels); the samples in reverse order (OpenCV's BGR) are far off.
TEST_F(OutputsAsReadTest, NormalsTiffHoldsNxFirst) {
  const auto normals = testing::read_float_tiff(scan_->out() / "normals.tiff");
  ASSERT_EQ(normals.samples, 3);
  const auto median_angle_deg = [&](int first, int third) {
    std::vector<double> angles;
    for (std::uint32_t y = 0; y < normals.height; ++y) {
      for (std::uint32_t x = 0; x < normals.width; ++x) {
        const cv::Vec3d truth = scan_->truth_normals.at<cv::Vec3f>(static_cast<int>(y), static_cast<int>(x));
        const cv::Vec3d n(normals.at(x, y, first), normals.at(x, y, 1), normals.at(x, y, third));
        if (!std::isfinite(n[0]) || !std::isfinite(truth[0])) continue;
        angles.push_back(std::acos(std::clamp(n.dot(truth) / cv::norm(n) / cv::norm(truth), -1.0, 1.0)) * 180.0 /
                         CV_PI);
      }
    }
    EXPECT_GT(angles.size(), 2000u);
    std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
    return angles[angles.size() / 2];
  };
  const double in_order = median_angle_deg(0, 2), reversed = median_angle_deg(2, 0);
  std::printf("normals.tiff against the truth: median %.2f deg; samples reversed: %.1f deg\n", in_order, reversed);
  EXPECT_LT(in_order, 5.0);
  EXPECT_GT(reversed, 30.0);
}

// The PLY's colour is the white frame T.h5 keeps: grey, and never darker where the white frame is brighter; the lit
// plane's white varies enough to span many grey levels.
TEST_F(OutputsAsReadTest, PlyColoursFollowTheWhiteFrame) {
  const auto transport = transport::read_transport(scan_->dir.path() / "T.h5");
  ASSERT_EQ(transport.white.size(), 80u * 60u);
  const auto ply = testing::read_ply_vertices(scan_->out() / "points.ply");
  ASSERT_EQ(ply.properties.size(), 15u);
  ASSERT_EQ(ply.properties[12], "red");
  std::vector<std::pair<float, float>> white_and_grey;
  for (std::size_t v = 0; v < ply.count; ++v) {
    ASSERT_EQ(ply.at(v, 12), ply.at(v, 13));
    ASSERT_EQ(ply.at(v, 12), ply.at(v, 14));
    const auto c = static_cast<std::size_t>(ply.at(v, 7)) * 80 + static_cast<std::size_t>(ply.at(v, 6));
    white_and_grey.emplace_back(transport.white[c], ply.at(v, 12));
  }
  std::sort(white_and_grey.begin(), white_and_grey.end());
  for (std::size_t i = 1; i < white_and_grey.size(); ++i) {
    ASSERT_GE(white_and_grey[i].second, white_and_grey[i - 1].second)
        << "white " << white_and_grey[i].first << " after " << white_and_grey[i - 1].first;
  }
  EXPECT_GT(white_and_grey.back().second - white_and_grey.front().second, 10.0f);
}

// Each point's depth sigma is in the PLY as the float TIFFs hold it, pixel for pixel: the total, then its calibration
// and observation parts (a true rig: the calibration's is 0 and the total is the observation's).
TEST_F(OutputsAsReadTest, PlyDepthSigmaIsTheTiffsAtEachPixel) {
  const auto ply = testing::read_ply_vertices(scan_->out() / "points.ply");
  const char* names[] = {"depth_sigma", "depth_sigma_calibration", "depth_sigma_observation"};
  std::size_t compared = 0;
  for (int part = 0; part < 3; ++part) {
    ASSERT_EQ(ply.properties[9 + part], names[part]);
    const auto tiff = testing::read_float_tiff(scan_->out() / (std::string(names[part]) + ".tiff"));
    ASSERT_EQ(tiff.samples, 1);
    for (std::size_t v = 0; v < ply.count; ++v) {
      const auto x = static_cast<std::uint32_t>(ply.at(v, 6)), y = static_cast<std::uint32_t>(ply.at(v, 7));
      const float in_ply = ply.at(v, 9 + part), in_tiff = tiff.at(x, y, 0);
      ASSERT_TRUE(in_ply == in_tiff || (std::isnan(in_ply) && std::isnan(in_tiff))) << names[part] << " at " << x;
      if (part == 1) {
        EXPECT_EQ(in_ply, 0.0f);
      }
      compared += std::isfinite(in_ply) ? 1 : 0;
    }
  }
  EXPECT_GT(compared, 1000u);
}

}  // namespace
}  // namespace rfrecon
