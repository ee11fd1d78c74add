// The transport side of the built-in pattern family "phase": each axis's N phase steps, summed per pixel into the
// sinusoid's phase and modulation, unwrapped to a sub-pixel projector coordinate by the order code (Gray code of the
// half-period index, decided pattern against inverse) or by the phases of longer periods, coarsest first
// (docs/method.md, "Phase shifting"). T holds that correspondence and one entry (white - black) at its projector pixel,
// as Gray-code-only captures do.
#pragma once

#include <memory>

#include <opencv2/core.hpp>

#include "host/transport/decoding_family.h"

namespace rfrecon::transport {

std::shared_ptr<const DecodingFamily> phase_decoding();

// The projector coordinate (pixel centres at integers) u = m P + theta P / (2 pi) of wrapped phase theta (rad) and
// period P whose fringe m puts it nearest `estimate`: exact while the estimate is off by less than P / 2 minus the
// phase's error in pixels.
double unwrap_near(double theta, double estimate, int period);

// unwrap_near from the half-period index `order` of the order code: the estimate is the middle of that half period,
// so the order may be off by one at its edge and the phase off by less than a quarter period.
double unwrap_phase(double theta, int order, int period);

}  // namespace rfrecon::transport
