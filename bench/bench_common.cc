// Roofline measurement and the context (version, devices) recorded in every benchmark's JSON output.
#include "bench/bench_common.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "host/cl/device_context.h"

namespace rfrecon::bench {

double host_stream_bytes_per_second() {
  static const double measured = [] {
    // 256 MiB per array: well beyond the last-level cache of current server CPUs (this machine's is 105 MiB).
    constexpr std::size_t kElements = std::size_t{1} << 26;
    const unsigned threads = std::max(1U, std::thread::hardware_concurrency());
    std::vector<float> a(kElements, 1.0f);
    std::vector<float> b(kElements, 2.0f);
    double best = 0.0;
    for (int pass = 0; pass < 5; ++pass) {
      const auto start = std::chrono::steady_clock::now();
      std::vector<std::thread> workers;
      for (unsigned t = 0; t < threads; ++t) {
        workers.emplace_back([&, t] {
          const std::size_t begin = kElements * t / threads;
          const std::size_t end = kElements * (t + 1) / threads;
          for (std::size_t i = begin; i < end; ++i) a[i] += 0.5f * b[i];
        });
      }
      for (auto& worker : workers) worker.join();
      benchmark::DoNotOptimize(a.data());
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      best = std::max(best, 3.0 * sizeof(float) * kElements / seconds);  // read a and b, write a
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

void RecordingReporter::ReportRuns(const std::vector<Run>& runs) {
  for (const auto& run : runs) {
    if (run.run_type == Run::RT_Aggregate && run.aggregate_name != "median") continue;
    const std::string& name = run.run_name.function_name;
    seconds_[name] = run.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(run.time_unit);
    counters_[name] = run.counters;
  }
  ConsoleReporter::ReportRuns(runs);
}

double RecordingReporter::seconds(const std::string& name) const {
  const auto found = seconds_.find(name);
  return found != seconds_.end() ? found->second : 0.0;
}

double RecordingReporter::counter(const std::string& name, const std::string& counter) const {
  const auto found = counters_.find(name);
  if (found == counters_.end()) return 0.0;
  const auto value = found->second.find(counter);
  return value != found->second.end() ? static_cast<double>(value->second) : 0.0;
}

}  // namespace rfrecon::bench
