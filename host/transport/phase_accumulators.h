// The phase family's accumulator steps and its two accumulators: the plain C++ reference (phase_decoding.cc) and the
// OpenCL kernels of kernels/transport/phase.cl, with decode.cl's Gray pairs for the order codes and compress.cl's dot
// frames (phase_device_accumulator.cc). Both take the steps PhaseDecoding::plan makes: every phase step, then every
// order pair, or for each axis its periods' steps from the coarsest, each but the finest followed by its fold; then the
// dot frames; the frames of the setup's frame depth, white and black linear CV_32F.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/program_cache.h"
#include "host/transport/accumulator.h"
#include "host/transport/transport_types.h"

namespace rfrecon::transport {

// TransportStep::op of the phase family: an order pair (frames pattern and inverse, or the pattern alone when the
// capture has no inverses: order_inverse_frame; args axis, bit from the most significant), a phase step (frame; args
// axis, step index) and, after the steps of every period but the finest, the fold of their sums into the axis's
// unwrapped estimate, or with beats into the level's phase kept for heterodyne_estimate (no frame; args axis, level),
// and after all of those a dot frame (args its offsets), which goes
// into T's rows at the projector pixel the phases found (host/transport/dot_rows.h) while the correspondence stays the
// phases'. Axis 0: columns.
enum PhaseStep : int { kOrderPairStep, kPhaseShiftStep, kPhaseFoldStep, kPhaseDotStep };

// The periods of an axis (capture::phase_periods for the setup's projector and parameters), finest first.
std::vector<double> axis_periods(const TransportSetup& setup, int axis);

// The heterodyne fringe counts of the setup, finest first (capture::phase_heterodyne_fringes); empty without beats.
std::vector<int> heterodyne_fringes(const TransportSetup& setup);

// A parameter of the setup (capture::kPhaseSteps, kPhasePeriod), or the family's default where the setup has none.
int phase_parameter(const TransportSetup& setup, const char* name);

// (sin, cos) of step `step`'s phase shift (capture::phase_shift_radians with the setup's steps and conventions),
// rounded to float: what both accumulators multiply by.
std::pair<float, float> phase_shift(const TransportSetup& setup, int step);

// The order code's stripe width in half periods (the finalize kernel's by_order): the setup's order_unit when the order
// code unwraps, 0 when longer periods or beats do.
int order_unit(const TransportSetup& setup);

// The frame an order pattern captured without its inverse is decided against: white + black - pattern, of the setup's
// frame depth (raw samples rounded), so that pattern > it where the pattern is brighter than the mean of white and
// black (linear). White and black linear CV_32F.
cv::Mat order_inverse_frame(const TransportSetup& setup, const cv::Mat& pattern, const cv::Mat& white,
                            const cv::Mat& black);

// The bit mask of order bit `bit` (0 = most significant) of `axis` in its code word.
std::uint32_t order_bit_mask(const TransportSetup& setup, int axis, int bit);

// Automatic thresholds (<= 0) are resolved for an 8-bit camera, as make_reference_accumulator does.
std::unique_ptr<TransportAccumulator> make_phase_reference_accumulator(TransportSetup setup);

// decode.cl (the order pairs) and phase.cl, with the NDRange entries' sample type and `extra` options; then, for a
// capture with the dot grid, compress.cl.
std::vector<cl::ProgramRequest> phase_programs(const TransportSetup& setup, KernelEntry entry,
                                               const std::string& extra = {});

// The kernels' state (the order codes, the phase sums, the unwrapped estimates, the flags, T) stays on the device until
// finish(). Phase steps and dot frames go RF_FRAME_BATCH per launch (steps of one axis), order pairs
// RF_GRAY_PAIR_BATCH; dot frames through compress.cl. `build_options` as
// make_device_accumulator's; `storage`: an earlier transport whose memory it may reuse.
std::unique_ptr<TransportAccumulator> make_phase_device_accumulator(TransportSetup setup, cl::DeviceContext& device,
                                                                    cl::ProgramCache& programs, KernelEntry entry,
                                                                    const std::string& build_options = {},
                                                                    CompressedTransport storage = {});

}  // namespace rfrecon::transport
