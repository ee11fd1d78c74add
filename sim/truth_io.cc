// The true rig and the objects of a scene, from its devices and shapes.
#include "sim/truth_io.h"

#include <opencv2/core/eigen.hpp>

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
  // The simulator's world frame is the camera's.
  const Eigen::Matrix3d proj_from_cam = scene.projector.device_from_world.linear();
  const Eigen::Vector3d proj_from_cam_t_mm = scene.projector.device_from_world.translation();
  cv::eigen2cv(proj_from_cam, rig.proj_from_cam_rotation);
  cv::eigen2cv(proj_from_cam_t_mm, rig.proj_from_cam_translation_mm);
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

std::vector<truth::TruthObject> truth_objects(const Scene& scene) {
  std::vector<truth::TruthObject> objects;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const Object& object = scene.objects[i];
    const auto [size_mm, rule] = characteristic_size_mm(object);
    objects.push_back({static_cast<int>(i) + 1, object.name, to_string(object.kind), size_mm, rule});
  }
  return objects;
}

}  // namespace rfrecon::sim
