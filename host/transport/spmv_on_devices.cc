// Tiled, double-buffered primal and dual products on several devices (kernels/transport/spmv.cl).
#include "host/transport/spmv_on_devices.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "host/cl/kernel_launch.h"

namespace rfrecon::transport {

namespace {

// Tiles are multiples of this many output pixels: large enough that per-tile overhead stays small.
constexpr std::size_t kGranularity = 256;
constexpr std::size_t kWorkGroup = 64;

// The tile's inputs in the slot's buffer: lent where the device runs kernels on the host's memory (no copy; the
// scheduler uploads a slot again only after its tile has run), else uploaded on the transfer queue without waiting.
template <typename T>
void tile_input(sched::Worker& worker, cl::GrowingBuffer& buffer, const T* data, std::size_t count) {
  if (worker.device().info().host_unified_memory && count > 0) {
    buffer.lend(worker.device().context(), data, count);
    return;
  }
  const ::cl::Buffer& target = buffer.at_least(worker.device().context(), count * sizeof(T), CL_MEM_READ_ONLY);
  cl::write_buffer(worker.transfer_queue(), target, data, count, false);
}

// One device's kernel, the light vector (same for every tile) and two sets of tile buffers.
struct DeviceState {
  std::vector<std::int32_t> rebased[2];     // dual: host copy of the rebased row starts (outlives the buffers over it)
  std::vector<std::int32_t> entry_rows[2];  // dual, single work-item entry: each entry's row in the tile
  ::cl::Kernel kernel;
  ::cl::Buffer light;
  cl::GrowingBuffer rows[2];     // primal: ELL indices; dual: rebased CSR row starts
  cl::GrowingBuffer columns[2];  // dual: camera pixels
  cl::GrowingBuffer entry_row_buffers[2];
  cl::GrowingBuffer weights[2];
  cl::GrowingBuffer output[2];
};

void prepare(sched::Worker& worker, DeviceState& state, cl::ProgramCache& programs, const char* name,
             const std::string& options, const std::vector<float>& light) {
  state.kernel = cl::make_kernel(programs.get(worker.device(), "transport/spmv.cl", options), name, worker.entry());
  state.light = cl::upload(worker.device().context(), light);
}

// Sets the arguments, runs the kernel after the slot's uploads, reads the tile's pixels and delivers them to `image`.
template <typename... Args>
void run_tile(sched::Worker& worker, DeviceState& state, const sched::Tile& tile, int slot, std::vector<float>& image,
              const Args&... args) {
  const ::cl::Buffer& output =
      state.output[slot].at_least(worker.device().context(), tile.size() * sizeof(float), CL_MEM_WRITE_ONLY);
  cl::set_args(state.kernel, args..., state.light, output, static_cast<cl_uint>(tile.size()));
  // A fixed work-group size, the global size rounded up to it (the kernels skip ids >= n): tiles of many sizes
  // would otherwise make PoCL compile the kernel again for every work-group size it picks.
  const std::size_t group = std::min<std::size_t>(kWorkGroup, worker.device().info().max_work_group_size);
  cl::enqueue_kernel(worker.queue(), state.kernel, worker.entry(), tile.size(), {group, &worker.inputs_ready(slot)});
  const auto pixels = cl::download<float>(worker.queue(), output, tile.size());
  worker.deliver(
      [&] { std::copy(pixels.begin(), pixels.end(), image.begin() + static_cast<std::ptrdiff_t>(tile.begin)); });
}

ProductRun run_product(std::vector<cl::DeviceContext>& devices, std::size_t pixels, const cl::EntryChoice& entries,
                       sched::Options& options, const char* stage, sched::TileWork& work, std::vector<float>& image) {
  if (options.stage == sched::Options().stage) options.stage = stage;
  options.entries = entries;
  if (options.granularity == 0) options.granularity = kGranularity;
  ProductRun run;
  run.report = sched::run_tiles(devices, pixels, work, options);
  run.image = std::move(image);
  return run;
}

}  // namespace

ProductRun primal_on_devices(std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs,
                             const cl::EntryChoice& entries, const transport::CompressedTransport& transport,
                             const std::vector<float>& light_p, sched::Options options) {
  if (light_p.size() != transport.projector_pixels()) {
    throw std::invalid_argument("primal: light has " + std::to_string(light_p.size()) + " values, expected " +
                                std::to_string(transport.projector_pixels()));
  }
  const auto k = static_cast<std::size_t>(transport.k());
  std::vector<float> image(transport.camera_pixels(), 0.0f);
  std::vector<DeviceState> states(devices.size());
  sched::TileWork work;
  work.prepare = [&](sched::Worker& worker) {
    prepare(worker, states[worker.position()], programs, "primal", transport_build_options(transport.k()), light_p);
  };
  work.upload = [&](sched::Worker& worker, const sched::Tile& tile, int slot) {
    auto& state = states[worker.position()];
    tile_input(worker, state.rows[slot], transport.indices.data() + tile.begin * k, tile.size() * k);
    tile_input(worker, state.weights[slot], transport.weights.data() + tile.begin * k, tile.size() * k);
  };
  work.compute = [&](sched::Worker& worker, const sched::Tile& tile, int slot) {
    auto& state = states[worker.position()];
    run_tile(worker, state, tile, slot, image, state.rows[slot].buffer(), state.weights[slot].buffer());
  };
  return run_product(devices, transport.camera_pixels(), entries, options, "primal", work, image);
}

ProductRun dual_on_devices(std::vector<cl::DeviceContext>& devices, cl::ProgramCache& programs,
                           const cl::EntryChoice& entries, const transport::TransposedTransport& transposed,
                           const std::vector<float>& light_c, sched::Options options) {
  const auto pixels = static_cast<std::size_t>(transposed.projector_size.area());
  if (transposed.row_start.size() != pixels + 1) throw std::invalid_argument("dual: malformed transposed transport");
  std::vector<float> image(pixels, 0.0f);
  std::vector<DeviceState> states(devices.size());
  sched::TileWork work;
  work.prepare = [&](sched::Worker& worker) {
    prepare(worker, states[worker.position()], programs, "dual", {}, light_c);
  };
  work.upload = [&](sched::Worker& worker, const sched::Tile& tile, int slot) {
    auto& state = states[worker.position()];
    const std::int32_t first = transposed.row_start[tile.begin];
    const auto nonzeros = static_cast<std::size_t>(transposed.row_start[tile.end] - first);
    auto& rebased = state.rebased[slot];
    rebased.assign(transposed.row_start.begin() + static_cast<std::ptrdiff_t>(tile.begin),
                   transposed.row_start.begin() + static_cast<std::ptrdiff_t>(tile.end) + 1);
    for (auto& start : rebased) start -= first;
    tile_input(worker, state.rows[slot], rebased.data(), rebased.size());
    if (worker.entry() == KernelEntry::kSingleWorkItem) {
      state.entry_rows[slot] = entry_rows(transposed.row_start, tile.begin, tile.end);
      tile_input(worker, state.entry_row_buffers[slot], state.entry_rows[slot].data(), nonzeros);
    }
    tile_input(worker, state.columns[slot], transposed.camera_pixel.data() + first, nonzeros);
    tile_input(worker, state.weights[slot], transposed.weights.data() + first, nonzeros);
  };
  work.compute = [&](sched::Worker& worker, const sched::Tile& tile, int slot) {
    auto& state = states[worker.position()];
    if (worker.entry() == KernelEntry::kSingleWorkItem) {
      run_tile(worker, state, tile, slot, image, state.rows[slot].buffer(), state.entry_row_buffers[slot].buffer(),
               state.columns[slot].buffer(), state.weights[slot].buffer());
    } else {
      run_tile(worker, state, tile, slot, image, state.rows[slot].buffer(), state.columns[slot].buffer(),
               state.weights[slot].buffer());
    }
  };
  return run_product(devices, pixels, entries, options, "dual", work, image);
}

}  // namespace rfrecon::transport
