// A program built against the installed rfrecon package through its front door alone (rfrecon/rfrecon.h): renders a
// small tilted plane with the synthetic rig, loads its frames into memory as a camera would hand them over, makes T
// and reconstructs it with the true rig on the OpenCL devices, and checks depth against the truth.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "rfrecon/rfrecon.h"

namespace {

namespace fs = std::filesystem;

// Pass criteria (measured: 0.31 mm and 92 %): median |depth - true depth| over the plane's reconstructed pixels, and
// the share of its interior pixels reconstructed.
constexpr double kMaxMedianErrorMm = 1.0;
constexpr double kMinCoveragePercent = 80.0;

// A 64x48 camera and projector (f = 80 px) 150 mm apart, toed in to a 160 x 120 mm Lambertian plane 500 mm ahead
// turned (10, -10, 0) degrees (about 22 x 17 pixels); the 4x4 dot grid that the fused method needs; one ray per pixel.
nlohmann::json scene_json() {
  return {{"name", "install-consumer"},
          {"camera", {{"size", {64, 48}}, {"focal", {80.0, 80.0}}}},
          {"projector",
           {{"size", {64, 48}},
            {"focal", {80.0, 80.0}},
            {"pose", {{"position", {150.0, 0.0, 0.0}}, {"look_at", {0.0, 0.0, 500.0}}}}}},
          {"radiometry", {{"intensity", 7.0e5}}},
          {"capture", {{"dot_spacing", 4}}},
          {"render", {{"supersample", 1}}},
          {"objects",
           {{{"name", "plane"},
             {"shape", "plane"},
             {"size", {160.0, 120.0}},
             {"pose", {{"position", {0.0, 0.0, 500.0}}, {"rotation_deg", {10.0, -10.0, 0.0}}}},
             {"material", {{"brdf", "lambert"}, {"diffuse", 0.6}}}}}}};
}

int run(const fs::path& work) {
  const auto start = std::chrono::steady_clock::now();
  fs::remove_all(work);
  fs::create_directories(work);
  std::ofstream(work / "scene.json") << scene_json().dump();

  rfrecon::Session session;  // every OpenCL device ($RFRECON_DEVICES chooses)
  const fs::path rendering = work / "rendering";
  const fs::path capture_dir = session.simulate((work / "scene.json").string(), rendering).at(0);

  // The frames in memory, as a camera SDK would hand them over, and their manifest.
  const auto files = rfrecon::Capture::from_directory(capture_dir);
  std::vector<cv::Mat> frames;
  for (std::size_t i = 0; i < files.manifest().frames.size(); ++i) frames.push_back(files.frame(i));
  const auto camera = rfrecon::Capture::from_frames(files.manifest(), std::move(frames), "frames in memory");

  const rfrecon::TransportResult transport = session.transport(camera);
  const rfrecon::Rig rig = rfrecon::read_rig(rendering / "truth" / "rig.yaml");
  rfrecon::ReconstructOptions options;
  options.method = "fused";
  const rfrecon::ReconstructResult result = session.reconstruct(transport.transport, rig, options);
  rfrecon::write_reconstruction(result, work / "reconstruction");

  // The plane's pixels: depth errors over those reconstructed; coverage over its interior (pixels whose 3x3
  // neighbourhood is all plane), as the fused method leaves out pixels that straddle the plane's edge.
  const cv::Mat true_depth = cv::imread((rendering / "truth" / "depth.tiff").string(), cv::IMREAD_UNCHANGED);
  const cv::Mat object_id = cv::imread((rendering / "truth" / "object_id.png").string(), cv::IMREAD_UNCHANGED);
  const cv::Mat& depth = result.maps.depth_mm;
  if (true_depth.type() != CV_32F || object_id.type() != CV_16U || true_depth.size() != depth.size()) {
    std::fprintf(stderr, "rfrecon_consumer: unexpected truth maps under %s\n", (rendering / "truth").c_str());
    return 1;
  }
  const auto on_plane = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < depth.cols && y < depth.rows && object_id.at<unsigned short>(y, x) == 1;
  };
  std::vector<double> errors;
  int interior = 0, interior_reconstructed = 0;
  for (int y = 0; y < depth.rows; ++y) {
    for (int x = 0; x < depth.cols; ++x) {
      if (!on_plane(x, y)) continue;
      const float z = depth.at<float>(y, x);
      if (std::isfinite(z)) errors.push_back(std::abs(z - true_depth.at<float>(y, x)));
      bool inside = true;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) inside = inside && on_plane(x + dx, y + dy);
      }
      if (!inside) continue;
      ++interior;
      if (std::isfinite(z)) ++interior_reconstructed;
    }
  }
  const double coverage = interior > 0 ? 100.0 * interior_reconstructed / interior : 0.0;
  double median = INFINITY;
  if (!errors.empty()) {
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    median = errors[errors.size() / 2];
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "rfrecon %s on %zu device(s): fused from %zu frames in memory, median |depth error| %.4f mm (limit %.1f), "
      "coverage %.1f %% (limit %.0f) of the %d interior plane pixels, %zu pixels reconstructed, %.1f s\n",
      RFRECON_VERSION, session.devices().size(), camera.manifest().frames.size(), median, kMaxMedianErrorMm, coverage,
      kMinCoveragePercent, interior, errors.size(), seconds);
  const bool pass = median < kMaxMedianErrorMm && coverage > kMinCoveragePercent;
  if (pass) fs::remove_all(work);
  return pass ? 0 : 1;
}

}  // namespace

// Usage: rfrecon_consumer [WORK_DIR]; WORK_DIR (default: under the system temporary directory) is replaced.
int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  const fs::path work = argc > 1 ? fs::path(argv[1]) : fs::temp_directory_path() / "rfrecon_install_consumer";
  try {
    return run(work);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rfrecon_consumer: %s\n", e.what());
    return 2;
  }
}
