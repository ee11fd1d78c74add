// Ground-truth files: OpenCV images for the maps, binary PLY for the points, the rig YAML for the calibration.
#include "sim/truth_io.h"

#include <opencv2/core/eigen.hpp>

#include "host/common/image_file.h"
#include "host/common/ply.h"

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

void write_points_ply(const GroundTruth& truth, const fs::path& file) {
  write_point_cloud_ply(file, "rfrecon synthetic ground truth, camera frame, mm", truth.points_mm, truth.normals);
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
