// The built-in pattern family "phase": N-step phase shifting of columns and rows, unwrapped by a Gray code of the
// half-period index with inverses, by sinusoids of longer periods (temporal unwrapping) or by the beats of nearby
// fringe counts (heterodyne). Sinusoids keep their phase
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

// Parameters: phase_steps N (3 to 64, default 4), phase_period P in projector pixels (4 to 4096, default 16) or
// phase_fringes F (0, the default: P gives the period; 1 to 1024: F periods across each axis, n / F pixels), and
// phase_ratio R (0, the default: the order code unwraps; 2 to 64: the periods of phase_periods do) or
// phase_heterodyne B (0, the default; 1 to 512: the beats of phase_heterodyne_fringes do). The conventions
// of another tool's capture (docs/capture.md, "Reading another tool's phase capture"): phase_coarsest (0 or 1: the
// ladder of periods ends as phase_periods says), phase_origin (degrees, 0 to
// 359) and phase_reversed (0 or 1) place the sinusoids (phase_pattern_level); order_unit (1 or 2: the order code
// counts half periods or whole periods) and order_inverses (1: each order pattern has its inverse; 0: none, each bit
// is decided against the mean of white and black).
inline constexpr const char* kPhaseSteps = "phase_steps";
inline constexpr const char* kPhasePeriod = "phase_period";
inline constexpr const char* kPhaseRatio = "phase_ratio";
inline constexpr const char* kPhaseFringes = "phase_fringes";
inline constexpr const char* kPhaseHeterodyne = "phase_heterodyne";
inline constexpr const char* kPhaseCoarsest = "phase_coarsest";
inline constexpr const char* kPhaseOrigin = "phase_origin";
inline constexpr const char* kPhaseReversed = "phase_reversed";
inline constexpr const char* kOrderUnit = "order_unit";
inline constexpr const char* kOrderInverses = "order_inverses";

std::shared_ptr<const PatternFamily> phase_family();

// How a capture's sinusoids are placed: step k of N at projector coordinate x (pixel centres at integers) is
// 0.5 + 0.5 cos(2 pi x / P + origin - s 2 pi k / N), s = -1 when reversed, else 1. Ours: origin 0, not reversed.
struct PhaseConvention {
  int origin_degrees = 0;
  bool reversed = false;
};

// The shift delta_k = s 2 pi k / N - origin (radians) of step k of N: the pattern is 0.5 + 0.5 cos(2 pi x / P -
// delta_k).
double phase_shift_radians(int step, int steps, PhaseConvention convention);

// Step k of N on an axis at projector coordinate x, before the 8-bit rounding.
double phase_pattern_level(double x, double period, int step, int steps, PhaseConvention convention = {});

// The order index floor(2 x / (unit P)) of projector pixel x (unit 1: half periods; 2: whole periods), which the
// order code carries, and its bit count on an axis of n pixels.
int phase_order(int x, double period, int unit = 1);
int phase_order_bits(int n, double period, int unit = 1);

// The periods of an axis of n pixels, finest first: P alone for ratio 0; else P, P R, P R^2, ... up to the first
// period p with p (R - 1) >= n, then a last one of n + p, which no pixel of the axis sees twice even p / 2 off. Each
// period is at most R times the one before, so each level unwraps the next finer one while its error in projector
// pixels stays under half that one's period. `spanning_last` (another tool's ladder, phase_coarsest 1): P, P R, ...
// up to the first period >= n, none after it; a pixel at the axis's ends may then read the coarsest phase a whole
// period off, and is flagged out of range.
std::vector<double> phase_periods(int n, double period, int ratio, bool spanning_last = false);

// The fringe counts across an axis of heterodyne beat B on F fringes, finest first: F, F - 1 for B = 1 (their beat
// spans the axis once); F, F - B, F - 2 B + 1 for B >= 2 (beats of B and B - 1 fringes, whose own beat spans the axis
// once). Empty for B = 0.
std::vector<int> phase_heterodyne_fringes(int fringes, int beat);

// The periods of the columns (or rows) for options of the phase family, finest first: the ladder of phase_periods,
// or n / f for each heterodyne fringe count f.
std::vector<double> phase_periods(const ProtocolOptions& options, bool columns);

}  // namespace rfrecon::capture
