// Helpers shared by the benchmarks: the machine's memory-bandwidth rooflines (streaming and read-only), throughput
// counters against it, and a reporter that keeps the figures main() needs for ratios measured in the same run.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

namespace rfrecon::bench {

// Host memory bandwidth in bytes/s, measured once per process: best of five streaming passes a += 0.5 b (read two
// arrays, write one in place, so no write-allocate traffic; 256 MiB each, beyond the last-level cache) in plain C++
// on every hardware thread, as PoCL uses them all.
double host_stream_bytes_per_second();

// Host read-only bandwidth in bytes/s, measured once per process the same way: best of five passes summing two
// 256 MiB integer arrays, nothing written. The ceiling of a stage that mostly reads, such as the compression of the
// dot frames; on a machine whose reads alone move less than the streaming pass, it is the lower of the two.
double host_read_bytes_per_second();

// Adds the run's context to the JSON and the console: rfrecon's version, the OpenCL devices and both rooflines
// (measured here, 512 MiB in memory for a moment). Call from main before RunSpecifiedBenchmarks, in the process that
// runs the benchmarks only (a child whose peak memory is measured must not call it).
void add_run_context();

// Sets "GB/s" and "roofline_fraction" (achieved bandwidth / host_stream_bytes_per_second()) for `bytes_per_iteration`
// bytes moved each iteration. Call after the timing loop.
void set_bandwidth_counters(benchmark::State& state, double bytes_per_iteration);

// Console output that also keeps, per benchmark function name, the real time per iteration in seconds (the median
// when --benchmark_repetitions aggregates) and its counters.
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override;
  double seconds(const std::string& name) const;                              // 0 when it did not run
  double counter(const std::string& name, const std::string& counter) const;  // 0 when absent

 private:
  std::map<std::string, double> seconds_;
  std::map<std::string, benchmark::UserCounters> counters_;
};

}  // namespace rfrecon::bench
