// The multi-device scheduler: one versus two PoCL devices on the dual and primal products (full size: camera
// 1280x1024, projector 1024x768, K = 8) and on the transport stage (a 640x512 capture of a 512x384 projector with an
// 8 x 8 dot grid, read from PNG files), and the scheduling overhead on a tiny product (80x64 camera) against the
// direct single-device call. Unless POCL_DEVICES is set, it runs itself again with POCL_DEVICES="pthread pthread",
// so PoCL exposes two CPU devices; on one machine they share the same cores, so two devices measure
// the scheduler's overhead and balance, not extra hardware. Prints the ratios after the runs.
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>

#include <benchmark/benchmark.h>
#include <opencv2/imgcodecs.hpp>
#include <unistd.h>

#include "bench/bench_common.h"
#include "host/capture/manifest.h"
#include "host/capture/protocol.h"
#include "host/cl/device_selection.h"
#include "host/transport/compute_transport.h"
#include "host/transport/spmv_on_devices.h"

namespace {

using namespace rfrecon;
namespace fs = std::filesystem;

std::vector<rfrecon::cl::DeviceContext>& all_devices() {
  static std::vector<rfrecon::cl::DeviceContext> devices = rfrecon::cl::open_devices("");
  return devices;
}

// The first `count` devices (fewer when the machine has fewer: the run's label says how many were used).
std::vector<rfrecon::cl::DeviceContext> devices(std::size_t count) {
  auto& all = all_devices();
  return {all.begin(), all.begin() + static_cast<std::ptrdiff_t>(std::min(count, all.size()))};
}

rfrecon::cl::ProgramCache& programs() {
  static rfrecon::cl::ProgramCache cache;
  return cache;
}

// Camera pixel (u, v) sees projector pixel (0.8 u, 0.75 v); its K entries spread over the 3 x 3 neighbourhood.
transport::CompressedTransport synthetic_transport(cv::Size camera, cv::Size projector) {
  transport::TransportSetup setup;
  setup.camera_size = camera;
  setup.projector_size = projector;
  auto t = transport::make_empty_transport(setup);
  std::mt19937 random(1);
  std::uniform_real_distribution<float> weight(0.01f, 1.0f);
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const std::size_t c = static_cast<std::size_t>(v) * camera.width + u;
      for (int k = 0; k < t.k(); ++k) {
        const int x = std::clamp(static_cast<int>(0.8 * u) + k % 3 - 1, 0, projector.width - 1);
        const int y = std::clamp(static_cast<int>(0.75 * v) + k / 3 - 1, 0, projector.height - 1);
        t.indices[c * t.k() + k] = y * projector.width + x;
        t.weights[c * t.k() + k] = weight(random);
      }
    }
  }
  return t;
}

struct Products {
  transport::CompressedTransport transport;
  transport::TransposedTransport transposed;
  std::vector<float> light_p;
  std::vector<float> light_c;
};

const Products& products(bool tiny) {
  static std::map<bool, Products> cache;
  auto it = cache.find(tiny);
  if (it == cache.end()) {
    Products p;
    p.transport = tiny ? synthetic_transport({80, 64}, {64, 48}) : synthetic_transport({1280, 1024}, {1024, 768});
    p.transposed = transport::transpose(p.transport);
    p.light_p.assign(p.transport.projector_pixels(), 1.0f);
    p.light_c.assign(p.transport.camera_pixels(), 1.0f);
    it = cache.emplace(tiny, std::move(p)).first;
  }
  return it->second;
}

void set_shares(benchmark::State& state, const sched::RunReport& report) {
  for (std::size_t i = 0; i < report.devices.size(); ++i) {
    state.counters["share_" + std::to_string(i)] = report.devices[i].share;
    state.counters["tiles_" + std::to_string(i)] = static_cast<double>(report.devices[i].tiles);
  }
}

// Direct single-device call (host/transport/spmv.h): the baseline without the scheduler.
void BM_DualDirect(benchmark::State& state, bool tiny) {
  const auto& p = products(tiny);
  auto& device = all_devices().front();
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        transport::dual_opencl(device, programs(), rfrecon::cl::KernelEntry::kNdRange, p.transposed, p.light_c).data());
  }
}

void BM_DualScheduled(benchmark::State& state, bool tiny, std::size_t count) {
  const auto& p = products(tiny);
  auto selected = devices(count);
  sched::RunReport report;
  for (auto _ : state) {
    auto run =
        transport::dual_on_devices(selected, programs(), rfrecon::cl::KernelEntry::kNdRange, p.transposed, p.light_c);
    report = std::move(run.report);
  }
  set_shares(state, report);
}

void BM_PrimalDirect(benchmark::State& state) {
  const auto& p = products(false);
  for (auto _ : state) {
    benchmark::DoNotOptimize(transport::primal_opencl(all_devices().front(), programs(),
                                                      rfrecon::cl::KernelEntry::kNdRange, p.transport, p.light_p)
                                 .data());
  }
}

void BM_PrimalScheduled(benchmark::State& state, std::size_t count) {
  const auto& p = products(false);
  auto selected = devices(count);
  sched::RunReport report;
  for (auto _ : state) {
    report =
        transport::primal_on_devices(selected, programs(), rfrecon::cl::KernelEntry::kNdRange, p.transport, p.light_p)
            .report;
  }
  set_shares(state, report);
}

bool capture_rendered = false;

// A capture on disk (8-bit PNG), rendered once per process.
const fs::path& capture_dir() {
  static const fs::path dir = [] {
    const cv::Size camera(640, 512);
    const cv::Size projector(512, 384);
    constexpr int kDotSpacing = 8;
    const fs::path path = fs::temp_directory_path() / ("rfrecon_sched_bench_" + std::to_string(::getpid()));
    fs::create_directories(path);
    capture::CaptureManifest manifest;
    manifest.projector_size = projector;
    manifest.camera_size = camera;
    manifest.dot_spacing = kDotSpacing;
    const auto sequence = capture::make_protocol({projector, kDotSpacing});
    for (std::size_t i = 0; i < sequence.size(); ++i) {
      const cv::Mat projected = capture::render_pattern(sequence[i], {projector, kDotSpacing});
      cv::Mat frame(camera, CV_8U);
      for (int v = 0; v < camera.height; ++v) {
        const auto* row = projected.ptr<unsigned char>(static_cast<int>(0.75 * v));
        for (int u = 0; u < camera.width; ++u) {
          frame.at<unsigned char>(v, u) = cv::saturate_cast<unsigned char>(0.8 * row[static_cast<int>(0.8 * u)] + 8);
        }
      }
      const std::string file = "frame_" + std::to_string(1000 + i) + ".png";
      cv::imwrite((path / file).string(), frame);
      manifest.frames.push_back({sequence[i], file});
    }
    capture::write_manifest(manifest, path);
    capture_rendered = true;
    return path;
  }();
  return dir;
}

void BM_Transport(benchmark::State& state, std::size_t count) {
  auto selected = devices(count);
  const auto manifest = capture::read_manifest(capture_dir());
  std::map<std::string, double> stage_seconds;
  std::vector<sched::RunReport> schedule;
  const auto transport_once = [&] {
    return transport::compute_transport_on_devices(capture_dir(), manifest, {}, selected, programs(),
                                                   rfrecon::cl::KernelEntry::kNdRange);
  };
  // Untimed: the first run builds or loads the programs, and PoCL compiles each kernel's work-group function at its
  // first launch (on an empty cache, seconds: one iteration of MinTime would then be all that is timed).
  transport_once();
  for (auto _ : state) {
    auto run = transport_once();
    for (const auto& timing : run.timings) stage_seconds[timing.stage] += timing.seconds;
    schedule = std::move(run.schedule);
  }
  for (const auto& [stage, seconds] : stage_seconds) {
    state.counters[stage + "_s"] = seconds / static_cast<double>(state.iterations());
  }
  for (const auto& stage : schedule) {
    if (stage.stage == "compress") set_shares(state, stage);
  }
}

}  // namespace

int main(int argc, char** argv) {
  // PoCL reads POCL_DEVICES when the OpenCL library loads, before main: set it and run again. An explicit
  // non-empty setting wins.
  if (const char* pocl = std::getenv("POCL_DEVICES"); pocl == nullptr || *pocl == '\0') {
    ::setenv("POCL_DEVICES", "pthread pthread", 1);
    ::execv("/proc/self/exe", argv);
    std::perror("sched_bench: cannot re-run itself with POCL_DEVICES set");
    return 1;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  const auto ms = [](benchmark::internal::Benchmark* b) {
    b->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime();
  };
  ms(benchmark::RegisterBenchmark("tiny/dual_direct", BM_DualDirect, true));
  ms(benchmark::RegisterBenchmark("tiny/dual_1_device", BM_DualScheduled, true, 1));
  ms(benchmark::RegisterBenchmark("tiny/dual_2_devices", BM_DualScheduled, true, 2));
  ms(benchmark::RegisterBenchmark("full/dual_direct", BM_DualDirect, false));
  ms(benchmark::RegisterBenchmark("full/dual_1_device", BM_DualScheduled, false, 1));
  ms(benchmark::RegisterBenchmark("full/dual_2_devices", BM_DualScheduled, false, 2));
  ms(benchmark::RegisterBenchmark("full/primal_direct", BM_PrimalDirect));
  ms(benchmark::RegisterBenchmark("full/primal_1_device", BM_PrimalScheduled, 1));
  ms(benchmark::RegisterBenchmark("full/primal_2_devices", BM_PrimalScheduled, 2));
  ms(benchmark::RegisterBenchmark("transport/1_device", BM_Transport, 1));
  ms(benchmark::RegisterBenchmark("transport/2_devices", BM_Transport, 2));
  rfrecon::bench::add_run_context();
  rfrecon::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  std::printf("\n%zu OpenCL device(s) available\n", all_devices().size());
  const auto ratio = [&](const char* a, const char* b) {
    const double denominator = reporter.seconds(b);
    return denominator > 0.0 ? reporter.seconds(a) / denominator : 0.0;
  };
  std::printf("tiny dual: scheduler overhead %.2fx (1 device / direct), %.2fx (2 devices / direct)\n",
              ratio("tiny/dual_1_device", "tiny/dual_direct"), ratio("tiny/dual_2_devices", "tiny/dual_direct"));
  std::printf("full dual: 1 device / direct %.2fx, speed-up 2 devices over 1: %.2fx\n",
              ratio("full/dual_1_device", "full/dual_direct"), ratio("full/dual_1_device", "full/dual_2_devices"));
  std::printf("full primal: 1 device / direct %.2fx, speed-up 2 devices over 1: %.2fx\n",
              ratio("full/primal_1_device", "full/primal_direct"),
              ratio("full/primal_1_device", "full/primal_2_devices"));
  std::printf("transport: speed-up 2 devices over 1: %.2fx\n", ratio("transport/1_device", "transport/2_devices"));
  if (capture_rendered) fs::remove_all(capture_dir());
  benchmark::Shutdown();
  return 0;
}
