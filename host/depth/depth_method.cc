// The registry of depth methods, with the built-ins: triangulation here, integration and fusion in row_methods.cc.
#include "host/depth/depth_method.h"

#include <utility>

#include "host/core/named_registry.h"
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
};

NamedRegistry<DepthMethod>& registry() {
  static NamedRegistry<DepthMethod> instance(
      "depth method", {std::make_shared<const TriangulateMethod>(), row_method(false), row_method(true)});
  return instance;
}

}  // namespace

void register_depth_method(std::shared_ptr<const DepthMethod> method) { registry().add(std::move(method)); }

const DepthMethod& depth_method(const std::string& name) { return registry().find(name); }

std::vector<std::string> depth_method_names() { return registry().names(); }

}  // namespace rfrecon::depth
