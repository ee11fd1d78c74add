// Tiled, double-buffered primal and dual products on several devices (kernels/transport/spmv.cl).
#include "host/sched/spmv_on_devices.h"

#include <stdexcept>
#include <string>

#include "host/cl/error.h"

namespace rfrecon::sched {

namespace {

// Tiles are multiples of this many output pixels: large enough that per-tile overhead stays small.
constexpr std::size_t kGranularity = 256;
constexpr std::size_t kWorkGroup = 64;

// A device buffer that grows to the largest tile it has held (one per input array and slot).
class GrowingBuffer {
 public:
  ::cl::Buffer& at_least(cl::DeviceContext& device, std::size_t bytes, cl_mem_flags flags) {
    bytes = std::max<std::size_t>(bytes, 4);  // zero-sized buffers are invalid
    if (bytes > capacity_) {
      cl_int status = CL_SUCCESS;
      buffer_ = ::cl::Buffer(device.context(), flags, bytes, nullptr, &status);
      RF_CL_CHECK_CODE(status, "clCreateBuffer");
      capacity_ = bytes;
    }
    return buffer_;
  }

 private:
  ::cl::Buffer buffer_;
  std::size_t capacity_ = 0;
};

template <typename T>
void write_async(Worker& worker, GrowingBuffer& buffer, const T* data, std::size_t count) {
  ::cl::Buffer& target = buffer.at_least(worker.device(), count * sizeof(T), CL_MEM_READ_ONLY);
  if (count > 0) RF_CL_CHECK(worker.transfer_queue().enqueueWriteBuffer(target, CL_FALSE, 0, count * sizeof(T), data));
}

// One device's kernel, the light vector (same for every tile) and two sets of tile buffers.
struct DeviceState {
  ::cl::Kernel kernel;
  ::cl::Buffer light;
  GrowingBuffer rows[2];     // primal: ELL indices; dual: rebased CSR row starts
  GrowingBuffer columns[2];  // dual: camera pixels
  GrowingBuffer weights[2];
  GrowingBuffer output[2];
  std::vector<std::int32_t> rebased[2];  // dual: host copy of the rebased row starts while they upload
};

void prepare(Worker& worker, DeviceState& state, cl::ProgramCache& programs, cl::KernelEntry entry, const char* name,
             const std::vector<float>& light) {
  cl_int status = CL_SUCCESS;
  const std::string kernel = std::string(name) + (entry == cl::KernelEntry::kSingleWorkItem ? "_single" : "_ndrange");
  state.kernel = ::cl::Kernel(programs.get(worker.device(), "transport/spmv.cl"), kernel.c_str(), &status);
  RF_CL_CHECK_CODE(status, "clCreateKernel");
  state.light = ::cl::Buffer(worker.device().context(), CL_MEM_READ_ONLY, std::max<std::size_t>(light.size(), 1) * 4,
                             nullptr, &status);
  RF_CL_CHECK_CODE(status, "clCreateBuffer");
  if (!light.empty()) {
    RF_CL_CHECK(worker.queue().enqueueWriteBuffer(state.light, CL_TRUE, 0, light.size() * sizeof(float), light.data()));
  }
}

// Sets the arguments, runs the kernel after the slot's uploads, and reads the tile's pixels into `image`.
template <typename... Args>
void run_tile(Worker& worker, DeviceState& state, cl::KernelEntry entry, const Tile& tile, int slot,
              std::vector<float>& image, const Args&... args) {
  ::cl::Buffer& output = state.output[slot].at_least(worker.device(), tile.size() * sizeof(float), CL_MEM_WRITE_ONLY);
  cl_uint index = 0;
  (RF_CL_CHECK(state.kernel.setArg(index++, args)), ...);
  RF_CL_CHECK(state.kernel.setArg(index++, state.light));
  RF_CL_CHECK(state.kernel.setArg(index++, output));
  RF_CL_CHECK(state.kernel.setArg(index++, static_cast<cl_uint>(tile.size())));
  // A fixed work-group size, the global size rounded up to it (the kernels skip ids >= n): tiles of many sizes
  // would otherwise make PoCL compile the kernel again for every work-group size it picks.
  const bool single = entry == cl::KernelEntry::kSingleWorkItem;
  const std::size_t group = std::min<std::size_t>(kWorkGroup, worker.device().info().max_work_group_size);
  const std::size_t global = (tile.size() + group - 1) / group * group;
  RF_CL_CHECK(worker.queue().enqueueNDRangeKernel(
      state.kernel, ::cl::NullRange, single ? ::cl::NDRange(1) : ::cl::NDRange(global),
      single ? ::cl::NDRange(1) : ::cl::NDRange(group), &worker.inputs_ready(slot)));
  RF_CL_CHECK(
      worker.queue().enqueueReadBuffer(output, CL_TRUE, 0, tile.size() * sizeof(float), image.data() + tile.begin));
}

ProductRun run_product(std::vector<cl::DeviceContext>& devices, std::size_t pixels, Options& options, const char* stage,
                       TileWork& work, std::vector<float>& image) {
  if (options.stage == Options().stage) options.stage = stage;
  if (options.granularity == 0) options.granularity = kGranularity;
  ProductRun run;
  run.report = run_tiles(devices, pixels, work, options);
  run.image = std::move(image);
  return run;
}

}  // namespace

ProductRun primal_on_devices(std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs, cl::KernelEntry entry,
                             const transport::CompressedTransport& transport, const std::vector<float>& light_p,
                             Options options) {
  if (light_p.size() != transport.projector_pixels()) {
    throw std::invalid_argument("primal: light has " + std::to_string(light_p.size()) + " values, expected " +
                                std::to_string(transport.projector_pixels()));
  }
  const auto k = static_cast<std::size_t>(transport.k());
  std::vector<float> image(transport.camera_pixels(), 0.0f);
  std::vector<DeviceState> states(devices.size());
  TileWork work;
  work.prepare = [&](Worker& worker) {
    prepare(worker, states[worker.position()], programs, entry, "primal", light_p);
  };
  work.upload = [&](Worker& worker, const Tile& tile, int slot) {
    auto& state = states[worker.position()];
    write_async(worker, state.rows[slot], transport.indices.data() + tile.begin * k, tile.size() * k);
    write_async(worker, state.weights[slot], transport.weights.data() + tile.begin * k, tile.size() * k);
  };
  work.compute = [&](Worker& worker, const Tile& tile, int slot) {
    auto& state = states[worker.position()];
    run_tile(worker, state, entry, tile, slot, image, static_cast<cl_uint>(k),
             state.rows[slot].at_least(worker.device(), 0, 0), state.weights[slot].at_least(worker.device(), 0, 0));
  };
  return run_product(devices, transport.camera_pixels(), options, "primal", work, image);
}

ProductRun dual_on_devices(std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs, cl::KernelEntry entry,
                           const transport::TransposedTransport& transposed, const std::vector<float>& light_c,
                           Options options) {
  const auto pixels = static_cast<std::size_t>(transposed.projector_size.area());
  if (transposed.row_start.size() != pixels + 1) throw std::invalid_argument("dual: malformed transposed transport");
  std::vector<float> image(pixels, 0.0f);
  std::vector<DeviceState> states(devices.size());
  TileWork work;
  work.prepare = [&](Worker& worker) { prepare(worker, states[worker.position()], programs, entry, "dual", light_c); };
  work.upload = [&](Worker& worker, const Tile& tile, int slot) {
    auto& state = states[worker.position()];
    const std::int32_t first = transposed.row_start[tile.begin];
    const auto nonzeros = static_cast<std::size_t>(transposed.row_start[tile.end] - first);
    auto& rebased = state.rebased[slot];
    rebased.assign(transposed.row_start.begin() + static_cast<std::ptrdiff_t>(tile.begin),
                   transposed.row_start.begin() + static_cast<std::ptrdiff_t>(tile.end) + 1);
    for (auto& start : rebased) start -= first;
    write_async(worker, state.rows[slot], rebased.data(), rebased.size());
    write_async(worker, state.columns[slot], transposed.camera_pixel.data() + first, nonzeros);
    write_async(worker, state.weights[slot], transposed.weights.data() + first, nonzeros);
  };
  work.compute = [&](Worker& worker, const Tile& tile, int slot) {
    auto& state = states[worker.position()];
    auto& device = worker.device();
    run_tile(worker, state, entry, tile, slot, image, state.rows[slot].at_least(device, 0, 0),
             state.columns[slot].at_least(device, 0, 0), state.weights[slot].at_least(device, 0, 0));
  };
  return run_product(devices, pixels, options, "dual", work, image);
}

}  // namespace rfrecon::sched
