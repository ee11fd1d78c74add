// The registry of depth methods, with the built-ins: triangulation here, integration and fusion in row_methods.cc.
#include "host/depth/depth_method.h"

#include <mutex>
#include <stdexcept>

#include "host/core/errors.h"
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

struct Registry {
  std::mutex mutex;
  std::vector<std::shared_ptr<const DepthMethod>> methods = {std::make_shared<const TriangulateMethod>(),
                                                             row_method(false), row_method(true)};
};

Registry& registry() {
  static Registry instance;
  return instance;
}

}  // namespace

void register_depth_method(std::shared_ptr<const DepthMethod> method) {
  if (!method) throw std::invalid_argument("register_depth_method: no method");
  Registry& methods = registry();
  const std::scoped_lock lock(methods.mutex);
  for (const auto& known : methods.methods) {
    if (known->name() == method->name()) {
      throw std::invalid_argument("register_depth_method: a depth method named '" + method->name() +
                                  "' is registered already");
    }
  }
  methods.methods.push_back(std::move(method));
}

const DepthMethod& depth_method(const std::string& name) {
  Registry& methods = registry();
  const std::scoped_lock lock(methods.mutex);
  std::string names;
  for (const auto& method : methods.methods) {
    if (method->name() == name) return *method;
    names += (names.empty() ? "" : ", ") + method->name();
  }
  throw InputError("unknown depth method '" + name + "' (" + names + ")");
}

std::vector<std::string> depth_method_names() {
  Registry& methods = registry();
  const std::scoped_lock lock(methods.mutex);
  std::vector<std::string> names;
  for (const auto& method : methods.methods) names.push_back(method->name());
  return names;
}

}  // namespace rfrecon::depth
