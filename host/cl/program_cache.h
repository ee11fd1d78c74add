// Builds OpenCL programs from embedded sources once per device and source (loading them from the on-disk program store
// when an earlier run built them), or loads the board binary once per device.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "host/cl/binary_manifest.h"
#include "host/cl/device_context.h"
#include "host/cl/opencl.h"
#include "host/cl/program_store.h"

namespace rfrecon::cl {

// The board's precompiled binary (an FPGA bitstream, .aocx or .xclbin) with its manifest FILE.json beside it; read
// when a ProgramCache is made without one. Else the directory of $RFRECON_KERNEL_BINARY_DIR, which must hold exactly
// one binary with a manifest (docs/fpga.md).
inline constexpr const char* kBinaryEnv = "RFRECON_KERNEL_BINARY";
inline constexpr const char* kBinaryDirEnv = "RFRECON_KERNEL_BINARY_DIR";

// The lines prepended to every source built for this device: a comment naming it, RF_TARGET_INTEL_FPGA or
// RF_TARGET_XILINX_FPGA on those boards (kernels/common/target.h), then `#line 1`.
std::string device_preamble(const DeviceInfo& info);

// The device's program binary, as clGetProgramInfo(CL_PROGRAM_BINARIES) returns it.
std::vector<unsigned char> program_binary(const ::cl::Program& program);

// Writes program_binary(program) to path atomically.
void save_program_binary(const ::cl::Program& program, const std::filesystem::path& path);

// How the programs of a ProgramCache came to be: compiled from source, or loaded from the program store.
struct ProgramBuilds {
  int built = 0;             // compiled from source (then saved to the store)
  int loaded = 0;            // loaded from the store's binaries
  double build_seconds = 0;  // summed over the builds, which may overlap on several devices
  double load_seconds = 0;
};

// {"compiled": 1, "loaded": 3, "compile_seconds": 0.8, "load_seconds": 0.05}
void to_json(nlohmann::json& json, const ProgramBuilds& builds);

// "0 compiled, 4 loaded from the program cache ~/.cache/rfrecon/programs" (or "(program cache off)").
std::string describe(const ProgramBuilds& builds, const ProgramStore& store);

class ProgramCache {
 public:
  // binary: the board binary, or a directory holding exactly one (find_board_binary); empty means
  // $RFRECON_KERNEL_BINARY, else $RFRECON_KERNEL_BINARY_DIR (possibly both unset). store: where programs built from
  // source are kept between runs (ProgramStore::default_directory() unless given).
  explicit ProgramCache(std::filesystem::path binary = {}, ProgramStore store = ProgramStore());

  // The built program for an embedded kernel file. Devices without an online compiler (FPGA boards), and
  // accelerators when a binary is set, get the board binary's program, which serves every kernel file: loaded once
  // per context after its manifest passed check_binary_manifest (BinaryManifestError otherwise), and `options` must
  // restate its parameters (check_options_match_manifest). Others build the embedded source after
  // device_preamble(). Throws ClError when a device needs the binary and none is set, BuildError with the log when
  // a build fails.
  ::cl::Program get(DeviceContext& device, std::string_view kernel_path, std::string_view options = {});

  // Builds OpenCL C text directly (the preamble is prepended); cached by device and source hash.
  ::cl::Program build_source(DeviceContext& device, std::string_view name, std::string_view source,
                             std::string_view options = {});

  // clCreateProgramWithBinary + clBuildProgram from a file, with no manifest check (get() checks first); throws
  // std::runtime_error naming an unreadable file.
  ::cl::Program build_binary(DeviceContext& device, const std::filesystem::path& path, std::string_view options = {});

  // True when get() would load the board binary for this device rather than build from source.
  bool uses_binary(const DeviceInfo& info) const;
  // The board binary or its directory, as given or read from the environment; empty when none is set.
  const std::filesystem::path& binary_location() const { return binary_location_; }

  // Number of distinct programs built so far (for tests of the cache).
  std::size_t size() const;
  // The source programs compiled and loaded so far.
  ProgramBuilds builds() const;
  const ProgramStore& store() const { return store_; }

 private:
  using Key = std::pair<cl_context, std::uint64_t>;  // programs belong to a context, not a device
  // store_key: the program's key in the store (0 for board binaries, which are not stored).
  ::cl::Program cached_or_built(DeviceContext& device, std::uint64_t hash, std::string_view name,
                                const std::function<::cl::Program()>& create, std::string_view options,
                                std::uint64_t store_key);
  // The program stored under key built for the device, or a null program when there is none or it does not build.
  ::cl::Program load_stored(DeviceContext& device, std::uint64_t key, std::string_view options);

  struct BoardProgram {
    BinaryManifest manifest;
    ::cl::Program program;
  };
  // The context's board program, checked and loaded on first use.
  const BoardProgram& board_program(DeviceContext& device);

  std::filesystem::path binary_location_;
  ProgramStore store_;
  mutable std::mutex mutex_;
  std::map<Key, ::cl::Program> programs_;
  using Request = std::pair<cl_context, std::string>;  // get()'s kernel path and options, one line each
  std::map<Request, ::cl::Program> requests_;          // get()'s programs built from source, by request
  ProgramBuilds builds_;
  std::mutex board_mutex_;  // held while a board binary loads, so each context loads it once
  std::map<cl_context, BoardProgram> boards_;
};

// A kernel file and its build options, as ProgramCache::get takes them.
struct ProgramRequest {
  std::string kernel_path;
  std::string options;
};

// Builds (or loads) every requested program on every device up front, the devices in parallel, so that a command
// times its program builds as a stage of their own and its stages start with the programs ready. A device that
// fails is skipped with a debug log: its stage meets the failure again and reports it (the scheduler then runs its
// tiles on the other devices).
void prepare_programs(std::vector<DeviceContext>& devices, ProgramCache& programs,
                      const std::vector<ProgramRequest>& requests);
// The same with each device's own requests: requests_for(position of the device in `devices`).
void prepare_programs(std::vector<DeviceContext>& devices, ProgramCache& programs,
                      const std::function<std::vector<ProgramRequest>(std::size_t)>& requests_for);

}  // namespace rfrecon::cl
