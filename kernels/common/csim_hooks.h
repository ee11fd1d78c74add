// The hooks of the C simulation's access and dependence check (RF_CSIM_CHECK, C++ only): what kernels/common/target.h's
// directives and hw/hls/hls_top.h's RF_HLS_M_AXI call there, implemented by tests/fpga/csim_check.cc
// (docs/fpga.md#access-and-dependence-check).
#ifndef RFRECON_KERNELS_COMMON_CSIM_HOOKS_H
#define RFRECON_KERNELS_COMMON_CSIM_HOOKS_H

#include <cstddef>

namespace rf_csim {

// One iteration of a pipelined loop (RF_HLS_PIPELINE_II), from its construction to its destruction.
class Iteration {
 public:
  Iteration(const char* file, int line, int claimed_ii);
  ~Iteration();
  Iteration(const Iteration&) = delete;
  Iteration& operator=(const Iteration&) = delete;
};

// A memory the check attributes accesses to while it exists: on-chip RAMs (a local array in `banks` equal blocks, one
// RAM each; a struct array is one RAM per field, as HLS disaggregates it) or an AXI4 master argument's bundle.
class Memory {
 public:
  Memory(const void* at, std::size_t bytes, std::size_t element_bytes, int banks, const char* name);  // on-chip
  // An AXI argument, up to the next one's start, of words of element_bytes (its pointee: a wide struct is one word).
  Memory(const void* at, std::size_t element_bytes, const char* argument, const char* bundle);
  ~Memory();
  Memory(const Memory&) = delete;
  Memory& operator=(const Memory&) = delete;

 private:
  const void* at_;
};

// In a pipelined iteration: the RAM at `at` has its read-after-write dependences `distance` iterations or more apart.
void dependence(const void* at, int distance);
// Before a pipelined loop: every memory's read-after-write dependences in it are `distance` iterations or more apart.
void safelen(int distance);

}  // namespace rf_csim

#define RF_CSIM_JOIN_(a, b) a##b
#define RF_CSIM_JOIN(a, b) RF_CSIM_JOIN_(a, b)
#define RF_CSIM_ITERATION(ii) rf_csim::Iteration rf_csim_iteration_(__FILE__, __LINE__, ii);
#define RF_CSIM_DEPENDENCE(var, d) rf_csim::dependence(var, d);
#define RF_CSIM_SAFELEN(n) rf_csim::safelen(n);
#define RF_CSIM_RAM(var, banks) \
  rf_csim::Memory RF_CSIM_JOIN(rf_csim_ram_, var)(var, sizeof(var), sizeof(var[0]), banks, #var);
#define RF_CSIM_PORT(argument, bundle_name) \
  rf_csim::Memory RF_CSIM_JOIN(rf_csim_port_, argument)(argument, sizeof(*argument), #argument, #bundle_name);

#endif  // RFRECON_KERNELS_COMMON_CSIM_HOOKS_H
