// Roofline measurements and the context (version, devices) recorded in every benchmark's JSON output.
#include "bench/bench_common.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "host/cl/device_context.h"

namespace rfrecon::bench {

namespace {
// 256 MiB per array: well beyond the last-level cache of current server CPUs (this machine's is 105 MiB).
constexpr std::size_t kElements = std::size_t{1} << 26;

// Best of five passes of pass(begin, end) over [0, kElements) split among every hardware thread, as PoCL uses them
// all: `bytes` over the fastest pass's seconds.
template <typename Pass>
double best_bytes_per_second(double bytes, const Pass& pass) {
  const unsigned threads = std::max(1U, std::thread::hardware_concurrency());
  double best = 0.0;
  for (int round = 0; round < 5; ++round) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::thread> workers;
    for (unsigned t = 0; t < threads; ++t) {
      workers.emplace_back([&, t] { pass(kElements * t / threads, kElements * (t + 1) / threads); });
    }
    for (auto& worker : workers) worker.join();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best = std::max(best, bytes / seconds);
  }
  return best;
}
}  // namespace

double host_stream_bytes_per_second() {
  static const double measured = [] {
    std::vector<float> a(kElements, 1.0f);
    std::vector<float> b(kElements, 2.0f);
    const double bytes = 3.0 * sizeof(float) * kElements;  // read a and b, write a
    const double best = best_bytes_per_second(bytes, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) a[i] += 0.5f * b[i];
    });
    benchmark::DoNotOptimize(a.data());
    return best;
  }();
  return measured;
}

double host_read_bytes_per_second() {
  static const double measured = [] {
    std::vector<std::uint32_t> a(kElements, 1);
    std::vector<std::uint32_t> b(kElements, 2);
    const double bytes = 2.0 * sizeof(std::uint32_t) * kElements;
    return best_bytes_per_second(bytes, [&](std::size_t begin, std::size_t end) {
      std::uint32_t sum = 0;  // integer sums, which the compiler may reorder into vector lanes
      for (std::size_t i = begin; i < end; ++i) sum += a[i] + b[i];
      benchmark::DoNotOptimize(sum);
    });
  }();
  return measured;
}

void set_bandwidth_counters(benchmark::State& state, double bytes_per_iteration) {
  const double bytes = bytes_per_iteration * static_cast<double>(state.iterations());
  state.counters["GB/s"] = benchmark::Counter(bytes, benchmark::Counter::kIsRate, benchmark::Counter::kIs1000);
  state.counters["roofline_fraction"] =
      benchmark::Counter(bytes / host_stream_bytes_per_second(), benchmark::Counter::kIsRate);
}

void add_run_context() {
  benchmark::AddCustomContext("rfrecon_version", RFRECON_VERSION);
  std::string devices;
  for (const auto& entry : rfrecon::cl::enumerate_devices()) {
    devices += (devices.empty() ? "" : "; ") + rfrecon::cl::describe(entry.info);
  }
  benchmark::AddCustomContext("opencl_devices", devices);
  benchmark::AddCustomContext("host_stream_GBps", std::to_string(host_stream_bytes_per_second() / 1e9));
  benchmark::AddCustomContext("host_read_GBps", std::to_string(host_read_bytes_per_second() / 1e9));
}

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
