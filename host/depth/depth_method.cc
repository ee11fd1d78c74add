// The registry of depth methods, with the built-ins: triangulation here, integration and fusion in row_methods.cc.
#include "host/depth/depth_method.h"

#include <utility>

#include "host/core/named_registry.h"
#include "host/depth/observation_sigma.h"
#include "host/depth/row_methods.h"

namespace rfrecon::depth {

namespace {

// Depth from the correspondences alone (Gray code's or the dots'), where they lie on their epipolar lines.
class TriangulateMethod : public DepthMethod {
 public:
  std::string name() const override { return "triangulate"; }
  std::string description() const override { return "correspondences triangulated (Gray code, dots)"; }
  bool needs_rows() const override { return false; }
  std::vector<cl::ProgramRequest> programs(const transport::CompressedTransport&) const override { return {}; }
  cv::Mat solve(MethodScan& scan) const override { return scan.triangulation.z_rect_mm; }
  cv::Mat observation_sigma(const MethodScan& scan, const cv::Mat& z_rect_mm) const override {
    const cv::Mat column_sigma = rectified_column_sigma_px(scan.transport, scan.rectification);
    return column_sigma.empty() ? column_sigma
                                : triangulated_depth_sigma(z_rect_mm, column_sigma, scan.rectification.rig);
  }
};

NamedRegistry<DepthMethod>& registry() {
  static NamedRegistry<DepthMethod> instance(
      "depth method", {std::make_shared<const TriangulateMethod>(), row_method(false), row_method(true)});
  return instance;
}

}  // namespace

cv::Mat DepthMethod::observation_sigma(const MethodScan&, const cv::Mat&) const { return {}; }

void register_depth_method(std::shared_ptr<const DepthMethod> method) { registry().add(std::move(method)); }

const DepthMethod& depth_method(const std::string& name) { return registry().find(name); }

std::vector<std::string> depth_method_names() { return registry().names(); }

}  // namespace rfrecon::depth
