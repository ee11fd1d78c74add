// Helpers shared by the benchmarks: the machine's memory-bandwidth roofline and throughput counters against it.
#pragma once

#include <benchmark/benchmark.h>

namespace rfrecon::bench {

// Host memory bandwidth in bytes/s, measured once per process: best of five streaming passes a += 0.5 b (read two
// arrays, write one in place, so no write-allocate traffic; 256 MiB each, beyond the last-level cache) in plain C++
// on every hardware thread, as PoCL uses them all.
double host_stream_bytes_per_second();

// Sets "GB/s" and "roofline_fraction" (achieved bandwidth / host_stream_bytes_per_second()) for `bytes_per_iteration`
// bytes moved each iteration. Call after the timing loop.
void set_bandwidth_counters(benchmark::State& state, double bytes_per_iteration);

}  // namespace rfrecon::bench
