// Board binaries and their manifests: which file is a device's one binary, and whether its manifest (written by the
// hw/ flows, docs/formats.md) matches this host's parameters header and embedded kernel sources, checked before the
// binary is loaded.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/cl/device_info.h"
#include "host/cl/error.h"

namespace rfrecon::cl {

// A board binary the host refuses: missing, ambiguous, or with a manifest that is missing, malformed or does not
// match. An OpenCL error (exit 5); what() names the file and the field with the expected and found values.
class BinaryManifestError : public ClError {
 public:
  // field: the manifest's field ("parameters.RF_K"), or empty when the problem is the file itself.
  BinaryManifestError(const std::filesystem::path& file, const std::string& field, const std::string& problem);
  const std::filesystem::path& manifest_file() const { return file_; }
  const std::string& field() const { return field_; }

 private:
  std::filesystem::path file_;
  std::string field_;
};

// The target macro the device's preamble defines: "RF_TARGET_INTEL_FPGA", "RF_TARGET_XILINX_FPGA", or "" for CPUs
// and GPUs (kernels/common/target.h).
std::string target_macro(const DeviceInfo& info);

// The parameters header's values (kernels/common/params.h) as a manifest records them: {"RF_K": 8,
// "RF_INTEGRATE_INTERLEAVE": 160, "RF_FUSE_INTERLEAVE": 32, "RF_MAX_ROW_WIDTH": 4096, "RF_FRAME_BATCH": 16,
// "RF_DOT_SPACINGS": [2, ..., 64]}.
nlohmann::json host_kernel_parameters();

// What a manifest must say for the host to load its binary on a device.
struct ManifestExpectation {
  nlohmann::json parameters;         // host_kernel_parameters()
  std::string source_sha256;         // embedded_kernel_sources_sha256()
  std::string hls_source_sha256;     // embedded_hls_sources_sha256(), for binaries of the HLS C++ tops
  std::vector<std::string> kernels;  // kernels the binary must hold: the embedded single work-item entries
  // target_macro(device), or on AMD/Xilinx boards also RF_TARGET_HLS (an xclbin of the HLS C++ tops of hw/hls/)
  std::vector<std::string> target_macros;
  // The flow target whose binary the device loads (manifest `target`), by its emulation (DeviceInfo::fpga_emulation):
  // "hardware" or "emulator" on Intel FPGA devices, "hw", "sw_emu" or "hw_emu" on AMD/Xilinx ones; empty for other
  // devices, which no hw/ flow targets (any target).
  std::string target;
  std::string target_device;  // what the device is, for the refusal: "an Intel FPGA board, not emulated"
};
ManifestExpectation host_manifest_expectation(const DeviceInfo& info);

// A checked manifest.
struct BinaryManifest {
  std::filesystem::path binary;  // the binary it describes
  std::filesystem::path file;    // the manifest, binary + ".json"
  nlohmann::json parameters;     // its `parameters`, equal to the expectation's
  nlohmann::json extra_flags;    // its `extra_flags`: what the flow added to every compile (RFRECON_FPGA_EXTRA_FLAGS)
};

// binary's manifest (binary + ".json"), read and checked against `expected`: valid JSON, every field of the format
// with its type, `binary` naming binary's file, `stand_in` false, then `target_macro` (one of the expected), `target`
// (the expected one: an emulation binary is refused on a board, a hardware one on an emulator, a report on both),
// `parameters`, `source_sha256`, `kernels` (a superset of the expected) and `binary_sha256` (the SHA-256 of binary's
// bytes). Throws BinaryManifestError at the first mismatch. Needs no device.
BinaryManifest check_binary_manifest(const std::filesystem::path& binary, const ManifestExpectation& expected);

// The board binary at `location`: the file itself, or in a directory the one file that has a manifest beside it
// (FILE and FILE.json). Throws BinaryManifestError when there is none, or more than one.
std::filesystem::path find_board_binary(const std::filesystem::path& location);

// Build options asked of a program that comes from this binary can only restate its parameters: each option must be
// -DNAME=VALUE with NAME one of the manifest's parameters and VALUE its value (a run-time K other than the binary's is
// refused). Throws BinaryManifestError naming the parameter, the option and the binary's value.
void check_options_match_manifest(const BinaryManifest& manifest, std::string_view options);

}  // namespace rfrecon::cl
