// Portability macros for rfrecon kernels: FPGA-only attributes that expand to nothing on CPU and GPU.
//
// The target is RF_TARGET_INTEL_FPGA (Intel FPGA SDK, aoc) or RF_TARGET_XILINX_FPGA (Vitis, v++): the host's
// per-device preamble (host/cl/program_cache.cc) defines it for those boards; an offline build of a binary must
// pass the same -D to the vendor's compiler.
//
//   RF_SINGLE_TASK        before a kernel: it runs as one work-item (a pipelined loop nest on FPGA).
//   RF_PIPELINE_II(n)     before a loop: ask for initiation interval n (one iteration every n clocks).
//   RF_UNROLL             before a loop with a constant trip count: unroll it fully.
//   RF_IVDEP_SAFELEN(n)   before a loop: a loop-carried dependency spans at least n iterations (rows interleaved
//                         by a single work-item kernel), so the loop can still start one iteration per clock.
//   RF_PARTITION_COMPLETE after a private array's name: keep every element in registers (fully partitioned),
//                         e.g. `float best[K] RF_PARTITION_COMPLETE;`.
// On PoCL, GPUs and oclgrind all of them are empty, so the same file runs everywhere.
//
//   RF_NDRANGE_ENTRIES    1, or 0 for the FPGA targets: `#if RF_NDRANGE_ENTRIES` around each NDRange entry keeps it
//                         out of a board binary, which would hold hardware for it that no board runs (boards run the
//                         single work-item entries: host/cl/entry_choice.h).
//
// The HLS C++ tops of hw/hls/ (Vitis 2023.1 and later) define RF_TARGET_HLS, for which all of the above are empty and
//   RF_HLS_PIPELINE       first statement of a loop body: `#pragma HLS PIPELINE II=1` (empty on the OpenCL targets).
//   RF_HLS_PIPELINE_II(n) the same at II n, where the loop's accesses to one AXI bundle allow no less.
//   RF_HLS_DEPENDENCE(a, d) in a pipelined loop's body: array a's read-after-write dependence spans d iterations
//                         (`#pragma HLS DEPENDENCE`; Intel's counterpart is RF_IVDEP_SAFELEN before the loop).
//   RF_ON_CHIP_RAM(a)     after a local array's declaration: a is an on-chip RAM (two ports), empty on every target.
//   RF_ON_CHIP_BANKS(a, n) the same for n RAMs, a's n equal blocks (`#pragma HLS ARRAY_PARTITION ... type=block`).
//   RF_HLS_STATIC         before a local array of rows: `static`, so that Vitis' software emulation (sw_emu) and the C
//                         simulation, which run the tops on a thread, keep megabytes of rows off its stack; the tool
//                         builds the same on-chip RAM. A body holding one is not reentrant: one call at a time, as a
//                         compute unit runs them. Empty on the OpenCL targets, whose functions have no static locals.
//   RF_IN_URAM(a)         after a's RF_ON_CHIP_RAM or RF_ON_CHIP_BANKS: bind a to UltraRAM (`#pragma HLS BIND_STORAGE
//                         ... impl=uram`), for a read-only row array of the pipelined loops (ports: one read, one
//                         read or write). scripts/fpga_budget.py counts a in URAM on AMD boards, in M20K on Intel's.
// The C simulation's access check (RF_CSIM_CHECK, common/csim_hooks.h) makes RF_HLS_PIPELINE, RF_HLS_DEPENDENCE,
// RF_IVDEP_SAFELEN and RF_ON_CHIP_RAM calls that count each RAM's and AXI bundle's accesses per iteration and check
// every claimed dependence distance (docs/fpga.md#access-and-dependence-check).
#ifndef RFRECON_KERNELS_COMMON_TARGET_H
#define RFRECON_KERNELS_COMMON_TARGET_H

#define RF_STRINGIFY_(x) #x
#define RF_PRAGMA_(x) _Pragma(RF_STRINGIFY_(x))

#if defined(RF_TARGET_INTEL_FPGA)
#define RF_SINGLE_TASK __attribute__((max_global_work_dim(0)))
#define RF_PIPELINE_II(n) RF_PRAGMA_(ii n)
#define RF_UNROLL RF_PRAGMA_(unroll)
#define RF_IVDEP_SAFELEN(n) RF_PRAGMA_(ivdep safelen(n))
#define RF_PARTITION_COMPLETE __attribute__((register))
#elif defined(RF_TARGET_XILINX_FPGA)
#define RF_SINGLE_TASK __attribute__((reqd_work_group_size(1, 1, 1)))
#define RF_PIPELINE_II(n) __attribute__((xcl_pipeline_loop(n)))
#define RF_UNROLL __attribute__((opencl_unroll_hint))
#define RF_IVDEP_SAFELEN(n)  // v++ has no OpenCL C equivalent; it schedules the interleaved loop at a longer II
#define RF_PARTITION_COMPLETE __attribute__((xcl_array_partition(complete, 1)))
#else
#define RF_SINGLE_TASK
#define RF_PIPELINE_II(n)
#define RF_UNROLL
#define RF_IVDEP_SAFELEN(n)
#define RF_PARTITION_COMPLETE
#endif

#if defined(RF_TARGET_INTEL_FPGA) || defined(RF_TARGET_XILINX_FPGA)
#define RF_NDRANGE_ENTRIES 0
#else
#define RF_NDRANGE_ENTRIES 1
#endif

// clang-format off
#if defined(RF_TARGET_HLS) && defined(RF_CSIM_CHECK)
#include "common/csim_hooks.h"
#undef RF_IVDEP_SAFELEN
#define RF_IVDEP_SAFELEN(n) RF_CSIM_SAFELEN(n)
#define RF_HLS_PIPELINE_II(n) RF_CSIM_ITERATION(n)
#define RF_HLS_DEPENDENCE(var, d) RF_CSIM_DEPENDENCE(var, d)
#define RF_ON_CHIP_RAM(var) RF_CSIM_RAM(var, 1)
#define RF_ON_CHIP_BANKS(var, n) RF_CSIM_RAM(var, n)
#define RF_IN_URAM(var)
#define RF_HLS_STATIC static
#elif defined(RF_TARGET_HLS)
#define RF_HLS_PIPELINE_II(n) RF_PRAGMA_(HLS PIPELINE II=n)
#define RF_HLS_DEPENDENCE(var, d) RF_PRAGMA_(HLS DEPENDENCE variable=var inter RAW distance=d true)
#define RF_ON_CHIP_RAM(var)
#define RF_ON_CHIP_BANKS(var, n) RF_PRAGMA_(HLS ARRAY_PARTITION variable=var type=block factor=n)
#define RF_IN_URAM(var) RF_PRAGMA_(HLS BIND_STORAGE variable=var type=ram_2p impl=uram)
#define RF_HLS_STATIC static
#else
#define RF_HLS_PIPELINE_II(n)
#define RF_HLS_DEPENDENCE(var, d)
#define RF_ON_CHIP_RAM(var)
#define RF_ON_CHIP_BANKS(var, n)
#define RF_IN_URAM(var)
#define RF_HLS_STATIC
#endif
#define RF_HLS_PIPELINE RF_HLS_PIPELINE_II(1)
// clang-format on

#endif  // RFRECON_KERNELS_COMMON_TARGET_H
