// C simulation of the HLS C++ tops (hw/hls/), what Vitis calls csim: the tops compiled by the host's C++ compiler
// (HLS pragmas ignored) against the C++ references: the row solvers on the inputs of the OpenCL kernel tests
// (tests/depth/row_solver_inputs.h, as many rows as one interleaved group and a few more), in row tiles smaller than,
// equal to and not dividing a group, with the parameters header's interleaves; the transport's
// decode, compression and sparse products and the phase decoding on the tiny captures of the transport kernel tests;
// the self-check.
#include <algorithm>
#include <array>
#include <functional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <pthread.h>

#include "hls/depth_tops.h"
#include "hls/selfcheck_tops.h"
#include "hls/transport_tops.h"
#include "host/capture/phase_patterns.h"
#include "host/depth/row_solvers.h"
#include "host/selfcheck/axpy.h"
#include "host/transport/phase_accumulators.h"
#include "host/transport/spmv.h"
#include "kernels/transport/gray_decode.h"
#include "tests/depth/row_solver_inputs.h"
#include "tests/transport/same_phase_transport.h"
#include "tests/transport/same_transport.h"
#include "tests/transport/test_capture_feed.h"

namespace rfrecon::depth {
namespace {

using testing::expect_close;

std::size_t tile_offset(const RectifiedRows& rows, int row) { return static_cast<std::size_t>(row) * rows.width; }

// The depth tops keep R x RF_MAX_ROW_WIDTH rows (11 MB for the integration's defaults) in arrays that are on-chip
// memory on a board and, being RF_HLS_STATIC, static storage here: they run on a thread of an 8 MB stack, the size
// glibc gives a thread by default, as Vitis' software emulation runs a kernel (finding #12 of the FPGA review).
template <typename Top>
void on_emulator_stack(Top top) {
  pthread_attr_t attributes;
  ASSERT_EQ(pthread_attr_init(&attributes), 0);
  ASSERT_EQ(pthread_attr_setstacksize(&attributes, std::size_t{8} << 20), 0);
  pthread_t thread;
  const auto run = [](void* argument) -> void* {
    (*static_cast<Top*>(argument))();
    return nullptr;
  };
  ASSERT_EQ(pthread_create(&thread, &attributes, run, &top), 0);
  ASSERT_EQ(pthread_join(thread, nullptr), 0);
  pthread_attr_destroy(&attributes);
}

// The integration top over rows [row_begin, row_end): its buffers hold the tile's rows only, as the kernels' do.
std::vector<float> integrate_top(const RectifiedRows& rows, int passes, int row_begin, int row_end) {
  std::vector<float> z(tile_offset(rows, row_end) - tile_offset(rows, row_begin));
  const RfRectifiedRig& rig = rows.rig;
  on_emulator_stack([&] {
    integrate_rows_single(rig.f, rig.cx_cam, rig.cx_proj, rig.cy, rig.b, row_begin, row_end - row_begin, rows.width,
                          rows.proj_width, passes, rows.e_cam.data() + tile_offset(rows, row_begin),
                          rows.e_proj.data() + static_cast<std::size_t>(row_begin) * rows.proj_width,
                          rows.z_tri.data() + tile_offset(rows, row_begin),
                          rows.runs.data() + tile_offset(rows, row_begin), z.data());
  });
  return z;
}

// The fusion top over rows [row_begin, row_end) from z_all (all rows' starting depths).
std::vector<float> fuse_top(const RectifiedRows& rows, const std::vector<float>& z_all, const FusionOptions& options,
                            int row_begin, int row_end) {
  std::vector<float> z(z_all.begin() + static_cast<std::ptrdiff_t>(tile_offset(rows, row_begin)),
                       z_all.begin() + static_cast<std::ptrdiff_t>(tile_offset(rows, row_end)));
  const RfRectifiedRig& rig = rows.rig;
  on_emulator_stack([&] {
    fuse_rows_single(rig.f, rig.cx_cam, rig.cx_proj, rig.cy, rig.b, row_begin, row_end - row_begin, rows.width,
                     rows.proj_width, options.iterations, options.sigma_disparity_px, options.sigma_step_mm,
                     rows.e_cam.data() + tile_offset(rows, row_begin),
                     rows.e_proj.data() + static_cast<std::size_t>(row_begin) * rows.proj_width,
                     rows.z_tri.data() + tile_offset(rows, row_begin), rows.runs.data() + tile_offset(rows, row_begin),
                     z.data());
  });
  return z;
}

// The tolerance is the OpenCL kernels' (tests/depth/row_solver_inputs.h): the tops run the same per-row arithmetic
// as the references, only with the rows' pixels interleaved, so they should agree far more closely.
// Tiles of 2 rows (smaller than a group), R rows (one whole group) and the rest (a group and a partial one when the
// rows are 2R + 3, else a partial one).
void expect_tiles_match(int interleave, const std::function<std::vector<float>(int, int)>& top,
                        const std::vector<float>& reference, int height) {
  std::vector<float> z;
  for (const auto& [begin, end] : {std::pair{0, 2}, std::pair{2, 2 + interleave}, std::pair{2 + interleave, height}}) {
    const auto tile = top(begin, end);
    z.insert(z.end(), tile.begin(), tile.end());
  }
  expect_close(z, reference);
}

TEST(HlsCsim, IntegrationTopMatchesReferenceOnTiles) {
  const auto rows = testing::kernel_test_rows(2 * RF_INTEGRATE_INTERLEAVE + 3);
  const auto reference = integrate_rows_reference(rows, IntegrationOptions{3}, 0, rows.height);
  expect_tiles_match(
      RF_INTEGRATE_INTERLEAVE, [&](int begin, int end) { return integrate_top(rows, 3, begin, end); }, reference,
      rows.height);
}

TEST(HlsCsim, FusionTopMatchesReferenceOnTiles) {
  const auto rows = testing::kernel_test_rows(2 * RF_FUSE_INTERLEAVE + 3);
  const FusionOptions options;
  const auto start = integrate_rows_reference(rows, IntegrationOptions{3}, 0, rows.height);
  const auto reference = fuse_rows_reference(rows, start, options, 0, rows.height);
  expect_tiles_match(
      RF_FUSE_INTERLEAVE, [&](int begin, int end) { return fuse_top(rows, start, options, begin, end); }, reference,
      rows.height);
}

TEST(HlsCsim, SelfcheckTopMatchesReference) {
  const std::vector<float> x{1, 2, 3, 4, -5};
  std::vector<float> y{0.5f, -1, 2, 8, 0.25f};
  const auto expected = selfcheck::axpy_reference(2.0f, x, y);
  axpy_single(2.0f, x.data(), y.data(), static_cast<unsigned>(y.size()));
  EXPECT_EQ(y, expected);
}

}  // namespace
}  // namespace rfrecon::depth

namespace rfrecon::transport {
namespace {

// The tops' batch of frames, pixel-major (kernels/common/frame_samples.h), as host/transport/device_frames.cc writes
// it.
class FrameBatch {
 public:
  explicit FrameBatch(std::size_t n = 0) : samples_(n) {}
  void set(unsigned slot, const cv::Mat& frame) {
    const float* linear = frame.ptr<float>();
    for (std::size_t c = 0; c < samples_.size(); ++c) samples_[c].sample[slot] = linear[c];
  }
  const RfFrameSamples* data() const { return samples_.data(); }

 private:
  std::vector<RfFrameSamples> samples_;
};

// T's rows and correspondences as the compression's tops take them (kernels/transport/ell_rows.h): the same memory,
// which an aggregate of its element type may access.
RfEllIndices* ell_indices(CompressedTransport& t) { return reinterpret_cast<RfEllIndices*>(t.indices.data()); }
RfEllWeights* ell_weights(CompressedTransport& t) { return reinterpret_cast<RfEllWeights*>(t.weights.data()); }
RfCorrespondence* correspondences(std::vector<float>& xy) { return reinterpret_cast<RfCorrespondence*>(xy.data()); }

// The transport accumulator on the HLS tops, its buffers host vectors, the Gray pairs batched RF_GRAY_PAIR_BATCH and
// the dot frames RF_FRAME_BATCH at a time in one batch buffer, as the device accumulator batches them.
class HlsAccumulator final : public GraycodeAccumulator {
 public:
  explicit HlsAccumulator(TransportSetup setup) {
    setup.thresholds = resolve_thresholds(setup.thresholds, 8);
    t_ = make_empty_transport(setup);
    n_ = static_cast<unsigned>(t_.camera_pixels());
    batch_ = FrameBatch(n_);
  }

  void add_gray_pair(GrayAxis axis, int bit, const cv::Mat& pattern, const cv::Mat& inverse) override {
    batch_.set(2 * gray_pending_, pattern);
    batch_.set(2 * gray_pending_ + 1, inverse);
    pairs_[2 * gray_pending_] = gray_bit_mask(t_.setup, axis, bit);
    pairs_[2 * gray_pending_ + 1] = axis == GrayAxis::kColumns ? 0 : 1;
    if (++gray_pending_ == RF_GRAY_PAIR_BATCH) decode_batch();
  }

  void finish_gray(const cv::Mat& white, const cv::Mat& black) override {
    if (gray_pending_ > 0) decode_batch();
    white_ = white;
    black_ = black;
    gray_finalize_single(white.ptr<float>(), black.ptr<float>(), t_.setup.thresholds.black,
                         t_.setup.projector_size.width, t_.setup.projector_size.height, t_.pixel_x.data(),
                         t_.pixel_y.data(), t_.flags.data(), n_);
  }

  void add_dot_frame(int offset_x, int offset_y, const cv::Mat& frame) override {
    batch_.set(pending_, frame);
    offsets_[2 * pending_] = offset_x;
    offsets_[2 * pending_ + 1] = offset_y;
    if (++pending_ == RF_FRAME_BATCH) compress_batch();
  }

  CompressedTransport finish() override {
    if (pending_ > 0) compress_batch();
    finalize_single(white_.ptr<float>(), black_.ptr<float>(), t_.setup.dot_spacing > 0 ? 1 : 0,
                    t_.setup.projector_size.width, t_.setup.thresholds.noise, t_.flags.data(), t_.pixel_x.data(),
                    t_.pixel_y.data(), ell_indices(t_), ell_weights(t_), t_.direct_energy.data(),
                    correspondences(t_.correspondence), n_);
    return std::move(t_);
  }

 private:
  void decode_batch() {
    gray_pairs_single(batch_.data(), static_cast<int>(gray_pending_), pairs_.data(), t_.setup.thresholds.white,
                      t_.pixel_x.data(), t_.pixel_y.data(), t_.flags.data(), n_);
    gray_pending_ = 0;
    pairs_.fill(0);
  }

  void compress_batch() {
    dot_frames_single(batch_.data(), static_cast<int>(pending_), offsets_.data(), t_.setup.dot_spacing,
                      t_.setup.projector_size.width, t_.setup.projector_size.height, t_.setup.thresholds.noise,
                      black_.ptr<float>(), t_.flags.data(), t_.pixel_x.data(), t_.pixel_y.data(), ell_indices(t_),
                      ell_weights(t_), t_.direct_energy.data(), n_);
    pending_ = 0;
    offsets_.fill(0);
  }

  CompressedTransport t_;
  unsigned n_ = 0;
  cv::Mat white_, black_;
  FrameBatch batch_;
  unsigned gray_pending_ = 0;
  std::array<unsigned, 2 * RF_GRAY_PAIR_BATCH> pairs_ = {};
  unsigned pending_ = 0;
  std::array<int, 2 * RF_FRAME_BATCH> offsets_ = {};
};

// K = RF_K, the tops' (the parameters header's). Gray code only; s = 3, one partial batch of 9 frames; s = 5, 25
// frames over batches of RF_FRAME_BATCH (16 by default: one full, one partial).
TEST(HlsCsim, TransportTopsMatchReference) {
  for (const int spacing : {0, 3, 5}) {
    SCOPED_TRACE("dot spacing " + std::to_string(spacing));
    const auto capture = testing::tiny_capture(spacing);
    const auto linear = testing::linearize(capture.frames);
    const auto setup = testing::setup_for(linear, capture.scene.projector_size, spacing, RF_K);
    auto reference = make_reference_accumulator(setup);
    const auto expected = testing::feed_all(*reference, capture.sequence, linear);
    HlsAccumulator tops(setup);
    testing::expect_same_transport(testing::feed_all(tops, capture.sequence, linear), expected);
  }
}

// Gray pairs over one full batch of RF_GRAY_PAIR_BATCH and a partial one: codes and flags bit for bit.
TEST(HlsCsim, GrayPairsTopOverAFullAndAPartialBatchMatchesReference) {
  const auto capture = testing::tiny_gray_capture_over_batches();
  if (!capture) GTEST_SKIP() << "RF_GRAY_PAIR_BATCH " << RF_GRAY_PAIR_BATCH << " has no tiny partial batch";
  const auto linear = testing::linearize(capture->frames);
  const auto setup = testing::setup_for(linear, capture->scene.projector_size, 0, RF_K);
  auto reference = make_reference_accumulator(setup);
  const auto expected = testing::feed_all(*reference, capture->sequence, linear);
  HlsAccumulator tops(setup);
  testing::expect_same_transport(testing::feed_all(tops, capture->sequence, linear), expected);
}

// The phase family on the HLS tops: phase steps RF_FRAME_BATCH of one axis per call, order pairs RF_GRAY_PAIR_BATCH
// per call of gray_pairs_single, then the dot frames RF_FRAME_BATCH per call of dot_frames_single, as the device
// accumulator batches them.
class HlsPhaseAccumulator final : public TransportAccumulator {
 public:
  explicit HlsPhaseAccumulator(TransportSetup setup)
      : steps_(phase_parameter(setup, capture::kPhaseSteps)),
        order_unit_(order_unit(setup)),
        fringes_(heterodyne_fringes(setup)),
        periods_{axis_periods(setup, 0), axis_periods(setup, 1)} {
    setup.thresholds = resolve_thresholds(setup.thresholds, 8);
    t_ = make_empty_transport(setup);
    n_ = static_cast<unsigned>(t_.camera_pixels());
    batch_ = FrameBatch(n_);
    sums_.assign(4 * static_cast<std::size_t>(n_), 0.0f);
    estimates_.assign(4 * static_cast<std::size_t>(n_), 0.0f);
  }

  void add(const TransportStep& step, const std::vector<cv::Mat>& frames, const cv::Mat& white,
           const cv::Mat& black) override {
    white_ = white;
    black_ = black;
    const int axis = step.args[0];
    if (step.op == kPhaseShiftStep) {
      if (steps_pending_ > 0 && axis != axis_) add_steps();
      axis_ = axis;
      batch_.set(steps_pending_, frames.at(0));
      std::tie(shifts_[2 * steps_pending_], shifts_[2 * steps_pending_ + 1]) = phase_shift(t_.setup, step.args[1]);
      if (++steps_pending_ == RF_FRAME_BATCH) add_steps();
    } else if (step.op == kPhaseFoldStep) {
      if (steps_pending_ > 0) add_steps();
      fold(axis, step.args[1]);
    } else if (step.op == kPhaseDotStep) {
      if (!resolved_) resolve();
      batch_.set(dots_pending_, frames.at(0));
      offsets_[2 * dots_pending_] = step.args[0];
      offsets_[2 * dots_pending_ + 1] = step.args[1];
      if (++dots_pending_ == RF_FRAME_BATCH) add_dots();
    } else {
      if (steps_pending_ > 0) add_steps();
      batch_.set(2 * pairs_pending_, frames.at(0));
      const cv::Mat inverse = frames.size() > 1 ? frames[1] : order_inverse_frame(t_.setup, frames.at(0), white, black);
      batch_.set(2 * pairs_pending_ + 1, inverse);
      pairs_[2 * pairs_pending_] = order_bit_mask(t_.setup, axis, step.args[1]);
      pairs_[2 * pairs_pending_ + 1] = static_cast<unsigned>(axis);
      if (++pairs_pending_ == RF_GRAY_PAIR_BATCH) add_pairs();
    }
  }

  CompressedTransport finish() override {
    if (!resolved_) resolve();
    if (dots_pending_ > 0) add_dots();
    if (t_.setup.dot_spacing > 0) {  // the rows' centroids to scratch: the phases' correspondences stay
      std::vector<float> centroids(2 * static_cast<std::size_t>(n_));
      finalize_single(white_.ptr<float>(), black_.ptr<float>(), 1, t_.setup.projector_size.width,
                      t_.setup.thresholds.noise, t_.flags.data(), t_.pixel_x.data(), t_.pixel_y.data(), ell_indices(t_),
                      ell_weights(t_), t_.direct_energy.data(), correspondences(centroids), n_);
    }
    return std::move(t_);
  }

 private:
  // phase_finalize_single; with the dot grid, T's rows and energies cleared for the dot frames.
  void resolve() {
    resolved_ = true;
    if (steps_pending_ > 0) add_steps();
    if (pairs_pending_ > 0) add_pairs();
    if (!fringes_.empty()) {
      for (int axis = 0; axis < 2; ++axis) fold(axis, 0);
    }
    phase_finalize_single(white_.ptr<float>(), black_.ptr<float>(), t_.setup.thresholds.black,
                          t_.setup.thresholds.white, steps_, static_cast<float>(periods_[0].front()),
                          static_cast<float>(periods_[1].front()), order_unit_, t_.setup.projector_size.width,
                          t_.setup.projector_size.height, t_.k(), t_.pixel_x.data(), t_.pixel_y.data(), sums_.data(),
                          estimates_.data(), t_.flags.data(), t_.indices.data(), t_.weights.data(),
                          t_.direct_energy.data(), t_.correspondence.data(), n_);
    if (t_.setup.dot_spacing == 0) return;
    std::fill(t_.indices.begin(), t_.indices.end(), -1);
    std::fill(t_.weights.begin(), t_.weights.end(), 0.0f);
    std::fill(t_.direct_energy.begin(), t_.direct_energy.end(), 0.0f);
  }

  // phase_fold_single, or with beats phase_beat_single, as the device accumulator calls them.
  void fold(int axis, int level) {
    const int n = axis == 0 ? t_.setup.projector_size.width : t_.setup.projector_size.height;
    if (fringes_.empty()) {
      phase_fold_single(axis, static_cast<float>(periods_[axis].at(level)),
                        level + 1 == static_cast<int>(periods_[axis].size()) ? 1 : 0, 0.5f * static_cast<float>(n - 1),
                        steps_, t_.setup.thresholds.white, sums_.data(), estimates_.data(), t_.flags.data(), n_);
    } else {
      phase_beat_single(axis, level, fringes_[0], fringes_[1], fringes_.size() > 2 ? fringes_[2] : 0,
                        static_cast<float>(n), steps_, t_.setup.thresholds.white, sums_.data(), estimates_.data(),
                        t_.flags.data(), n_);
    }
  }

  void add_dots() {
    dot_frames_single(batch_.data(), static_cast<int>(dots_pending_), offsets_.data(), t_.setup.dot_spacing,
                      t_.setup.projector_size.width, t_.setup.projector_size.height, t_.setup.thresholds.noise,
                      black_.ptr<float>(), t_.flags.data(), t_.pixel_x.data(), t_.pixel_y.data(), ell_indices(t_),
                      ell_weights(t_), t_.direct_energy.data(), n_);
    dots_pending_ = 0;
    offsets_.fill(0);
  }

  void add_steps() {
    phase_steps_single(batch_.data(), axis_, static_cast<int>(steps_pending_), shifts_.data(), sums_.data(), n_);
    steps_pending_ = 0;
    shifts_.fill(0.0f);
  }

  void add_pairs() {
    gray_pairs_single(batch_.data(), static_cast<int>(pairs_pending_), pairs_.data(), t_.setup.thresholds.white,
                      t_.pixel_x.data(), t_.pixel_y.data(), t_.flags.data(), n_);
    pairs_pending_ = 0;
    pairs_.fill(0);
  }

  int steps_;
  int order_unit_;
  std::vector<int> fringes_;
  std::vector<double> periods_[2];
  CompressedTransport t_;
  unsigned n_ = 0;
  cv::Mat white_, black_;
  FrameBatch batch_;
  std::vector<float> sums_;
  std::vector<float> estimates_;
  int axis_ = 0;
  unsigned steps_pending_ = 0;
  std::array<float, 2 * RF_FRAME_BATCH> shifts_ = {};
  unsigned pairs_pending_ = 0;
  std::array<unsigned, 2 * RF_GRAY_PAIR_BATCH> pairs_ = {};
  bool resolved_ = false;
  unsigned dots_pending_ = 0;
  std::array<int, 2 * RF_FRAME_BATCH> offsets_ = {};
};

// 5 steps of period 4 (a partial batch per axis) and RF_FRAME_BATCH + 2 steps of period 6 (a full and a partial one)
// unwrapped by the order code, 4 steps of period 4 unwrapped by periods 8, 16, ... (ratio 2), and a 5 x 5 dot grid
// after 4 steps of period 4 (25 dot frames: a full and a partial batch); another tool's conventions (sines, an order
// code of whole periods without inverses); heterodyne beats of 4, 2 and 1 fringes (phase_beat_single).
TEST(HlsCsim, PhaseTopsMatchReference) {
  for (const testing::PhaseParameters phase :
       {testing::PhaseParameters{5, 4}, testing::PhaseParameters{RF_FRAME_BATCH + 2, 6},
        testing::PhaseParameters{4, 4, 2}, testing::PhaseParameters{4, 4, 0, 5},
        testing::PhaseParameters{3, 4, 0, 0, 270, 1, 2, 0},
        testing::PhaseParameters{5, 4, 0, 0, 0, 0, 1, 1, 0, 4, 2, 24, 16}}) {
    SCOPED_TRACE("steps " + std::to_string(phase.steps) + " ratio " + std::to_string(phase.ratio) + " dots " +
                 std::to_string(phase.dot_spacing));
    const auto capture = testing::tiny_phase_capture(phase);
    const auto linear = testing::linearize(capture.frames);
    const auto setup = testing::phase_setup_for(linear, phase, RF_K);
    const auto expected =
        testing::feed_plan(*make_phase_reference_accumulator(setup), "phase", capture.sequence, linear, linear);
    HlsPhaseAccumulator tops(setup);
    testing::expect_same_phase_transport(testing::feed_plan(tops, "phase", capture.sequence, linear, linear), expected);
  }
}

// The products sum in the references' order: bit for bit.
TEST(HlsCsim, SparseProductTopsMatchReference) {
  const auto transport = testing::tiny_reference_transport(3, RF_K);
  const auto [light_p, light_c] = testing::random_lights(transport);

  std::vector<float> primal(transport.camera_pixels());
  primal_single(transport.indices.data(), transport.weights.data(), light_p.data(), primal.data(),
                static_cast<unsigned>(primal.size()));
  EXPECT_EQ(primal, primal_reference(transport, light_p));
  const auto transposed = transpose(transport);
  std::vector<float> dual(transport.projector_pixels());
  const auto rows = entry_rows(transposed.row_start, 0, dual.size());
  dual_single(transposed.row_start.data(), rows.data(), transposed.camera_pixel.data(), transposed.weights.data(),
              light_c.data(), dual.data(), static_cast<unsigned>(dual.size()));
  EXPECT_EQ(dual, dual_reference(transport, light_c));
}

}  // namespace
}  // namespace rfrecon::transport
