// The transport side of the built-in pattern family "graycode": Gray pairs decoded, then dot frames compressed, by
// the accumulators of host/transport/graycode_accumulator.h; Gray-code-only captures are decided and refined to
// sub-pixel correspondences on the host (gray_decision.h, gray_subpixel.h).
#pragma once

#include <memory>

#include "host/transport/decoding_family.h"

namespace rfrecon::transport {

std::shared_ptr<const DecodingFamily> graycode_decoding();

}  // namespace rfrecon::transport
