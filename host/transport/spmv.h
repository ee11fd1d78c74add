// Products with the compressed T: primal images T L_p (camera side) and dual images T^T L_c (projector side).
#pragma once

#include <string>
#include <vector>

#include "host/cl/device_context.h"
#include "host/cl/program_cache.h"
#include "host/transport/transport_types.h"

namespace rfrecon::transport {

// T^T in CSR form, one row per projector pixel q: entries row_start[q] .. row_start[q + 1] - 1 hold the camera
// pixels that see q (ascending) and their weights. Built by a stable counting sort of the ELL entries, so the dual
// product needs no float atomics: each projector pixel is summed by one work-item.
struct TransposedTransport {
  cv::Size projector_size;
  std::vector<std::int32_t> row_start;     // projector pixels + 1
  std::vector<std::int32_t> camera_pixel;  // one per nonzero
  std::vector<float> weights;              // one per nonzero
};

TransposedTransport transpose(const CompressedTransport& transport);

// The row of each entry of rows [begin, end) (entries row_start[begin] to row_start[end] - 1), less begin: what the
// single work-item dual streams instead of waiting on row_start (kernels/transport/sparse_products.h).
std::vector<std::int32_t> entry_rows(const std::vector<std::int32_t>& row_start, std::size_t begin, std::size_t end);

// C++ references: primal[c] = sum_k w[c,k] light_p[idx[c,k]]; dual[q] = sum_c T[c,q] light_c[c], summed in
// ascending c (the order the kernel's CSR rows have). Throw std::invalid_argument on a light of the wrong size.
std::vector<float> primal_reference(const CompressedTransport& transport, const std::vector<float>& light_p);
std::vector<float> dual_reference(const CompressedTransport& transport, const std::vector<float>& light_c);

// kernels/transport/spmv.cl on one device.
// build_options are added to spmv.cl's (tests build the single work-item entries with an FPGA target macro).
std::vector<float> primal_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                                 const CompressedTransport& transport, const std::vector<float>& light_p,
                                 const std::string& build_options = {});
std::vector<float> dual_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                               const TransposedTransport& transposed, const std::vector<float>& light_c,
                               const std::string& build_options = {});

}  // namespace rfrecon::transport
