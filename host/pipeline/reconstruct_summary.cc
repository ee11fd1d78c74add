// summary.json's camera intrinsics and options of a reconstruction.
#include "host/pipeline/reconstruct_summary.h"

#include <charconv>
#include <cstdlib>
#include <iterator>
#include <string>

#include "host/cl/entry_choice.h"
#include "host/depth/depth_option_table.h"
#include "host/sched/watchdog.h"

namespace rfrecon::pipeline {

namespace {
// OpenCV's names of the distortion coefficients, in its order (cv::calibrateCamera).
constexpr const char* kDistortionNames[] = {"k1", "k2", "p1", "p2", "k3", "k4",   "k5",
                                            "k6", "s1", "s2", "s3", "s4", "tauX", "tauY"};

// A float option as the shortest decimal that reads back as it (0.97, not 0.9700000286102295).
double shortest(float value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::strtod(std::string(text, end).c_str(), nullptr);
}
}  // namespace

nlohmann::json camera_intrinsics_json(const calib::StereoRig& rig) {
  cv::Mat_<double> k;
  rig.camera_matrix.convertTo(k, CV_64F);
  cv::Mat_<double> dist;
  rig.dist_coeffs.reshape(1, 1).convertTo(dist, CV_64F);
  nlohmann::json json;
  json["image_size"] = {rig.camera_size.width, rig.camera_size.height};
  json["camera_matrix"] = nlohmann::json::array();
  for (int row = 0; row < 3; ++row) json["camera_matrix"].push_back({k(row, 0), k(row, 1), k(row, 2)});
  json["dist_coeffs"] = nlohmann::json::array();
  json["dist_coeffs_names"] = nlohmann::json::array();
  for (int i = 0; i < dist.cols && i < static_cast<int>(std::size(kDistortionNames)); ++i) {
    json["dist_coeffs"].push_back(dist(0, i));
    json["dist_coeffs_names"].push_back(kDistortionNames[i]);
  }
  return json;
}

nlohmann::json reconstruct_options_json(const ReconstructRequest& request,
                                        const std::vector<cl::DeviceContext>& devices,
                                        const std::vector<cl::KernelEntry>& entries) {
  const depth::DepthOptions& depth = request.depth;
  nlohmann::json json;
  json["transport"] = request.transport.string();
  json["calib"] = request.rig.string();
  json["output"] = request.out_dir.string();
  json["method"] = depth.method;
  json["devices"] = nlohmann::json::array();
  for (const auto& device : devices) json["devices"].push_back(device.info().device_name);
  json["entry"] = depth.entries.text();
  json["entries"] = nlohmann::json::array();
  for (const cl::KernelEntry entry : entries) json["entries"].push_back(cl::entry_name(entry));
  json["tile-timeout"] = sched::tile_timeout_from_environment();
  depth::DepthOptions values = depth;  // the table's accessors hand out pointers into a mutable struct
  for (const auto& spec : depth::depth_option_table()) {
    json[spec.name] =
        spec.real != nullptr ? nlohmann::json(shortest(*spec.real(values))) : nlohmann::json(*spec.whole(values));
  }
  json["force"] = request.force;
  return json;
}

}  // namespace rfrecon::pipeline
