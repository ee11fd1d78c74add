// Throughput of the depth stage's row solvers at full size (1024 rectified rows of 1280 pixels): reciprocity
// integration and fusion, C++ reference and the OpenCL NDRange and single work-item entries on the first device.
// Inputs are the analytic rows of a slightly tilted plane (tests/depth/analytic_rows.h) segmented by
// host/depth/row_segmentation.h, so every pixel carries the ODE. Prints the kernel / reference speed-ups after the
// runs.
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "host/cl/device_selection.h"
#include "host/depth/row_segmentation.h"
#include "host/depth/row_solvers.h"
#include "tests/depth/analytic_rows.h"

namespace {

using namespace rfrecon;

constexpr int kWidth = 1280;
constexpr int kHeight = 1024;

enum class Solver { kReference, kNdRange, kSingleWorkItem };

// The plane's depth runs from 485 mm (left edge) to 600 mm (right edge) over the analytic rig's wide field (f = 300
// px): its disparity then keeps every projector column inside the analytic rows' projector image (width + 16).
depth::testing::Plane bench_plane() {
  const double nx = 0.0497, nz = -1.0, length = std::sqrt(nx * nx + nz * nz);
  return depth::testing::Plane{nx / length, 0.0, nz / length, -536.3 / length};
}

const depth::RectifiedRows& rows() {
  static const depth::RectifiedRows instance = [] {
    auto r = depth::testing::analytic_rows(bench_plane(), kWidth, kHeight);
    const auto stats = depth::segment_rows(r, depth::SegmentationOptions{});
    if (stats.usable != kWidth * kHeight || stats.runs != kHeight) {
      throw std::runtime_error("depth_bench: the plane does not carry the ODE on every pixel (" +
                               std::to_string(stats.usable) + " usable, " + std::to_string(stats.runs) + " runs)");
    }
    return r;
  }();
  return instance;
}

// Starting depth of the fusion: the integrated rows.
const std::vector<float>& integrated() {
  static const std::vector<float> z = depth::integrate_rows_reference(rows(), {}, 0, kHeight);
  return z;
}

rfrecon::cl::DeviceContext& device() {
  static std::vector<rfrecon::cl::DeviceContext> devices = rfrecon::cl::open_devices("");
  return devices.front();
}
rfrecon::cl::ProgramCache& programs() {
  static rfrecon::cl::ProgramCache cache;
  return cache;
}

rfrecon::cl::KernelEntry entry(Solver solver) {
  return solver == Solver::kNdRange ? rfrecon::cl::KernelEntry::kNdRange : rfrecon::cl::KernelEntry::kSingleWorkItem;
}

std::vector<float> integrate(Solver solver) {
  if (solver == Solver::kReference) return depth::integrate_rows_reference(rows(), {}, 0, kHeight);
  return depth::integrate_rows_opencl(device(), programs(), entry(solver), rows(), {}, 0, kHeight);
}

std::vector<float> fuse(Solver solver) {
  if (solver == Solver::kReference) return depth::fuse_rows_reference(rows(), integrated(), {}, 0, kHeight);
  return depth::fuse_rows_opencl(device(), programs(), entry(solver), rows(), integrated(), {}, 0, kHeight);
}

// rows/s and Mpx/s of the whole image per iteration, plus the RMS depth error (um) of the result against the plane,
// which shows the run solved the real problem.
void set_counters(benchmark::State& state, const std::vector<float>& z) {
  const auto iterations = static_cast<double>(state.iterations());
  state.counters["rows/s"] = benchmark::Counter(kHeight * iterations, benchmark::Counter::kIsRate);
  state.counters["Mpx/s"] = benchmark::Counter(kWidth * kHeight * iterations / 1e6, benchmark::Counter::kIsRate);
  double sum = 0.0;
  for (std::size_t i = 0; i < z.size(); ++i) sum += (z[i] - rows().z_tri[i]) * (z[i] - rows().z_tri[i]);
  state.counters["rms_error_um"] = 1e3 * std::sqrt(sum / static_cast<double>(z.size()));
}

template <typename Solve>
void run(benchmark::State& state, Solver solver, Solve solve) {
  integrated();  // builds the inputs outside the timing
  std::vector<float> z;
  if (solver != Solver::kReference) {
    z = solve(solver);  // builds the OpenCL program outside the timing
    state.SetLabel(rfrecon::cl::describe(device().info()));
  }
  for (auto _ : state) {
    z = solve(solver);  // uploads the rows, runs, reads the depths back
    benchmark::DoNotOptimize(z.data());
  }
  set_counters(state, z);
}

void BM_Integrate(benchmark::State& state, Solver solver) { run(state, solver, integrate); }
void BM_Fuse(benchmark::State& state, Solver solver) { run(state, solver, fuse); }

// Wall-clock rates (the OpenCL runs spend their time in PoCL's threads). A whole image takes about a second: two
// iterations each keep the run short.
void configure(benchmark::internal::Benchmark* benchmark) {
  benchmark->Unit(benchmark::kMillisecond)->Iterations(2)->UseRealTime();
}
BENCHMARK_CAPTURE(BM_Integrate, reference, Solver::kReference)->Apply(configure);
BENCHMARK_CAPTURE(BM_Integrate, ndrange, Solver::kNdRange)->Apply(configure);
BENCHMARK_CAPTURE(BM_Integrate, single, Solver::kSingleWorkItem)->Apply(configure);
BENCHMARK_CAPTURE(BM_Fuse, reference, Solver::kReference)->Apply(configure);
BENCHMARK_CAPTURE(BM_Fuse, ndrange, Solver::kNdRange)->Apply(configure);
BENCHMARK_CAPTURE(BM_Fuse, single, Solver::kSingleWorkItem)->Apply(configure);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  rfrecon::bench::add_run_context();
  rfrecon::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  // Speed-ups of the OpenCL entries over the reference, for the stages whose runs were all selected.
  for (const std::string stage : {"BM_Integrate", "BM_Fuse"}) {
    const double reference = reporter.seconds(stage + "/reference");
    const double ndrange = reporter.seconds(stage + "/ndrange"), single = reporter.seconds(stage + "/single");
    if (reference > 0.0 && ndrange > 0.0 && single > 0.0) {
      std::printf("%s: OpenCL over the C++ reference: NDRange %.2fx, single work-item %.2fx\n", stage.c_str(),
                  reference / ndrange, reference / single);
    }
  }
  benchmark::Shutdown();
  return 0;
}
