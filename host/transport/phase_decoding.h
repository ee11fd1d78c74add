// The transport side of the built-in pattern family "phase": each axis's N phase steps, summed per pixel into the
// sinusoid's phase and modulation, unwrapped to a sub-pixel projector coordinate by the order code (Gray code of the
// half-period or period index, decided pattern against inverse or against the mean of white and black), by the phases
// of longer periods, coarsest first, or by the beats of nearby fringe counts (docs/method.md, "Phase shifting"). T
// holds that correspondence and one entry (white - black) at its projector pixel, as Gray-code-only captures do.
#pragma once

#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "host/transport/decoding_family.h"

namespace rfrecon::transport {

std::shared_ptr<const DecodingFamily> phase_decoding();

// The projector coordinate (pixel centres at integers) u = m P + theta P / (2 pi) of wrapped phase theta (rad) and
// period P whose fringe m puts it nearest `estimate`: exact while the estimate is off by less than P / 2 minus the
// phase's error in pixels.
double unwrap_near(double theta, double estimate, double period);

// unwrap_near from the index `order` of the order code's stripes, `unit` half periods wide: the estimate is the middle
// of that stripe. With half periods (unit 1) the order may be off by one at its edge and the phase off by less than a
// quarter period; with whole periods (unit 2) a stripe's edge is the phase's wrap, and an order off by one there
// moves the pixel by a period.
double unwrap_phase(double theta, int order, double period, int unit = 1);

// The heterodyne estimate (projector pixels) of an axis of `axis_pixels` from its phases in turns, t[l] in [0, 1) of
// fringes[l] periods across the axis, finest first (two or three levels, fringes as
// capture::phase_heterodyne_fringes): the beat t0 - t1 spans the axis once (two levels), or is unwrapped near the beat
// of the beats, (t0 - t1) - (t1 - t2), which does. Right while the beat of the beats is off by less than half the
// beat's period; the finest phase is then unwrapped near it as by longer periods.
double heterodyne_estimate(const double* turns, const std::vector<int>& fringes, double axis_pixels);

}  // namespace rfrecon::transport
