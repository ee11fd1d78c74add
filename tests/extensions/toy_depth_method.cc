// A depth method registered from outside host/depth, through the front door only: "toy-scale", the triangulated
// depth times 1.01. Linked into the CLI's own main as rfrecon_toy_cli, it shows that a new method is one class and one
// registration (docs/architecture.md#extension-points).
#include <memory>

#include "rfrecon/rfrecon.h"

namespace {

class ToyScaleMethod : public rfrecon::DepthMethod {
 public:
  std::string name() const override { return "toy-scale"; }
  std::string description() const override { return "test method: triangulated depth times 1.01"; }
  bool needs_rows() const override { return false; }
  std::vector<rfrecon::cl::ProgramRequest> programs(const rfrecon::Transport&) const override { return {}; }
  cv::Mat solve(rfrecon::MethodScan& scan) const override {
    scan.clock.lap("toy");
    return scan.triangulation.z_rect_mm * 1.01;
  }
};

[[maybe_unused]] const bool kRegistered = [] {
  rfrecon::register_depth_method(std::make_shared<const ToyScaleMethod>());
  return true;
}();

}  // namespace
