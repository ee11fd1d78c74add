// The phase family's accumulator on one OpenCL device: kernels/transport/phase.cl for the phase steps and the
// finalizing, decode.cl's Gray pairs for the order codes, compress.cl's dot frames for T's rows. The transport's own
// arrays are the kernels' state.
#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "host/capture/phase_patterns.h"
#include "host/cl/error.h"
#include "host/cl/kernel_launch.h"
#include "host/transport/device_frames.h"
#include "host/transport/dot_rows.h"
#include "host/transport/phase_accumulators.h"
#include "kernels/transport/gray_decode.h"

namespace rfrecon::transport {

namespace {

class PhaseDeviceAccumulator final : public TransportAccumulator {
 public:
  PhaseDeviceAccumulator(const TransportSetup& setup, cl::DeviceContext& device, cl::ProgramCache& programs,
                         KernelEntry entry, const std::string& build_options, CompressedTransport storage)
      : setup_(setup),
        device_(device),
        steps_(phase_parameter(setup, capture::kPhaseSteps)),
        order_unit_(order_unit(setup)),
        fringes_(heterodyne_fringes(setup)),
        periods_{axis_periods(setup, 0), axis_periods(setup, 1)},
        frames_(setup, device, entry, kBatch, transport_private_bytes(setup.entries_per_pixel)),
        state_(make_empty_transport(setup, std::move(storage))) {
    if (setup.entries_per_pixel < 1) throw std::invalid_argument("transport: K must be at least 1");
    const std::vector<cl::ProgramRequest> requests = phase_programs(setup, entry, build_options);
    const ::cl::Program decode = programs.get(device, requests[0].kernel_path, requests[0].options);
    const ::cl::Program phase = programs.get(device, requests[1].kernel_path, requests[1].options);
    order_pairs_ = cl::make_kernel(decode, "gray_pairs", entry);
    phase_steps_ = cl::make_kernel(phase, "phase_steps", entry);
    fold_ = cl::make_kernel(phase, fringes_.empty() ? "phase_fold" : "phase_beat", entry);
    finalize_ = cl::make_kernel(phase, "phase_finalize", entry);
    if (setup.dot_spacing > 0) {
      const ::cl::Program compress = programs.get(device, requests[2].kernel_path, requests[2].options);
      dot_frames_ = cl::make_kernel(compress, "dot_frames", entry);
      rows_finalize_ = cl::make_kernel(compress, "finalize", entry);
    }

    const ::cl::Context& context = device.context();
    pairs_buffer_ = cl::make_buffer<cl_uint>(context, pairs_.size());
    shifts_buffer_ = cl::make_buffer<float>(context, shifts_.size());
    const std::vector<float> zeros(4 * state_.camera_pixels(), 0.0f);
    sums_ = cl::upload(context, zeros.data(), zeros.size(), CL_MEM_READ_WRITE);
    // One estimate per axis, or with beats two slots of phases per axis (phase_beat).
    estimates_ =
        cl::upload(context, zeros.data(), fringes_.empty() ? zeros.size() / 2 : zeros.size(), CL_MEM_READ_WRITE);
    // T's arrays, the order codes in pixel_x / pixel_y until phase_finalize writes the projector pixels there.
    code_x_ = cl::share(context, state_.pixel_x);
    code_y_ = cl::share(context, state_.pixel_y);
    flags_ = cl::share(context, state_.flags);
    indices_ = cl::share(context, state_.indices);
    weights_ = cl::share(context, state_.weights);
    energy_ = cl::share(context, state_.direct_energy);
    correspondence_ = cl::share(context, state_.correspondence);
  }

  void add(const TransportStep& step, const std::vector<cv::Mat>& frames, const cv::Mat& white,
           const cv::Mat& black) override {
    white_ = white;
    black_ = black;
    const int axis = step.args[0];
    if (step.op == kPhaseShiftStep) {
      if (steps_pending_ > 0 && axis != steps_axis_) add_steps();
      steps_axis_ = axis;
      frames_.add(steps_pending_, frames.at(0));
      const auto [sin_delta, cos_delta] = phase_shift(setup_, step.args[1]);
      shifts_[2 * steps_pending_] = sin_delta;
      shifts_[2 * steps_pending_ + 1] = cos_delta;
      if (++steps_pending_ == kBatch) add_steps();
    } else if (step.op == kOrderPairStep) {
      if (steps_pending_ > 0) add_steps();  // the batch's frames are the phase steps' until they have run
      frames_.add(2 * pairs_pending_, frames.at(0));
      frames_.add(2 * pairs_pending_ + 1,
                  frames.size() > 1 ? frames[1] : order_inverse_frame(setup_, frames.at(0), white, black));
      pairs_[2 * pairs_pending_] = order_bit_mask(setup_, axis, step.args[1]);
      pairs_[2 * pairs_pending_ + 1] = static_cast<cl_uint>(axis);
      if (++pairs_pending_ == kPairBatch) add_pairs();
    } else if (step.op == kPhaseFoldStep) {
      if (steps_pending_ > 0) add_steps();
      fold(axis, step.args[1]);
    } else if (step.op == kPhaseDotStep) {
      if (!resolved_) resolve();
      check_dot_offsets(setup_, step.args[0], step.args[1]);
      frames_.add(dots_pending_, frames.at(0));
      offsets_[2 * dots_pending_] = step.args[0];
      offsets_[2 * dots_pending_ + 1] = step.args[1];
      if (++dots_pending_ == kBatch) add_dots();
    } else {
      throw std::invalid_argument("PhaseDeviceAccumulator::add: not a phase step");
    }
  }

  CompressedTransport finish() override {
    if (!resolved_) resolve();
    if (dots_pending_ > 0) add_dots();
    if (setup_.dot_spacing > 0) {
      // compress.cl's finalize flags the pixels no dot reached; its centroids go to the phase sums (4 n floats, done
      // with since phase_finalize), the phases' correspondences stay.
      cl::set_args(rows_finalize_, frames_.white(), frames_.black(), 1, setup_.projector_size.width,
                   setup_.thresholds.noise, flags_, code_x_, code_y_, indices_, weights_, energy_, sums_,
                   frames_.count());
      frames_.run(rows_finalize_, frames_.count());
    }
    for (const auto* buffer : {&code_x_, &code_y_, &flags_, &indices_, &weights_, &energy_, &correspondence_}) {
      cl::sync_to_host(device_.queue(), *buffer);
    }
    code_x_ = code_y_ = flags_ = indices_ = weights_ = energy_ = correspondence_ = sums_ = estimates_ = ::cl::Buffer();
    frames_.release();
    return std::move(state_);
  }

 private:
  // Flags, projector pixels and correspondences from the phases (phase_finalize, which also writes T's single entry);
  // with the dot grid, T's rows and energies then start empty for the dot frames.
  void resolve() {
    resolved_ = true;
    if (steps_pending_ > 0) add_steps();
    if (pairs_pending_ > 0) add_pairs();
    if (!fringes_.empty()) {
      for (int axis = 0; axis < 2; ++axis) fold(axis, 0);  // the finest level's beats into the estimates
    }
    frames_.set_white_black(white_, black_);
    cl::set_args(finalize_, frames_.white(), frames_.black(), setup_.thresholds.black, setup_.thresholds.white, steps_,
                 static_cast<float>(periods_[0].front()), static_cast<float>(periods_[1].front()), order_unit_,
                 setup_.projector_size.width, setup_.projector_size.height, setup_.entries_per_pixel, code_x_, code_y_,
                 sums_, estimates_, flags_, indices_, weights_, energy_, correspondence_, frames_.count());
    frames_.run(finalize_, frames_.lanes_items());
    if (setup_.dot_spacing == 0) return;
    ::cl::CommandQueue& queue = device_.queue();
    const std::size_t entries = state_.camera_pixels() * static_cast<std::size_t>(setup_.entries_per_pixel);
    RF_CL_CHECK(queue.enqueueFillBuffer(indices_, cl_int{-1}, 0, entries * sizeof(cl_int)));
    RF_CL_CHECK(queue.enqueueFillBuffer(weights_, 0.0f, 0, entries * sizeof(float)));
    RF_CL_CHECK(queue.enqueueFillBuffer(energy_, 0.0f, 0, state_.camera_pixels() * sizeof(float)));
  }

  // One launch over the pending dot frames into T's rows (compress.cl's dot_frames; rows filled, never fresh).
  void add_dots() {
    frames_.run_dot_frames(dot_frames_, dots_pending_, offsets_, false,
                           {flags_, code_x_, code_y_, indices_, weights_, energy_});
    dots_pending_ = 0;
    offsets_.fill(0);
  }

  // One launch over the pending phase steps (all of axis steps_axis_); unused slots' shifts stay 0.
  void add_steps() {
    cl::write_buffer(device_.queue(), shifts_buffer_, shifts_.data(), shifts_.size(), false);
    const cl_uint next = frames_.set_arguments(phase_steps_, steps_pending_);
    cl::set_args_from(phase_steps_, next, static_cast<cl_int>(steps_axis_), static_cast<cl_int>(steps_pending_),
                      shifts_buffer_, sums_, frames_.count());
    frames_.run_batch(phase_steps_);
    steps_pending_ = 0;
    shifts_.fill(0.0f);
  }

  // The sums of period `level` of the axis folded into its estimate (phase_fold), or with beats kept as the level's
  // phase, the finest level (0) made into the estimate (phase_beat).
  void fold(int axis, int level) {
    const int n = axis == 0 ? setup_.projector_size.width : setup_.projector_size.height;
    if (fringes_.empty()) {
      const bool coarsest = level + 1 == static_cast<int>(periods_[axis].size());
      cl::set_args(fold_, static_cast<cl_int>(axis), static_cast<float>(periods_[axis].at(level)), coarsest ? 1 : 0,
                   0.5f * (n - 1), steps_, setup_.thresholds.white, sums_, estimates_, flags_, frames_.count());
    } else {
      cl::set_args(fold_, static_cast<cl_int>(axis), static_cast<cl_int>(level), fringes_[0], fringes_[1],
                   fringes_.size() > 2 ? fringes_[2] : 0, static_cast<float>(n), steps_, setup_.thresholds.white, sums_,
                   estimates_, flags_, frames_.count());
    }
    frames_.run(fold_, frames_.lanes_items());
  }

  // One launch over the pending order pairs; unused slots stay 0 (the kernel skips those pairs).
  void add_pairs() {
    cl::write_buffer(device_.queue(), pairs_buffer_, pairs_.data(), pairs_.size(), false);
    const cl_uint next = frames_.set_arguments(order_pairs_, 2 * pairs_pending_);
    cl::set_args_from(order_pairs_, next, static_cast<cl_int>(pairs_pending_), pairs_buffer_, setup_.thresholds.white,
                      code_x_, code_y_, flags_, frames_.count());
    frames_.run_batch(order_pairs_);
    pairs_pending_ = 0;
    pairs_.fill(0);
  }

  static constexpr std::size_t kBatch = RF_FRAME_BATCH;
  static constexpr std::size_t kPairBatch = RF_GRAY_PAIR_BATCH;

  TransportSetup setup_;
  cl::DeviceContext& device_;
  int steps_;
  int order_unit_;            // the finalize kernel's by_order
  std::vector<int> fringes_;  // the heterodyne fringe counts, finest first; empty without beats
  std::vector<double> periods_[2];
  DeviceFrames frames_;  // the batch of phase steps, of order pairs (pair p: frames 2p and 2p + 1) or of dot frames
  CompressedTransport state_;  // the kernels' state, shared with them (cl::share) until finish() returns it
  cv::Mat white_, black_;
  ::cl::Kernel order_pairs_, phase_steps_, fold_, finalize_, dot_frames_, rows_finalize_;
  ::cl::Buffer pairs_buffer_, shifts_buffer_, sums_, estimates_, code_x_, code_y_, flags_, indices_, weights_, energy_,
      correspondence_;
  std::size_t steps_pending_ = 0;                              // phase steps in the batch not yet added
  int steps_axis_ = 0;                                         // their axis
  std::array<float, 2 * kBatch> shifts_ = {};                  // their (sin, cos) of the phase shift
  std::size_t pairs_pending_ = 0;                              // order pairs in the batch not yet decoded
  std::array<cl_uint, 2 * kPairBatch> pairs_ = {};             // their (bit mask, axis)
  bool resolved_ = false;                                      // phase_finalize has run
  std::size_t dots_pending_ = 0;                               // dot frames in the batch not yet compressed
  std::array<cl_int, 2 * DeviceFrames::kSlots> offsets_ = {};  // their (x, y) dot offsets
};

}  // namespace

std::unique_ptr<TransportAccumulator> make_phase_device_accumulator(TransportSetup setup, cl::DeviceContext& device,
                                                                    cl::ProgramCache& programs, KernelEntry entry,
                                                                    const std::string& build_options,
                                                                    CompressedTransport storage) {
  check_kernel_dot_spacing(setup.dot_spacing);
  setup.thresholds = resolve_thresholds(setup.thresholds, 8);
  return std::make_unique<PhaseDeviceAccumulator>(setup, device, programs, entry, build_options, std::move(storage));
}

}  // namespace rfrecon::transport
