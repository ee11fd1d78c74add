// Self-check kernel throughput on each OpenCL device and its C++ reference, as a fraction of the host
// memory-bandwidth roofline measured in the same run (bench/bench_common.h).
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/bench_common.h"
#include "host/cl/device_selection.h"
#include "host/cl/error.h"
#include "host/selfcheck/axpy.h"

namespace {

constexpr std::size_t kElements = std::size_t{1} << 26;  // 256 MiB per array: beyond the last-level cache

// Bytes an axpy moves: read x, read y, write y.
constexpr double kBytesPerElement = 3 * sizeof(float);

void BM_AxpyReference(benchmark::State& state) {
  std::vector<float> x(kElements, 1.0f);
  std::vector<float> y(kElements, 2.0f);
  for (auto _ : state) {
    y = rfrecon::selfcheck::axpy_reference(0.5f, x, std::move(y));
    benchmark::DoNotOptimize(y.data());
  }
  rfrecon::bench::set_bandwidth_counters(state, kBytesPerElement * kElements);
}
BENCHMARK(BM_AxpyReference)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_AxpyKernel(benchmark::State& state) {
  auto devices = rfrecon::cl::open_devices("");
  auto& device = devices.front();
  rfrecon::cl::ProgramCache programs;
  std::vector<float> x(kElements, 1.0f);
  std::vector<float> y(kElements, 2.0f);
  const std::size_t bytes = kElements * sizeof(float);
  ::cl::Buffer x_buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes, x.data());
  ::cl::Buffer y_buffer(device.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, y.data());
  ::cl::Kernel kernel(programs.get(device, "selfcheck/axpy.cl"), "axpy_ndrange");
  kernel.setArg(0, 0.5f);
  kernel.setArg(1, x_buffer);
  kernel.setArg(2, y_buffer);
  kernel.setArg(3, static_cast<cl_uint>(kElements));
  for (auto _ : state) {
    RF_CL_CHECK(device.queue().enqueueNDRangeKernel(kernel, ::cl::NullRange, ::cl::NDRange(kElements)));
    RF_CL_CHECK(device.queue().finish());
  }
  state.SetLabel(rfrecon::cl::describe(device.info()));
  rfrecon::bench::set_bandwidth_counters(state, kBytesPerElement * kElements);
}
BENCHMARK(BM_AxpyKernel)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  rfrecon::bench::add_run_context();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
