// Renders each view of a scene and writes captures, ground truth and the resolved scene through a staging directory.
#include "sim/simulate.h"

#include <cstdio>
#include <optional>
#include <thread>

#include <spdlog/spdlog.h>

#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/output_path.h"
#include "host/core/progress.h"
#include "sim/frames.h"
#include "sim/render.h"
#include "sim/truth_io.h"

namespace rfrecon::sim {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
// The 3D inner corners of the first checkerboard (camera frame, mm), row by row as OpenCV orders them.
json board_corners(const Scene& scene) {
  for (const auto& object : scene.objects) {
    if (!object.checkerboard) continue;
    const Checkerboard& b = *object.checkerboard;
    json corners = json::array();
    for (int j = 1; j < b.squares_y; ++j) {
      for (int i = 1; i < b.squares_x; ++i) {
        const Eigen::Vector3d local((i - b.squares_x / 2.0) * b.square_size, (j - b.squares_y / 2.0) * b.square_size,
                                    0.0);
        const Eigen::Vector3d X = object.world_from_object * local;
        corners.push_back({X.x(), X.y(), X.z()});
      }
    }
    const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> R = object.world_from_object.linear();
    const Eigen::Vector3d t = object.world_from_object.translation();
    return {{"object", object.name},
            {"cam_from_board_rotation", std::vector<double>(R.data(), R.data() + 9)},
            {"cam_from_board_translation_mm", {t.x(), t.y(), t.z()}},
            {"inner_corners_cam_mm", corners}};
  }
  return nullptr;
}

std::string view_name(std::size_t view) {
  char name[32];
  std::snprintf(name, sizeof name, "pose_%02zu", view);
  return name;
}

// Renders one view and writes its capture and ground-truth maps; `rays` as for render_transport.
void render_view(const Scene& scene, int threads, const CameraRays* rays, const std::string& label,
                 const fs::path& capture_dir, const fs::path& truth_dir) {
  RenderOptions render = scene.render;
  render.threads = threads;
  Transport transport;
  {
    Progress progress(label + ": transport", static_cast<std::size_t>(scene.camera.size.height), "rows");
    transport = render_transport(scene, render, rays, &progress);
  }
  spdlog::debug("{}: T is {}x{} with {} non-zeros", label, transport.T.rows(), transport.T.cols(),
                transport.T.nonZeros());
  fs::create_directories(capture_dir);
  fs::create_directories(truth_dir);
  const auto frames = make_manifest(scene.capture, scene.camera.size, scene.projector.size).frames.size();
  Progress progress(label + ": frames", frames, "frames");
  write_capture(transport.T, scene.capture, scene.camera.size, scene.projector.size, scene.render.seed, threads,
                capture_dir, &progress);
  truth::write_truth(truth_dir, transport.truth, truth_objects(scene));
}
}  // namespace

void simulate(const Scene& scene, const fs::path& out_dir, const SimulateOptions& options) {
  const int threads =
      options.threads > 0 ? options.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  check_output_directory({out_dir, "--output", options.force}, options.inputs);
  StagingDirectory staging(out_dir, options.force);
  const fs::path root = staging.path();
  if (scene.views.empty()) {
    render_view(scene, threads, nullptr, scene.name, root / "capture", root / "truth");
    calib::write_rig(true_rig(scene), root / "truth" / "rig.yaml");
  } else {
    // The views move objects in front of one camera: without jitter they trace the same rays, undistorted once.
    std::optional<CameraRays> rays;
    if (!scene.render.jitter) {
      RenderOptions options = scene.render;
      options.threads = threads;
      rays = camera_rays(scene.camera, options);
    }
    json poses = json::array();
    for (std::size_t v = 0; v < scene.views.size(); ++v) {
      Scene view = scene_for_view(scene, v);
      view.render.seed = scene.render.seed * 1000003ULL + v;  // independent noise per view
      const std::string name = view_name(v);
      render_view(view, threads, rays ? &*rays : nullptr, scene.name + " " + name, root / "capture" / name,
                  root / "truth" / name);
      json pose = board_corners(view);
      if (!pose.is_null()) pose["view"] = name;
      poses.push_back(pose);
    }
    calib::write_rig(true_rig(scene), root / "truth" / "rig.yaml");
    write_file_atomically(root / "truth" / "board_poses.json", poses.dump(2) + "\n");
  }
  write_file_atomically(root / "scene.json", scene_to_json(scene).dump(2) + "\n");
  staging.commit();
}

}  // namespace rfrecon::sim
