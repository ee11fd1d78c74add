// Roofline measurement and the context (version, devices) recorded in every benchmark's JSON output.
#include "bench/bench_common.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "host/cl/device_context.h"

namespace rfrecon::bench {

double host_stream_bytes_per_second() {
  static const double measured = [] {
    constexpr std::size_t kElements = 1 << 24;
    std::vector<float> a(kElements, 1.0f);
    std::vector<float> b(kElements, 2.0f);
    std::vector<float> c(kElements, 0.0f);
    double best = 0.0;
    for (int pass = 0; pass < 5; ++pass) {
      const auto start = std::chrono::steady_clock::now();
      for (std::size_t i = 0; i < kElements; ++i) c[i] = a[i] + 0.5f * b[i];
      benchmark::DoNotOptimize(c.data());
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      best = std::max(best, 3.0 * sizeof(float) * kElements / seconds);
    }
    return best;
  }();
  return measured;
}

void set_bandwidth_counters(benchmark::State& state, double bytes_per_iteration) {
  const double bytes = bytes_per_iteration * static_cast<double>(state.iterations());
  state.counters["GB/s"] = benchmark::Counter(bytes, benchmark::Counter::kIsRate, benchmark::Counter::kIs1000);
  state.counters["roofline_fraction"] =
      benchmark::Counter(bytes / host_stream_bytes_per_second(), benchmark::Counter::kIsRate);
}

namespace {
const bool kContextAdded = [] {
  benchmark::AddCustomContext("rfrecon_version", RFRECON_VERSION);
  std::string devices;
  for (const auto& entry : rfrecon::cl::enumerate_devices()) {
    devices += (devices.empty() ? "" : "; ") + rfrecon::cl::describe(entry.info);
  }
  benchmark::AddCustomContext("opencl_devices", devices);
  benchmark::AddCustomContext("host_stream_GBps", std::to_string(host_stream_bytes_per_second() / 1e9));
  return true;
}();
}  // namespace

}  // namespace rfrecon::bench
