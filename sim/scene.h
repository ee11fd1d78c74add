// A synthetic projector-camera scene: devices, radiometry, capture settings, render settings and objects.
// The camera frame is the world frame; lengths in millimetres. JSON format in docs/sim.md.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/device.h"
#include "sim/objects.h"

namespace rfrecon::sim {

// What `render_transport` computes and how finely.
struct RenderOptions {
  int supersample = 4;                // camera pixel sampled on an N x N grid of sub-pixel rays
  bool jitter = false;                // each ray at a random place in its grid cell (unbiased edges), else centred
  int interreflection_samples = 0;    // cosine-weighted rays per camera sample for one-bounce interreflection; 0 = off
  double projector_defocus_px = 0.0;  // sigma of a Gaussian projector PSF, projector pixels; 0 = in focus
  double camera_defocus_px = 0.0;     // sigma of a Gaussian camera PSF, camera pixels; 0 = in focus
  int threads = 0;                    // 0 = std::thread::hardware_concurrency()
  unsigned long long seed = 1;        // noise of the frames and interreflection sampling
};

// How pattern frames are turned into camera readings (docs/sim.md, "Noise model").
struct CaptureSettings {
  std::string family = "graycode";          // the pattern family (host/capture/pattern_family.h)
  std::map<std::string, int> parameters{};  // the family's parameters given (phase: phase_steps, phase_period)
  int dot_spacing = 8;                      // graycode: s of the s x s dot grid; 0 = Gray code, white and black only
  int bit_depth = 10;                       // 8, 10, 12 or 16
  double black_level = 16.0;                // digital numbers added to every reading
  double response_gamma = 1.0;              // reading = linear^(1/gamma); 1 = linear
  double ambient = 0.0;                     // linear reading added to every pixel of every frame (full scale = 1)
  double full_well_electrons = 20000.0;     // electrons at full scale (shot noise); 0 = no shot noise
  double read_noise_dn = 0.5;               // Gaussian read noise, digital numbers (of bit_depth); 0 = none
  std::string format = "tiff";              // frame files: "tiff" (uncompressed) or "png"
};

struct Scene {
  std::string name;
  Device camera;     // device_from_world is the identity
  Device projector;  // device_from_world: X_proj = R X_cam + t
  // Camera reading (full scale = 1) of a surface point lit by the projector at full level:
  // gain * intensity * f_r * cos(theta_p) / d_p^2 with d_p in mm, so `intensity` is in mm^2 / sr.
  double gain = 1.0;
  double intensity = 1.0e6;
  CaptureSettings capture;
  RenderOptions render;
  std::vector<Object> objects;
  // Multi-view scenes (e.g. checkerboard-poses): each view sets the pose of named objects (world_from_object).
  std::vector<std::map<std::string, Eigen::Isometry3d>> views;
};

// Parses and validates a scene; errors are InputError naming `source` (a file or "scene 'NAME'") and the field path,
// e.g. "objects[2].size: must be > 0". Relative mesh paths resolve against `base_dir`.
Scene scene_from_json(const nlohmann::json& root, const std::string& source, const std::filesystem::path& base_dir);
Scene load_scene_file(const std::filesystem::path& file);

// The resolved scene (every field, defaults filled in), so that a run can be reproduced.
nlohmann::json scene_to_json(const Scene& scene);

// The scene with the pose of each object named in `view` replaced.
Scene scene_for_view(const Scene& scene, std::size_t view);

// The same physical rig with camera and projector exchanged (the projector frame becomes the world frame):
// its transport matrix is, by Helmholtz reciprocity, T^T up to the pixel solid-angle ratio (docs/sim.md).
Scene swap_devices(const Scene& scene);

// The largest simulated camera or projector side (px): rendering T costs pixels x supersample^2 rays.
inline constexpr int kMaxSimulatedSide = 4096;

// Changes device resolutions keeping the field of view: focal lengths scale with the width ratio, the principal
// point with the width and height ratios. Throws InputError for a side outside [1, kMaxSimulatedSide].
void resize_device(Device& device, cv::Size size);

}  // namespace rfrecon::sim
