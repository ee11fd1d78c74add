// The built-in methods that work along rectified rows: reciprocity integration (the paper's method, "integrate") and
// its fusion with the triangulated positions ("fused"), on the OpenCL devices through the scheduler.
#pragma once

#include <memory>

#include "host/depth/depth_method.h"

namespace rfrecon::depth {

// fuse: whether the integration is then fused with triangulation.
std::shared_ptr<const DepthMethod> row_method(bool fuse);

}  // namespace rfrecon::depth
