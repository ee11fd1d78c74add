// The C simulation's access and dependence check (docs/fpga.md#access-and-dependence-check): what the hooks of
// kernels/common/csim_hooks.h recorded while tops built with RF_CSIM_CHECK ran, per pipelined loop.
//
// The tops' translation units are compiled with -fsanitize=thread and linked without its runtime: csim_check.cc
// defines the __tsan_read / __tsan_write entry points the compiler puts before every load and store, so every access
// the compiled loop body makes, after the compiler's own optimizations, is counted. An access inside an iteration
// (RF_HLS_PIPELINE) goes to the on-chip RAM (RF_ON_CHIP_RAM, one per field of a struct array) or AXI bundle
// (RF_HLS_M_AXI) that holds its address; other stack addresses are registers, not counted. A bundle counts beats: the
// loads (or stores) of one iteration within one word of an argument (its pointee type, a wide struct's whole) are one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rf_csim {

// One memory's accesses in one loop: the most reads, writes and accesses in all of one iteration, and the shortest
// read-after-write distance seen (0 when none) against the one the loop claims (0 when none).
struct MemoryUse {
  std::string memory;  // "z_rows", "states+4" (a struct array's field at byte 4), "gmem0"
  bool bundle = false;
  std::string arguments;  // a bundle's, as the top names them
  int reads = 0;
  int writes = 0;
  int accesses = 0;
  std::int64_t shortest_distance = 0;
  int claimed_distance = 0;

  // The initiation interval these accesses allow: a RAM has two ports, a bundle one read and one write channel.
  int initiation_interval() const;
};

struct LoopUse {
  std::string where;   // file:line of the loop's RF_HLS_PIPELINE, the file relative to the repository
  int claimed_ii = 1;  // the II its directive asks for
  std::int64_t executions = 0;
  std::int64_t iterations = 0;
  std::vector<MemoryUse> memories;
  std::vector<std::string> violations;  // dependences shorter than claimed, and accesses to unregistered memory

  int initiation_interval() const;  // the largest of its memories'
};

// Every loop that ran since the last reset, in order of first run.
std::vector<LoopUse> loop_uses();
void reset();
// The table docs/fpga.md shows: one line per loop and memory.
std::string table(std::vector<LoopUse> loops);

}  // namespace rf_csim
