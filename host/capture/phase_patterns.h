// The built-in pattern family "phase": N-step phase shifting of columns and rows, unwrapped by a Gray code of the
// half-period index with inverses. Sinusoids keep their phase under projector defocus, where Gray code's finest
// stripes wash out; the coarsest stripes needed here are half a period wide (docs/method.md, "Phase shifting").
#pragma once

#include <memory>

#include "host/capture/pattern_family.h"

namespace rfrecon::capture {

// The manifest's pattern kinds: a phase step of an axis (`bit` = step k of N) and a bit of the axis's order code
// (`bit`, 0 = most significant, and `inverse`).
namespace pattern_kind {
inline constexpr const char* kPhaseColumn = "phase_col";
inline constexpr const char* kPhaseRow = "phase_row";
inline constexpr const char* kOrderColumn = "order_col";
inline constexpr const char* kOrderRow = "order_row";
}  // namespace pattern_kind

// Parameters: phase_steps N (3 to 64, default 4) and phase_period P in projector pixels (4 to 4096, default 16).
inline constexpr const char* kPhaseSteps = "phase_steps";
inline constexpr const char* kPhasePeriod = "phase_period";

std::shared_ptr<const PatternFamily> phase_family();

// Step k of N on an axis: 0.5 + 0.5 cos(2 pi x / P - 2 pi k / N) at projector coordinate x (pixel centres at
// integers), before the 8-bit rounding.
double phase_pattern_level(double x, int period, int step, int steps);

// The half-period index floor(2 x / P) of projector pixel x, which the order code carries, and its bit count on an
// axis of n pixels.
int phase_order(int x, int period);
int phase_order_bits(int n, int period);

}  // namespace rfrecon::capture
