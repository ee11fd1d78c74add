// The built-in pattern family "phase": N-step phase shifting of columns and rows, unwrapped by a Gray code of the
// half-period index with inverses, or by sinusoids of longer periods (temporal unwrapping). Sinusoids keep their phase
// under projector defocus, where Gray code's finest stripes wash out; the finest stripes the order code needs are half
// a period wide, and the longer periods need none (docs/method.md, "Phase shifting"). The dot grid
// (host/capture/dot_grid.h) may follow, for T's full rows; the phase still gives the correspondences.
#pragma once

#include <memory>
#include <vector>

#include "host/capture/pattern_family.h"

namespace rfrecon::capture {

// The manifest's pattern kinds: a phase step of an axis (`bit` = step k of N, `level` = its period's index in
// phase_periods) and a bit of the axis's order code (`bit`, 0 = most significant, and `inverse`).
namespace pattern_kind {
inline constexpr const char* kPhaseColumn = "phase_col";
inline constexpr const char* kPhaseRow = "phase_row";
inline constexpr const char* kOrderColumn = "order_col";
inline constexpr const char* kOrderRow = "order_row";
}  // namespace pattern_kind

// Parameters: phase_steps N (3 to 64, default 4), phase_period P in projector pixels (4 to 4096, default 16) and
// phase_ratio R (0, the default: the order code unwraps; 2 to 64: the periods of phase_periods do).
inline constexpr const char* kPhaseSteps = "phase_steps";
inline constexpr const char* kPhasePeriod = "phase_period";
inline constexpr const char* kPhaseRatio = "phase_ratio";

std::shared_ptr<const PatternFamily> phase_family();

// Step k of N on an axis: 0.5 + 0.5 cos(2 pi x / P - 2 pi k / N) at projector coordinate x (pixel centres at
// integers), before the 8-bit rounding.
double phase_pattern_level(double x, int period, int step, int steps);

// The half-period index floor(2 x / P) of projector pixel x, which the order code carries, and its bit count on an
// axis of n pixels.
int phase_order(int x, int period);
int phase_order_bits(int n, int period);

// The periods of an axis of n pixels, finest first: P alone for ratio 0; else P, P R, P R^2, ... up to the first
// period p with p (R - 1) >= n, then a last one of n + p, which no pixel of the axis sees twice even p / 2 off. Each
// period is at most R times the one before, so each level unwraps the next finer one while its error in projector
// pixels stays under half that one's period.
std::vector<int> phase_periods(int n, int period, int ratio);

}  // namespace rfrecon::capture
