// Transpose (counting sort), C++ references and OpenCL runs of the primal and dual products.
#include "host/transport/spmv.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

#include "host/cl/kernel_launch.h"

namespace rfrecon::transport {

namespace {

void check_light(std::size_t got, std::size_t expected, const char* what) {
  if (got != expected) {
    throw std::invalid_argument(std::string(what) + ": light has " + std::to_string(got) + " values, expected " +
                                std::to_string(expected));
  }
}

// options: the build options of spmv.cl (the primal's K).
template <typename... Args>
std::vector<float> run_spmv(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry, const char* name,
                            const std::string& options, std::size_t n, const Args&... args) {
  if (n == 0) return {};
  ::cl::Kernel kernel = cl::make_kernel(programs.get(device, "transport/spmv.cl", options), name, entry);
  const ::cl::Buffer output = cl::make_buffer<float>(device.context(), n, CL_MEM_WRITE_ONLY);
  cl::set_args(kernel, args..., output, static_cast<cl_uint>(n));
  cl::enqueue_kernel(device.queue(), kernel, entry, n);
  return cl::download<float>(device.queue(), output, n);
}

}  // namespace

TransposedTransport transpose(const CompressedTransport& transport) {
  TransposedTransport transposed;
  transposed.projector_size = transport.setup.projector_size;
  const std::size_t projector_pixels = transport.projector_pixels();
  const auto k = static_cast<std::size_t>(transport.k());
  // The camera pixels in blocks, one per core (at most kMaxBlocks: each block counts every projector pixel): block b's
  // entries of projector pixel q go after those of the blocks before it, so each row lists its camera pixels in
  // ascending order, as one pass over them would.
  constexpr int kMaxBlocks = 8;
  const int blocks = std::clamp(cv::getNumThreads(), 1, kMaxBlocks);
  const std::size_t camera_pixels = transport.camera_pixels();
  const auto block_slots = [&](int b, std::size_t& begin, std::size_t& end) {
    begin = camera_pixels * static_cast<std::size_t>(b) / static_cast<std::size_t>(blocks) * k;
    end = camera_pixels * static_cast<std::size_t>(b + 1) / static_cast<std::size_t>(blocks) * k;
  };
  // next[b][q]: first the count of block b's entries in row q, then where its next one goes.
  std::vector<std::vector<std::int32_t>> next(static_cast<std::size_t>(blocks));
  const auto each_block = [&](const auto& body) {
    cv::parallel_for_(cv::Range(0, blocks), [&](const cv::Range& range) {
      for (int b = range.start; b < range.end; ++b) {
        std::size_t begin = 0, end = 0;
        block_slots(b, begin, end);
        body(next[static_cast<std::size_t>(b)], begin, end);
      }
    });
  };
  each_block([&](std::vector<std::int32_t>& count, std::size_t begin, std::size_t end) {
    count.assign(projector_pixels, 0);
    for (std::size_t slot = begin; slot < end; ++slot) {
      const std::int32_t q = transport.indices[slot];
      if (q >= 0) ++count[static_cast<std::size_t>(q)];
    }
  });
  transposed.row_start.assign(projector_pixels + 1, 0);
  for (std::size_t q = 0; q < projector_pixels; ++q) {
    std::int32_t at = transposed.row_start[q];
    for (auto& block : next) {
      const std::int32_t count = block[q];
      block[q] = at;
      at += count;
    }
    transposed.row_start[q + 1] = at;
  }
  const auto nonzeros = static_cast<std::size_t>(transposed.row_start.back());
  transposed.camera_pixel.resize(nonzeros);
  transposed.weights.resize(nonzeros);
  each_block([&](std::vector<std::int32_t>& at, std::size_t begin, std::size_t end) {
    for (std::size_t slot = begin; slot < end; ++slot) {
      const std::int32_t q = transport.indices[slot];
      if (q < 0) continue;
      const auto j = static_cast<std::size_t>(at[static_cast<std::size_t>(q)]++);
      transposed.camera_pixel[j] = static_cast<std::int32_t>(slot / k);
      transposed.weights[j] = transport.weights[slot];
    }
  });
  return transposed;
}

std::vector<std::int32_t> entry_rows(const std::vector<std::int32_t>& row_start, std::size_t begin, std::size_t end) {
  std::vector<std::int32_t> rows;
  rows.reserve(static_cast<std::size_t>(row_start[end] - row_start[begin]));
  for (std::size_t q = begin; q < end; ++q) {
    rows.insert(rows.end(), static_cast<std::size_t>(row_start[q + 1] - row_start[q]),
                static_cast<std::int32_t>(q - begin));
  }
  return rows;
}

std::vector<float> primal_reference(const CompressedTransport& transport, const std::vector<float>& light_p) {
  check_light(light_p.size(), transport.projector_pixels(), "primal");
  std::vector<float> image(transport.camera_pixels(), 0.0f);
  const auto k = static_cast<std::size_t>(transport.k());
  for (std::size_t slot = 0; slot < transport.indices.size(); ++slot) {
    const std::int32_t q = transport.indices[slot];
    if (q >= 0) image[slot / k] += transport.weights[slot] * light_p[static_cast<std::size_t>(q)];
  }
  return image;
}

std::vector<float> dual_reference(const CompressedTransport& transport, const std::vector<float>& light_c) {
  check_light(light_c.size(), transport.camera_pixels(), "dual");
  std::vector<float> image(transport.projector_pixels(), 0.0f);
  const auto k = static_cast<std::size_t>(transport.k());
  for (std::size_t slot = 0; slot < transport.indices.size(); ++slot) {
    const std::int32_t q = transport.indices[slot];
    if (q >= 0) image[static_cast<std::size_t>(q)] += transport.weights[slot] * light_c[slot / k];
  }
  return image;
}

std::vector<float> primal_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                                 const CompressedTransport& transport, const std::vector<float>& light_p,
                                 const std::string& build_options) {
  check_light(light_p.size(), transport.projector_pixels(), "primal");
  return run_spmv(device, programs, entry, "primal", transport_build_options(transport.k(), build_options),
                  transport.camera_pixels(), cl::upload(device.context(), transport.indices),
                  cl::upload(device.context(), transport.weights), cl::upload(device.context(), light_p));
}

std::vector<float> dual_opencl(cl::DeviceContext& device, cl::ProgramCache& programs, KernelEntry entry,
                               const TransposedTransport& transposed, const std::vector<float>& light_c,
                               const std::string& build_options) {
  const std::size_t n = static_cast<std::size_t>(transposed.projector_size.area());
  if (transposed.row_start.size() != n + 1) throw std::invalid_argument("dual: malformed transposed transport");
  const auto row_start = cl::upload(device.context(), transposed.row_start);
  const auto camera_pixel = cl::upload(device.context(), transposed.camera_pixel);
  const auto weights = cl::upload(device.context(), transposed.weights);
  const auto light = cl::upload(device.context(), light_c);
  if (entry == KernelEntry::kSingleWorkItem) {
    const auto rows = cl::upload(device.context(), entry_rows(transposed.row_start, 0, n));
    return run_spmv(device, programs, entry, "dual", build_options, n, row_start, rows, camera_pixel, weights, light);
  }
  return run_spmv(device, programs, entry, "dual", build_options, n, row_start, camera_pixel, weights, light);
}

}  // namespace rfrecon::transport
