// Throughput of Gray code decoding and transport compression at full size (camera 1280x1024, projector 1024x768,
// standard protocol with an 8 x 8 dot grid), C++ reference and OpenCL, against OpenCV structured_light's
// GrayCodePattern decoding of the same frames and the host's memory-bandwidth roofline (bench/bench_common.h).
// Prints the ratios after the runs. Frames are synthetic (a plane seen at 0.8 projector pixels per camera pixel).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <numeric>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "bench/opencv_graycode.h"
#include "host/capture/protocol.h"
#include "host/cl/device_selection.h"
#include "host/transport/gray_decision.h"
#include "host/transport/gray_subpixel.h"
#include "host/transport/graycode_accumulator.h"

namespace {

using namespace rfrecon;

const cv::Size kCamera(1280, 1024);
const cv::Size kProjector(1024, 768);
constexpr int kDotSpacing = 8;
constexpr int kDotFramesKept = 16;  // dot frames held in memory; the benchmark cycles through them

struct Frames {
  std::vector<capture::Pattern> gray_sequence;  // make_protocol order: white, black, then the Gray pairs
  std::vector<cv::Mat> raw;                     // 8-bit, as a camera saves them (for OpenCV)
  std::vector<cv::Mat> linear;                  // CV_32F, linear [0, 1] (for rfrecon)
  std::vector<capture::Pattern> dot_patterns;
  std::vector<cv::Mat> dots;  // CV_32F
};

// Camera pixel (u, v) sees projector pixel (0.8 u, 0.75 v): value 0.8 * lit + 0.03 ambient, 1 DN noise, 8 bits.
cv::Mat render(const capture::Pattern& pattern, cv::RNG& random) {
  const cv::Mat projected = capture::render_pattern(pattern, {kProjector, kDotSpacing});
  cv::Mat noise(kCamera, CV_32F);
  random.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
  cv::Mat frame(kCamera, CV_8U);
  for (int v = 0; v < kCamera.height; ++v) {
    const auto* row = projected.ptr<unsigned char>(static_cast<int>(0.75 * v));
    for (int u = 0; u < kCamera.width; ++u) {
      const double reading = 255.0 * (0.8 * row[static_cast<int>(0.8 * u)] / 255.0 + 0.03) + noise.at<float>(v, u);
      frame.at<unsigned char>(v, u) = cv::saturate_cast<unsigned char>(reading);
    }
  }
  return frame;
}

const Frames& frames() {
  static const Frames instance = [] {
    Frames f;
    cv::RNG random(1);
    for (const auto& pattern : capture::make_protocol({kProjector, kDotSpacing})) {
      if (pattern.kind == capture::pattern_kind::kDot) {
        if (f.dots.size() == kDotFramesKept) continue;
        cv::Mat linear;
        render(pattern, random).convertTo(linear, CV_32F, 1.0 / 255.0);
        f.dot_patterns.push_back(pattern);
        f.dots.push_back(linear);
        continue;
      }
      f.gray_sequence.push_back(pattern);
      f.raw.push_back(render(pattern, random));
      cv::Mat linear;
      f.raw.back().convertTo(linear, CV_32F, 1.0 / 255.0);
      f.linear.push_back(linear);
    }
    return f;
  }();
  return instance;
}

transport::TransportSetup setup() {
  transport::TransportSetup s;
  s.camera_size = kCamera;
  s.projector_size = kProjector;
  s.dot_spacing = kDotSpacing;
  return s;
}

double frame_bytes() { return static_cast<double>(kCamera.area()) * sizeof(float); }

// GB/s counts the camera frames processed as float (4 bytes per pixel, OpenCV's 8-bit frames included), so every
// benchmark is measured on the same bytes; roofline_fraction divides it by the host's streaming bandwidth.
void set_counters(benchmark::State& state, double frames_per_iteration, double bytes_per_iteration) {
  const auto iterations = static_cast<double>(state.iterations());
  state.counters["frames/s"] = benchmark::Counter(frames_per_iteration * iterations, benchmark::Counter::kIsRate);
  rfrecon::bench::set_bandwidth_counters(state, bytes_per_iteration);
}

void decode(transport::GraycodeAccumulator& accumulator) {
  const auto& f = frames();
  for (std::size_t i = 2; i < f.gray_sequence.size(); i += 2) {
    const auto& pattern = f.gray_sequence[i];
    const auto axis =
        pattern.kind == capture::pattern_kind::kGrayColumn ? transport::GrayAxis::kColumns : transport::GrayAxis::kRows;
    accumulator.add_gray_pair(axis, pattern.bit, f.linear[i], f.linear[i + 1]);
  }
  accumulator.finish_gray(f.linear[0], f.linear[1]);
}

rfrecon::cl::DeviceContext& device() {
  static std::vector<rfrecon::cl::DeviceContext> devices = rfrecon::cl::open_devices("");
  return devices.front();
}
rfrecon::cl::ProgramCache& programs() {
  static rfrecon::cl::ProgramCache cache;
  return cache;
}

void BM_DecodeReference(benchmark::State& state) {
  const auto& f = frames();
  for (auto _ : state) {
    auto accumulator = transport::make_reference_accumulator(setup());
    decode(*accumulator);
  }
  set_counters(state, static_cast<double>(f.linear.size()), f.linear.size() * frame_bytes());
}

void BM_DecodeOpenCL(benchmark::State& state) {
  const auto& f = frames();
  const auto entry = transport::KernelEntry::kNdRange;
  auto accumulator = transport::make_device_accumulator(setup(), device(), programs(), entry);  // builds kernels
  for (auto _ : state) {
    state.PauseTiming();
    accumulator = transport::make_device_accumulator(setup(), device(), programs(), entry);
    state.ResumeTiming();
    decode(*accumulator);  // uploads every frame and waits for each batch's kernel
  }
  set_counters(state, static_cast<double>(f.linear.size()), f.linear.size() * frame_bytes());
}

// OpenCV's single-camera decoding: shadow mask from white/black (black threshold), then getProjPixel per pixel
// (bench/opencv_graycode.h).
void BM_DecodeOpenCV(benchmark::State& state) {
  const auto& f = frames();
  const bench::OpencvGrayFrames gray{kProjector, f.raw[0], f.raw[1], {f.raw.begin() + 2, f.raw.end()}};
  for (auto _ : state) {
    const bench::OpencvCorrespondences decoded = bench::opencv_gray_decode(gray, 10, 5);  // rfrecon's defaults, 8-bit
    benchmark::DoNotOptimize(decoded.projector_px.data());
  }
  set_counters(state, static_cast<double>(f.raw.size()), f.raw.size() * frame_bytes());
}

template <typename MakeAccumulator>
void compress(benchmark::State& state, MakeAccumulator make) {
  const auto& f = frames();
  auto accumulator = make();
  decode(*accumulator);
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& pattern = f.dot_patterns[i % f.dots.size()];
    accumulator->add_dot_frame(pattern.dot_offset_x, pattern.dot_offset_y, f.dots[i % f.dots.size()]);
    ++i;
  }
  set_counters(state, 1.0, frame_bytes());
}

void BM_CompressReference(benchmark::State& state) {
  compress(state, [] { return transport::make_reference_accumulator(setup()); });
}

void BM_CompressOpenCL(benchmark::State& state) {
  const auto entry = transport::KernelEntry::kNdRange;
  compress(state, [&] { return transport::make_device_accumulator(setup(), device(), programs(), entry); });
}

// The host's part of a Gray-code-only capture of the same frames: GrayDecision and GraySubpixel fed every pair, then
// decide() and refine() on a copy of the decoded transport (one entry per pixel). `refine_seconds`: the fastest
// refine() of the iterations, the least disturbed by other work on the machine (a compute-bound host stage: no
// bandwidth counters).
void BM_GraySubpixel(benchmark::State& state) {
  const auto& f = frames();
  transport::TransportSetup gray_only = setup();
  gray_only.dot_spacing = 0;
  gray_only.entries_per_pixel = 1;
  auto accumulator = transport::make_reference_accumulator(gray_only);
  decode(*accumulator);
  const transport::CompressedTransport decoded = accumulator->finish();
  double refine_seconds = std::numeric_limits<double>::infinity();
  for (auto _ : state) {
    transport::GrayDecision decision(f.linear[0], f.linear[1]);
    transport::GraySubpixel subpixel(kCamera);
    for (std::size_t i = 2; i < f.gray_sequence.size(); i += 2) {
      const auto& pattern = f.gray_sequence[i];
      const auto axis = pattern.kind == capture::pattern_kind::kGrayColumn ? transport::GrayAxis::kColumns
                                                                           : transport::GrayAxis::kRows;
      decision.add_gray_pair(axis, transport::gray_bit_mask(gray_only, axis, pattern.bit), f.linear[i],
                             f.linear[i + 1]);
      subpixel.add_gray_pair(axis, f.linear[i], f.linear[i + 1]);
    }
    transport::CompressedTransport transport = decoded;
    decision.decide(transport);
    const auto start = std::chrono::steady_clock::now();
    subpixel.refine(transport);
    refine_seconds =
        std::min(refine_seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    benchmark::DoNotOptimize(transport.correspondence.data());
  }
  state.counters["refine_seconds"] = refine_seconds;
}

// Wall-clock rates throughout (the OpenCL runs spend their time in PoCL's threads, not the calling one).
BENCHMARK(BM_DecodeReference)->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime();
BENCHMARK(BM_DecodeOpenCL)->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime();
BENCHMARK(BM_DecodeOpenCV)->Unit(benchmark::kMillisecond)->Iterations(2)->UseRealTime();
BENCHMARK(BM_CompressReference)->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime();
BENCHMARK(BM_CompressOpenCL)->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime();
BENCHMARK(BM_GraySubpixel)->Unit(benchmark::kMillisecond)->Iterations(8)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  rfrecon::bench::add_run_context();
  rfrecon::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto ratio = [](double a, double b) { return b > 0.0 ? a / b : 0.0; };
  const double opencv = reporter.seconds("BM_DecodeOpenCV");
  std::printf("\nspeed-up over OpenCV GrayCodePattern decoding (same frames): reference %.1fx, OpenCL %.1fx\n",
              ratio(opencv, reporter.seconds("BM_DecodeReference")),
              ratio(opencv, reporter.seconds("BM_DecodeOpenCL")));
  std::printf(
      "fraction of the host streaming roofline (%.2f GB/s): decode reference %.2f, decode OpenCL %.2f, "
      "compress reference %.2f, compress OpenCL %.2f\n",
      rfrecon::bench::host_stream_bytes_per_second() / 1e9, reporter.counter("BM_DecodeReference", "roofline_fraction"),
      reporter.counter("BM_DecodeOpenCL", "roofline_fraction"),
      reporter.counter("BM_CompressReference", "roofline_fraction"),
      reporter.counter("BM_CompressOpenCL", "roofline_fraction"));
  benchmark::Shutdown();
  return 0;
}
