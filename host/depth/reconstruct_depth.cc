// Orchestration of the depth stage: triangulation, rectification, segmentation, row solvers, back to the camera.
#include "host/depth/reconstruct_depth.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "host/core/errors.h"
#include "host/core/parallel_rows.h"
#include "host/core/stage_clock.h"
#include "host/depth/camera_grid.h"
#include "host/sched/scheduler.h"
#include "host/transport/spmv.h"
#include "host/transport/spmv_on_devices.h"
#include "kernels/common/lanes.h"

namespace rfrecon::depth {

namespace {

constexpr const char* kMethodNames[] = {"triangulate", "integrate", "fused"};

// Gaussian agreement weight exp(-d^2 / 2 s^2), 0 where d is NaN.
float agreement(float difference, float sigma) {
  return std::isnan(difference) ? 0.0f : std::exp(-0.5f * (difference / sigma) * (difference / sigma));
}

// Triangulation: how close the correspondence lies to its rectified row (0.5 px scale). Row solvers: how well the
// result agrees with the triangulated depth, in units of three times its expected noise.
void fill_confidence(outputs::Reconstruction& maps, const cv::Mat& z_rect_mm,
                     const CameraGridTriangulation& triangulation, const RfRectifiedRig& rig,
                     const DepthOptions& options) {
  const float depth_noise_scale = options.fusion.sigma_disparity_px / (rig.f * std::abs(rig.b));
  for_each_row(maps.depth_mm.rows, [&](int y) {
    for (int x = 0; x < maps.depth_mm.cols; ++x) {
      const float z = z_rect_mm.at<float>(y, x);
      if (!(z > 0.0f)) continue;
      float confidence = agreement(triangulation.epipolar_px.at<float>(y, x), 0.5f);
      if (options.method != Method::kTriangulate) {
        confidence *= agreement(z - triangulation.z_rect_mm.at<float>(y, x), 3.0f * z * z * depth_noise_scale);
      }
      maps.confidence.at<float>(y, x) = confidence;
    }
  });
}

// Throws before any work: no device, an entry list of the wrong length, a method the capture cannot serve.
void check_request(const transport::CompressedTransport& transport, const DepthOptions& options,
                   const std::vector<cl::DeviceContext>& devices) {
  if (devices.empty()) throw std::invalid_argument("reconstruct_depth: no device");
  options.entries.check_device_count(devices.size());
  if (options.method != Method::kTriangulate && transport.setup.dot_spacing == 0) {
    throw InputError("the " + method_name(options.method) +
                     " method needs the dot-grid scan (T's full rows for the primal and dual images), and this "
                     "capture has Gray code only (dot_spacing 0): use --method triangulate, or capture with dots");
  }
}

// Where the pixels with a correspondence went, each loss with the option that sets it: the text of the warning when
// fewer than half are reconstructed and of the error when none is.
std::string where_pixels_went(const nlohmann::json& summary, const CameraGridTriangulation& triangulation,
                              const DepthOptions& options, const std::string& rig_name) {
  std::string why = std::to_string(triangulation.off_epipolar) + " off their epipolar line by more than " +
                    fmt::format("{:g}", options.rectification.epipolar_tolerance_px) + " px (--epipolar-tolerance; " +
                    "is " + rig_name + " this capture's calibration?), " +
                    std::to_string(triangulation.boundary_pixels) + " on object boundaries, " +
                    std::to_string(triangulation.edge_pixels) + " on albedo or shadow edges (--edge-relative)";
  if (summary.contains("segmentation")) {
    const auto& segmentation = summary["segmentation"];
    why += ", " + std::to_string(segmentation["usable_pixels"].get<int>()) +
           " usable rectified samples for the integration (others lack primal or dual signal, or saturate: "
           "--saturation), in runs ended by " +
           std::to_string(segmentation["jumps"].get<int>()) + " depth jumps (--jump) and " +
           std::to_string(segmentation["creases"].get<int>()) + " creases (--crease)";
  }
  return why;
}
}  // namespace

std::string method_name(Method method) { return kMethodNames[static_cast<int>(method)]; }

Method parse_method(const std::string& name) {
  for (int i = 0; i < 3; ++i) {
    if (name == kMethodNames[i]) return static_cast<Method>(i);
  }
  throw InputError("unknown depth method '" + name + "' (triangulate, integrate or fused)");
}

DepthRun reconstruct_depth(const transport::CompressedTransport& transport, const calib::StereoRig& rig,
                           const std::string& rig_name, const DepthOptions& options,
                           std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs) {
  check_request(transport, options, devices);
  StageClock clock;
  const Rectification rectification = clock.time(
      "rig geometry", [&] { return depth_rectification(rig, rig_name, options.method != Method::kTriangulate); });
  DepthRun run = reconstruct_depth(transport, rig, rectification, rig_name, options, devices, programs);
  nlohmann::json timings = clock.timings();
  for (const auto& timing : run.summary["timings"]) timings.push_back(timing);
  run.summary["timings"] = timings;
  return run;
}

DepthRun reconstruct_depth(const transport::CompressedTransport& transport, const calib::StereoRig& rig,
                           const Rectification& rectification, const std::string& rig_name, const DepthOptions& options,
                           std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs) {
  check_request(transport, options, devices);
  DepthRun run;
  nlohmann::json& summary = run.summary;
  summary["method"] = method_name(options.method);
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

  cv::Mat z_rect_grid = triangulation.z_rect_mm;
  if (options.method != Method::kTriangulate) {
    std::vector<cl::ProgramRequest> requests = {
        {"transport/spmv.cl", transport::transport_build_options(transport.k())},
        {"transport/spmv.cl", ""},
        {"depth/integrate.cl", ""}};
    if (options.method == Method::kFused) requests.push_back({"depth/fuse.cl", ""});
    cl::prepare_programs(devices, programs, requests);
    clock.lap("build programs");
    std::vector<sched::RunReport> reports;
    auto primal = transport::primal_on_devices(devices, programs, options.entries, transport,
                                               std::vector<float>(transport.projector_pixels(), 1.0f));
    auto dual = transport::dual_on_devices(devices, programs, options.entries, transport::transpose(transport),
                                           std::vector<float>(transport.camera_pixels(), 1.0f));
    reports.push_back(primal.report);
    reports.push_back(dual.report);
    clock.lap("primal and dual images");
    RectifiedRows rows =
        rectify_rows(transport, primal.image, dual.image, rectification, triangulation, options.rectification);
    clock.lap("rectify");
    const SegmentationStats segments = segment_rows(rows, options.segmentation);
    summary["segmentation"] = {{"usable_pixels", segments.usable},
                               {"runs", segments.runs},
                               {"jumps", segments.jumps},
                               {"creases", segments.creases},
                               {"ode_breakdowns", segments.ode_breakdowns}};
    clock.lap("segment");
    if (segments.usable == 0) {
      throw ProcessingError("nothing to integrate: every rectified pixel is masked: of the " +
                            std::to_string(triangulation.correspondences) + " pixels with a correspondence, " +
                            where_pixels_went(summary, triangulation, options, rig_name));
    }
    // Rows are independent: the scheduler cuts them into tiles over the devices; each tile's depths go to its own
    // rows of z_rect, so the result does not depend on the split.
    std::vector<float> z_rect(rows.pixels());
    const auto solve_rows = [&](const std::string& stage, const auto& solve) {
      sched::Options tiles;
      tiles.stage = stage;
      tiles.entries = options.entries;
      tiles.granularity = RF_LANES;  // an NDRange work-item's rows (kernels/depth/row_lanes.h)
      reports.push_back(sched::run_tiles(
          devices, static_cast<std::size_t>(rows.height),
          [&](sched::Worker& worker, const sched::Tile& tile) {
            const int first = static_cast<int>(tile.begin), end = static_cast<int>(tile.end);
            const auto z = solve(worker, first, end);
            worker.deliver([&] {
              std::copy(z.begin(), z.end(), z_rect.begin() + static_cast<std::ptrdiff_t>(first) * rows.width);
            });
          },
          tiles));
      clock.lap(stage);
    };
    // The NDRange entries' interleaved rows, made once for every tile of both solvers (timed with the integration).
    const std::vector<cl::KernelEntry> entries = options.entries.resolve(devices);
    const bool any_lanes = std::find(entries.begin(), entries.end(), cl::KernelEntry::kNdRange) != entries.end();
    const LaneRows lanes = any_lanes ? interleave_rows(rows) : LaneRows{};
    solve_rows("integrate", [&](sched::Worker& worker, int first, int end) {
      return integrate_rows_opencl(worker.device(), programs, worker.entry(), rows, options.integration, first, end,
                                   &lanes);
    });
    if (options.method == Method::kFused) {
      const std::vector<float> z_integrated = z_rect;
      solve_rows("fuse", [&](sched::Worker& worker, int first, int end) {
        const auto begin = z_integrated.begin() + static_cast<std::ptrdiff_t>(first) * rows.width;
        const std::vector<float> start(begin, begin + static_cast<std::ptrdiff_t>(end - first) * rows.width);
        return fuse_rows_opencl(worker.device(), programs, worker.entry(), rows, start, options.fusion, first, end,
                                &lanes);
      });
    }
    summary["scheduler"] = reports;
    sched::log_reports(reports);
    z_rect_grid = sample_rectified_depth(z_rect, rows, triangulation.rect_cam, options.segmentation.jump_relative);
  }
  run.maps = camera_frame_maps(z_rect_grid, triangulation.rect_cam, rectified, rectification.R1);
  fill_confidence(run.maps, z_rect_grid, triangulation, rectified, options);
  clock.lap("camera grid");
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
