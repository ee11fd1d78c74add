// The transport side of the built-in pattern family "phase": each axis's order code (Gray code of the half-period
// index, decided pattern against inverse) and its N phase steps, summed per pixel into the sinusoid's phase and
// modulation, then unwrapped to a sub-pixel projector coordinate (docs/method.md, "Phase shifting"). T holds that
// correspondence and one entry (white - black) at its projector pixel, as Gray-code-only captures do.
#pragma once

#include <memory>

#include <opencv2/core.hpp>

#include "host/transport/decoding_family.h"

namespace rfrecon::transport {

std::shared_ptr<const DecodingFamily> phase_decoding();

// The unwrapped projector coordinate (pixel centres at integers) from the wrapped phase theta (rad) of an axis and
// its half-period index `order`, for period `period`: the coordinate u = m P + theta P / (2 pi) whose fringe m puts it
// nearest the middle of the order's half period. Exact when the order is right or off by one at its edge and the
// phase is off by less than a quarter period.
double unwrap_phase(double theta, int order, int period);

}  // namespace rfrecon::transport
