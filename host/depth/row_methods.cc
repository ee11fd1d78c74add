// Integration and fusion as depth methods: primal and dual images, rectified rows, segmentation, the row solvers
// tiled over the devices, and back to the camera grid.
#include "host/depth/row_methods.h"

#include <algorithm>
#include <string>
#include <vector>

#include "host/core/errors.h"
#include "host/depth/camera_grid.h"
#include "host/depth/pixel_losses.h"
#include "host/sched/scheduler.h"
#include "host/transport/spmv.h"
#include "host/transport/spmv_on_devices.h"
#include "kernels/common/lanes.h"

namespace rfrecon::depth {

namespace {

class RowMethod : public DepthMethod {
 public:
  explicit RowMethod(bool fuse) : fuse_(fuse) {}

  std::string name() const override { return fuse_ ? "fused" : "integrate"; }
  std::string description() const override {
    return fuse_ ? "the reciprocity integration fused with the triangulated positions"
                 : "reciprocity ODE along rectified rows, seeded by triangulation (any BRDF)";
  }
  bool needs_rows() const override { return true; }

  std::vector<cl::ProgramRequest> programs(const transport::CompressedTransport& transport) const override {
    std::vector<cl::ProgramRequest> requests = {
        {"transport/spmv.cl", transport::transport_build_options(transport.k())},
        {"transport/spmv.cl", ""},
        {"depth/integrate.cl", ""}};
    if (fuse_) requests.push_back({"depth/fuse.cl", ""});
    return requests;
  }

  cv::Mat solve(MethodScan& scan) const override {
    const auto& transport = scan.transport;
    const auto& options = scan.options;
    std::vector<sched::RunReport> reports;
    auto primal = transport::primal_on_devices(scan.devices, scan.programs, options.entries, transport,
                                               std::vector<float>(transport.projector_pixels(), 1.0f));
    auto dual =
        transport::dual_on_devices(scan.devices, scan.programs, options.entries, transport::transpose(transport),
                                   std::vector<float>(transport.camera_pixels(), 1.0f));
    reports.push_back(primal.report);
    reports.push_back(dual.report);
    scan.clock.lap("primal and dual images");
    RectifiedRows rows = rectify_rows(transport, primal.image, dual.image, scan.rectification, scan.triangulation,
                                      options.rectification);
    scan.clock.lap("rectify");
    const SegmentationStats segments = segment_rows(rows, options.segmentation);
    scan.summary["segmentation"] = {{"usable_pixels", segments.usable},
                                    {"runs", segments.runs},
                                    {"jumps", segments.jumps},
                                    {"creases", segments.creases},
                                    {"ode_breakdowns", segments.ode_breakdowns}};
    scan.clock.lap("segment");
    if (segments.usable == 0) {
      throw ProcessingError("nothing to integrate: every rectified pixel is masked: of the " +
                            std::to_string(scan.triangulation.correspondences) + " pixels with a correspondence, " +
                            where_pixels_went(scan.summary, scan.triangulation, options, scan.rig_name));
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
          scan.devices, static_cast<std::size_t>(rows.height),
          [&](sched::Worker& worker, const sched::Tile& tile) {
            const int first = static_cast<int>(tile.begin), end = static_cast<int>(tile.end);
            const auto z = solve(worker, first, end);
            worker.deliver([&] {
              std::copy(z.begin(), z.end(), z_rect.begin() + static_cast<std::ptrdiff_t>(first) * rows.width);
            });
          },
          tiles));
      scan.clock.lap(stage);
    };
    // The NDRange entries' interleaved rows, made once for every tile of both solvers (timed with the integration).
    const std::vector<cl::KernelEntry> entries = options.entries.resolve(scan.devices);
    const bool any_lanes = std::find(entries.begin(), entries.end(), cl::KernelEntry::kNdRange) != entries.end();
    const LaneRows lanes = any_lanes ? interleave_rows(rows) : LaneRows{};
    solve_rows("integrate", [&](sched::Worker& worker, int first, int end) {
      return integrate_rows_opencl(worker.device(), scan.programs, worker.entry(), rows, options.integration, first,
                                   end, &lanes);
    });
    if (fuse_) {
      const std::vector<float> z_integrated = z_rect;
      solve_rows("fuse", [&](sched::Worker& worker, int first, int end) {
        const auto begin = z_integrated.begin() + static_cast<std::ptrdiff_t>(first) * rows.width;
        const std::vector<float> start(begin, begin + static_cast<std::ptrdiff_t>(end - first) * rows.width);
        return fuse_rows_opencl(worker.device(), scan.programs, worker.entry(), rows, start, options.fusion, first, end,
                                &lanes);
      });
    }
    scan.summary["scheduler"] = reports;
    sched::log_reports(reports);
    return sample_rectified_depth(z_rect, rows, scan.triangulation.rect_cam, options.segmentation.jump_relative);
  }

 private:
  bool fuse_;
};

}  // namespace

std::shared_ptr<const DepthMethod> row_method(bool fuse) { return std::make_shared<const RowMethod>(fuse); }

}  // namespace rfrecon::depth
