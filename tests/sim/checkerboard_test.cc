// The checkerboard-poses scene is calibratable: every inner corner of every pose is seen by the camera and lit by
// the projector, and OpenCV finds the corners in a rendered white frame where the true model projects them; a
// ray's footprint carries the board's albedo averaged over its area.
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "sim/builtin_scenes.h"
#include "sim/frames.h"
#include "sim/render.h"

namespace rfrecon::sim {
namespace {

std::vector<cv::Point3d> inner_corners_cam(const Scene& scene) {
  const Object& board = scene.objects.at(0);
  const Checkerboard& c = *board.checkerboard;
  std::vector<cv::Point3d> out;
  for (int j = 1; j < c.squares_y; ++j) {
    for (int i = 1; i < c.squares_x; ++i) {
      const Eigen::Vector3d X = board.world_from_object * Eigen::Vector3d((i - c.squares_x / 2.0) * c.square_size,
                                                                          (j - c.squares_y / 2.0) * c.square_size, 0);
      out.emplace_back(X.x(), X.y(), X.z());
    }
  }
  return out;
}

TEST(CheckerboardTest, EveryPoseIsSeenAndLit) {
  // Calibration needs all 126 corners in both images, away from the border (10 px margin for the corner detector's
  // window), and the board facing both devices.
  const Scene scene = builtin_scene("checkerboard-poses");
  ASSERT_EQ(scene.views.size(), 16u);
  for (std::size_t v = 0; v < scene.views.size(); ++v) {
    const Scene view = scene_for_view(scene, v);
    const Eigen::Vector3d normal = view.objects[0].world_from_object.linear().col(2);
    const Eigen::Vector3d centre = view.objects[0].world_from_object.translation();
    EXPECT_GT(std::abs(normal.dot(-centre.normalized())), 0.5) << "view " << v;
    EXPECT_GT(normal.dot(view.projector.centre_world() - centre) * normal.dot(-centre), 0.0) << "view " << v;
    for (const auto& X : inner_corners_cam(view)) {
      for (const Device* device : {&view.camera, &view.projector}) {
        const Eigen::Vector3d X_dev = device->device_from_world * Eigen::Vector3d(X.x, X.y, X.z);
        const Eigen::Vector2d u = project_device_point(*device, X_dev);
        EXPECT_TRUE(u.x() > 10 && u.y() > 10 && u.x() < device->size.width - 10 && u.y() < device->size.height - 10)
            << "view " << v << " corner " << X << " at " << u.transpose();
      }
    }
  }
}

TEST(CheckerboardTest, OpenCvFindsCornersWhereTheModelProjectsThem) {
  // On the anti-aliased 8-bit render of a tilted, distorted view, cornerSubPix scatters around the true
  // projections (measured here: max 0.25 px, 320x240 with 3x3 supersampling; 0.23 px at 640x480, 4x4) but without
  // bias (measured mean offset 0.009 px): max 0.4 px, and a mean offset below 0.03 px, which a half-pixel slip in
  // either device's pixel convention would break.
  Scene scene = scene_for_view(builtin_scene("checkerboard-poses"), 1);
  resize_device(scene.camera, {320, 256});  // half size keeps the test fast; squares are still ~13 px
  RenderOptions options = scene.render;
  options.supersample = 3;
  const auto T = render_transport(scene, options).T;
  const cv::Mat white(scene.projector.size, CV_8U, cv::Scalar(255));
  cv::Mat image;
  transport_image(T, white, scene.camera.size).convertTo(image, CV_8U, 255.0);
  std::vector<cv::Point2f> found;
  ASSERT_TRUE(cv::findChessboardCorners(image, {14, 9}, found));
  cv::cornerSubPix(image, found, {5, 5}, {-1, -1},
                   cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 100, 1e-4));
  std::vector<cv::Point2d> expected;
  cv::projectPoints(inner_corners_cam(scene), cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), scene.camera.camera_matrix(),
                    scene.camera.dist_coeffs(), expected);
  // OpenCV may report the grid from either end; match the order to the model's.
  if (cv::norm(cv::Point2d(found.front()) - expected.front()) >
      cv::norm(cv::Point2d(found.front()) - expected.back())) {
    std::reverse(found.begin(), found.end());
  }
  double worst = 0;
  cv::Point2d mean_offset(0, 0);
  for (std::size_t i = 0; i < found.size(); ++i) {
    worst = std::max(worst, cv::norm(cv::Point2d(found[i]) - expected[i]));
    mean_offset += (cv::Point2d(found[i]) - expected[i]) / static_cast<double>(found.size());
  }
  RecordProperty("max_corner_error_px", std::to_string(worst));
  RecordProperty("mean_corner_offset_px", std::to_string(cv::norm(mean_offset)));
  EXPECT_LT(worst, 0.4);
  EXPECT_LT(cv::norm(mean_offset), 0.03);
}

// A 4 x 3-square board of 10 mm squares (dark 0.1, light 0.7) on a white (0.9) plate, turned and moved.
Object turned_board() {
  Object board;
  board.material.diffuse = 0.9;
  board.checkerboard = Checkerboard{4, 3, 10.0, 0.1, 0.7};
  board.world_from_object =
      Eigen::Translation3d(5.0, -3.0, 400.0) * Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.3, 1.0, 0.2).normalized());
  return board;
}

// The albedo over the footprint centred at board point (x, y) mm with board-frame edges `du`, `dv` (mm).
double albedo_over(const Object& board, double x, double y, const Eigen::Vector3d& du, const Eigen::Vector3d& dv) {
  Hit hit;
  hit.position = board.world_from_object * Eigen::Vector3d(x, y, 0.0);
  hit.diffuse = -1.0;  // the point sample, which a footprint on a board never returns
  const Eigen::Matrix3d R = board.world_from_object.linear();
  return footprint_diffuse(board, hit, R * du, R * dv);
}

TEST(CheckerboardTest, FootprintAlbedoIsTheAreaAverage) {
  const Object board = turned_board();
  const Eigen::Vector3d du(2.0, 0.0, 0.0), dv(0.0, 1.0, 0.0);
  // Squares span x in [-20, 20], y in [-15, 15]; the square at (-20, -15) is dark.
  EXPECT_NEAR(albedo_over(board, -15.0, -10.0, du, dv), 0.1, 1e-12) << "inside a dark square";
  EXPECT_NEAR(albedo_over(board, -5.0, -10.0, du, dv), 0.7, 1e-12) << "inside a light square";
  EXPECT_NEAR(albedo_over(board, -10.0, -10.0, du, dv), 0.4, 1e-12) << "centred on an edge";
  EXPECT_NEAR(albedo_over(board, -9.5, -10.0, du, dv), 0.1 * 0.25 + 0.7 * 0.75, 1e-12) << "a quarter on the dark side";
  EXPECT_NEAR(albedo_over(board, 0.0, -5.0, du, dv), 0.4, 1e-12) << "centred on an inner corner";
  EXPECT_NEAR(albedo_over(board, -20.0, -10.0, du, dv), 0.5 * (0.1 + 0.9), 1e-12) << "half on the plate";
  EXPECT_NEAR(albedo_over(board, -20.0, -15.0, du, dv), 0.25 * 0.1 + 0.75 * 0.9, 1e-12) << "a quarter on the board";
  Hit outside;
  outside.diffuse = 0.9;
  EXPECT_EQ(footprint_diffuse(Object{}, outside, du, dv), 0.9) << "no checkerboard: the point's albedo";

  // A skewed footprint is averaged over its bounding box: compare with a 2000 x 2000 midpoint sum over that box.
  const Eigen::Vector3d skew_u(1.3, 0.8, 0.0), skew_v(-0.5, 2.1, 0.0);
  const double cx = 9.1, cy = 4.2, hx = 0.5 * (1.3 + 0.5), hy = 0.5 * (0.8 + 2.1);
  const int n = 2000;
  double sum = 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = cx - hx + (i + 0.5) * 2.0 * hx / n, y = cy - hy + (j + 0.5) * 2.0 * hy / n;
      const long ix = static_cast<long>(std::floor(x / 10.0 + 2.0)), iy = static_cast<long>(std::floor(y / 10.0 + 1.5));
      sum += (ix + iy) % 2 == 0 ? 0.1 : 0.7;
    }
  }
  EXPECT_NEAR(albedo_over(board, cx, cy, skew_u, skew_v), sum / (n * n), 1e-3);
}

}  // namespace
}  // namespace rfrecon::sim
