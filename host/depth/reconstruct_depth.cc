// The depth stage's driver: triangulation on the camera grid, the chosen method, and back to the camera frame.
#include "host/depth/reconstruct_depth.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <spdlog/spdlog.h>

#include "host/core/errors.h"
#include "host/core/parallel_rows.h"
#include "host/core/stage_clock.h"
#include "host/depth/calibration_sigma.h"
#include "host/depth/camera_grid.h"
#include "host/depth/depth_sigma.h"
#include "host/depth/pixel_losses.h"
#include "host/depth/sampled_sigma.h"

namespace rfrecon::depth {

namespace {

// Gaussian agreement weight exp(-d^2 / 2 s^2), 0 where d is NaN.
float agreement(float difference, float sigma) {
  return std::isnan(difference) ? 0.0f : std::exp(-0.5f * (difference / sigma) * (difference / sigma));
}

// How close the correspondence lies to its rectified row (0.5 px scale), times how well the depth agrees with the
// triangulated one, in units of three times its expected noise (1 for triangulation itself).
void fill_confidence(outputs::Reconstruction& maps, const cv::Mat& z_rect_mm,
                     const CameraGridTriangulation& triangulation, const RfRectifiedRig& rig,
                     const DepthOptions& options) {
  const float depth_noise_scale = options.fusion.sigma_disparity_px / (rig.f * std::abs(rig.b));
  for_each_row(maps.depth_mm.rows, [&](int y) {
    for (int x = 0; x < maps.depth_mm.cols; ++x) {
      const float z = z_rect_mm.at<float>(y, x);
      if (!(z > 0.0f)) continue;
      maps.confidence.at<float>(y, x) =
          agreement(triangulation.epipolar_px.at<float>(y, x), 0.5f) *
          agreement(z - triangulation.z_rect_mm.at<float>(y, x), 3.0f * z * z * depth_noise_scale);
    }
  });
}

// The method, before any work; throws on no device, an entry list of the wrong length, a method unknown or one the
// capture cannot serve.
const DepthMethod& check_request(const transport::CompressedTransport& transport, const DepthOptions& options,
                                 const std::vector<cl::DeviceContext>& devices) {
  if (devices.empty()) throw std::invalid_argument("reconstruct_depth: no device");
  options.entries.check_device_count(devices.size());
  const DepthMethod& method = depth_method(options.method);
  if (method.needs_rows() && transport.setup.dot_spacing == 0) {
    throw InputError("the " + method.name() +
                     " method needs the dot-grid scan (T's full rows for the primal and dual images), and this "
                     "capture has Gray code only (dot_spacing 0): use --method triangulate, or capture with dots");
  }
  return method;
}

// The calibration's part from the rig's covariance (0 for a rig without one, a ground truth): to first order through
// the triangulation, or with `rerun`, by rerunning the method on the rig moved along each principal direction.
SigmaPart calibration_sigma(const DepthMethod& method, const MethodScan& scan, const calib::StereoRig& rig,
                            const cv::Mat& depth_mm, bool rerun) {
  const cv::Mat covariance = rig_parameter_covariance(rig);
  if (covariance.empty()) {
    return {cv::Mat(depth_mm.size(), CV_32F, cv::Scalar(0.0f)), "none: the rig has no uncertainty (0)"};
  }
  const std::string source = rig.uncertainty.parameter_covariance.empty()
                                 ? "the rig's standard deviations (no covariance in the file)"
                                 : "the rig's parameter covariance";
  const cv::Mat first_order = calibration_depth_sigma(rig, covariance, depth_mm);
  if (!rerun) return {first_order, source + ", through the triangulation"};
  const std::vector<std::vector<double>> steps = principal_steps(covariance);
  return {rerun_calibration_sigma(method, scan, rig, steps, depth_mm, first_order),
          source + ", through the method rerun on the rig moved along " + std::to_string(steps.size()) +
              " principal directions"};
}

// The frames' part: the method's closed form (along the rectified axis), or with `samples`, the spread over that many
// noisy copies of T.
SigmaPart observation_sigma(const cv::Mat& closed_form, int samples, const DepthMethod& method, const MethodScan& scan,
                            const calib::StereoRig& rig, const cv::Mat& z_rect_mm, const cv::Mat& depth_mm) {
  if (!closed_form.empty()) {
    return {camera_z_sigma(closed_form, z_rect_mm, depth_mm), "the frames' noise through the correspondences"};
  }
  const cv::Mat sampled = samples > 0 ? sampled_observation_sigma(method, scan, rig, samples) : cv::Mat();
  if (sampled.empty()) return {{}, "not propagated by this method or capture"};
  return {sampled, "the spread over " + std::to_string(samples) + " noisy copies of T"};
}
}  // namespace

DepthRun reconstruct_depth(const transport::CompressedTransport& transport, const calib::StereoRig& rig,
                           const std::string& rig_name, const DepthOptions& options,
                           std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs) {
  const DepthMethod& method = check_request(transport, options, devices);
  StageClock clock;
  const Rectification rectification =
      clock.time("rig geometry", [&] { return depth_rectification(rig, rig_name, method.needs_rows()); });
  DepthRun run = reconstruct_depth(transport, rig, rectification, rig_name, options, devices, programs);
  nlohmann::json timings = clock.timings();
  for (const auto& timing : run.summary["timings"]) timings.push_back(timing);
  run.summary["timings"] = timings;
  return run;
}

DepthRun reconstruct_depth(const transport::CompressedTransport& transport, const calib::StereoRig& rig,
                           const Rectification& rectification, const std::string& rig_name, const DepthOptions& options,
                           std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs) {
  const DepthMethod& method = check_request(transport, options, devices);
  DepthRun run;
  nlohmann::json& summary = run.summary;
  summary["method"] = method.name();
  summary["camera_size"] = {transport.setup.camera_size.width, transport.setup.camera_size.height};
  summary["projector_size"] = {transport.setup.projector_size.width, transport.setup.projector_size.height};
  StageClock clock;
  const RfRectifiedRig& rectified = rectification.rig;
  summary["rectified"] = {{"f_px", rectified.f},
                          {"cx_camera_px", rectified.cx_cam},
                          {"cx_projector_px", rectified.cx_proj},
                          {"cy_px", rectified.cy},
                          {"baseline_mm", rectified.b},
                          {"camera_size", {rectification.camera_size.width, rectification.camera_size.height}},
                          {"projector_width", rectification.projector_width}};
  const CameraGridTriangulation triangulation =
      triangulate_camera_grid(transport, rig, rectification, options.rectification);
  summary["correspondences"] = triangulation.correspondences;
  summary["off_epipolar"] = triangulation.off_epipolar;
  summary["boundary_pixels"] = triangulation.boundary_pixels;
  summary["edge_pixels"] = triangulation.edge_pixels;
  clock.lap("triangulate");
  if (triangulation.correspondences - triangulation.off_epipolar == 0) {
    throw ProcessingError("nothing to reconstruct: no camera pixel has a correspondence on its epipolar line (" +
                          std::to_string(triangulation.correspondences) + " correspondences, all off by more than " +
                          std::to_string(options.rectification.epipolar_tolerance_px) + " px: is " + rig_name +
                          " the calibration of this capture?)");
  }

  const std::vector<cl::ProgramRequest> requests = method.programs(transport);
  if (!requests.empty()) {
    cl::prepare_programs(devices, programs, requests);
    clock.lap("build programs");
  }
  MethodScan scan{transport, rectification, triangulation, options, rig_name, devices, programs, clock, summary};
  const cv::Mat z_rect_grid = method.solve(scan);
  if (z_rect_grid.type() != CV_32F || z_rect_grid.size() != triangulation.z_rect_mm.size()) {
    throw std::logic_error("depth method " + method.name() + " returned depth of another size or type than the " +
                           "camera's CV_32F grid");
  }
  run.maps = camera_frame_maps(z_rect_grid, triangulation.rect_cam, rectified, rectification.rect_from_cam);
  fill_confidence(run.maps, z_rect_grid, triangulation, rectified, options);
  clock.lap("camera grid");
  // A method without a closed form for the frames' part is rerun for both parts when samples are asked for.
  const cv::Mat closed_form = method.observation_sigma(scan, z_rect_grid);
  const int samples = closed_form.empty() ? options.sigma_samples : 0;
  add_depth_sigma(run.maps, calibration_sigma(method, scan, rig, run.maps.depth_mm, samples > 0),
                  observation_sigma(closed_form, samples, method, scan, rig, z_rect_grid, run.maps.depth_mm), summary);
  clock.lap("uncertainty");
  summary["timings"] = clock.timings();
  summary["programs"] = programs.builds();
  const int reconstructed = cv::countNonZero(run.maps.depth_mm == run.maps.depth_mm);
  summary["reconstructed_pixels"] = reconstructed;
  summary["devices"] = nlohmann::json::array();
  for (const auto& device : devices) summary["devices"].push_back(device.info().device_name);
  if (reconstructed == 0) {
    throw ProcessingError("nothing reconstructed: of the " + std::to_string(triangulation.correspondences) +
                          " pixels with a correspondence, " +
                          where_pixels_went(summary, triangulation, options, rig_name));
  }
  if (2 * reconstructed < triangulation.correspondences) {
    const std::string warning = "only " + std::to_string(reconstructed) + " of the " +
                                std::to_string(triangulation.correspondences) +
                                " pixels with a correspondence were reconstructed: " +
                                where_pixels_went(summary, triangulation, options, rig_name);
    spdlog::warn("reconstruct: {}", warning);
    summary["warnings"].push_back(warning);
  }
  return run;
}

}  // namespace rfrecon::depth
