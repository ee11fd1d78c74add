// Ground-truth files: OpenCV images for the maps, binary PLY for the points, the rig YAML for the calibration.
#include "sim/truth_io.h"

#include <cmath>
#include <fstream>

#include <opencv2/core/eigen.hpp>
#include <opencv2/imgcodecs.hpp>

#include "host/common/atomic_file.h"

namespace rfrecon::sim {

namespace fs = std::filesystem;

calib::StereoRig true_rig(const Scene& scene) {
  calib::StereoRig rig;
  rig.camera_size = scene.camera.size;
  rig.projector_size = scene.projector.size;
  rig.camera_matrix = scene.camera.camera_matrix();
  rig.dist_coeffs = scene.camera.dist_coeffs();
  rig.projector_matrix = scene.projector.camera_matrix();
  rig.projector_dist_coeffs = scene.projector.dist_coeffs();
  const Eigen::Matrix3d R = scene.projector.device_from_world.linear();
  const Eigen::Vector3d t = scene.projector.device_from_world.translation();
  cv::eigen2cv(R, rig.R);
  cv::eigen2cv(t, rig.T);
  for (const auto& object : scene.objects) {
    if (object.checkerboard) {
      rig.board = {object.checkerboard->squares_x - 1, object.checkerboard->squares_y - 1,
                   object.checkerboard->square_size};
      break;
    }
  }
  calib::compute_stereo_geometry(rig);
  return rig;
}

namespace {
// Float TIFFs are written uncompressed: OpenCV 4.6 corrupts multi-channel float TIFFs with its default LZW.
void write_image(const fs::path& file, const cv::Mat& image) {
  const std::vector<int> params{cv::IMWRITE_TIFF_COMPRESSION, 1};
  if (!cv::imwrite(file.string(), image, image.depth() == CV_32F ? params : std::vector<int>{})) {
    throw std::runtime_error("cannot write " + file.string());
  }
}
}  // namespace

void write_points_ply(const GroundTruth& truth, const fs::path& file) {
  std::string body;
  std::size_t count = 0;
  for (int y = 0; y < truth.depth_mm.rows; ++y) {
    for (int x = 0; x < truth.depth_mm.cols; ++x) {
      if (!std::isfinite(truth.depth_mm.at<float>(y, x))) continue;
      const cv::Vec3f p = truth.points_mm.at<cv::Vec3f>(y, x), n = truth.normals.at<cv::Vec3f>(y, x);
      const float values[6] = {p[0], p[1], p[2], n[0], n[1], n[2]};
      body.append(reinterpret_cast<const char*>(values), sizeof values);  // x86/ARM hosts are little-endian
      ++count;
    }
  }
  const std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment rfrecon synthetic ground truth, camera "
      "frame, mm\nelement vertex " +
      std::to_string(count) +
      "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty "
      "float ny\nproperty float nz\nend_header\n";
  write_file_atomically(file, header + body);
}

void write_ground_truth(const GroundTruth& truth, const fs::path& dir) {
  write_image(dir / "depth.tiff", truth.depth_mm);
  write_image(dir / "normals.tiff", truth.normals);
  write_image(dir / "visibility.png", truth.visible);
  write_image(dir / "shadow.png", truth.shadow);
  // cv::imwrite cannot write 2-channel images: the (x, y) pair is padded with a zero third channel.
  cv::Mat padded;
  cv::merge(std::vector<cv::Mat>{truth.correspondence, cv::Mat::zeros(truth.correspondence.size(), CV_32FC1)}, padded);
  write_image(dir / "correspondences.tiff", padded);
  write_image(dir / "object_id.png", truth.object_id);
  write_points_ply(truth, dir / "points.ply");
}

}  // namespace rfrecon::sim
