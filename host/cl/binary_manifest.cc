// Finding a board binary and checking its manifest against the host's parameters and embedded kernel sources.
#include "host/cl/binary_manifest.h"

#include <algorithm>
#include <sstream>

#include "host/cl/kernel_sources.h"
#include "host/core/errors.h"
#include "host/core/file_sha256.h"
#include "host/core/input_file.h"
#include "host/core/json_file.h"
#include "host/core/limits.h"
#include "host/core/message_text.h"
#include "kernels/common/params.h"

namespace rfrecon::cl {

namespace {
std::string describe_problem(const std::filesystem::path& file, const std::string& field, const std::string& problem) {
  return file.string() + (field.empty() ? "" : ": field " + field) + ": " + problem;
}

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& field, const std::string& problem) {
  throw BinaryManifestError(file, field, problem);
}

void expect_equal(const std::filesystem::path& file, const std::string& field, const nlohmann::json& expected,
                  const nlohmann::json& found, const std::string& whose) {
  if (expected != found) {
    fail(file, field, "expected " + expected.dump() + " (" + whose + "), found " + excerpt(found.dump()));
  }
}

// The manifest's fields and their JSON types (docs/formats.md); every one must be present.
struct FieldType {
  const char* name;
  nlohmann::json::value_t type;
  const char* type_name;
};
constexpr FieldType kFields[] = {
    {"binary", nlohmann::json::value_t::string, "a string"},
    {"board", nlohmann::json::value_t::string, "a string"},
    {"device", nlohmann::json::value_t::string, "a string"},
    {"target", nlohmann::json::value_t::string, "a string"},
    {"tool", nlohmann::json::value_t::string, "a string"},
    {"tool_version", nlohmann::json::value_t::string, "a string"},
    {"target_macro", nlohmann::json::value_t::string, "a string"},
    {"source_sha256", nlohmann::json::value_t::string, "a string"},
    {"binary_sha256", nlohmann::json::value_t::string, "a string"},
    {"stand_in", nlohmann::json::value_t::boolean, "true or false"},
    {"parameters", nlohmann::json::value_t::object, "an object"},
    {"kernels", nlohmann::json::value_t::array, "an array of kernel names"},
    {"sources", nlohmann::json::value_t::array, "an array of file names"},
    {"extra_flags", nlohmann::json::value_t::array, "an array of compiler flags"},
};

void check_format(const std::filesystem::path& file, const nlohmann::json& manifest) {
  if (!manifest.is_object()) fail(file, "", "not a JSON object");
  for (const auto& field : kFields) {
    const auto it = manifest.find(field.name);
    if (it == manifest.end()) fail(file, field.name, "missing");
    if (it->type() != field.type)
      fail(file, field.name, std::string("expected ") + field.type_name + ", found " + excerpt(it->dump()));
  }
  for (const char* list : {"kernels", "sources", "extra_flags"}) {
    for (const auto& item : manifest[list]) {
      if (!item.is_string()) fail(file, list, "expected an array of strings, found " + excerpt(manifest[list].dump()));
    }
  }
}
}  // namespace

BinaryManifestError::BinaryManifestError(const std::filesystem::path& file, const std::string& field,
                                         const std::string& problem)
    : ClError("checking kernel binary", CL_INVALID_BINARY, __FILE__, __LINE__, describe_problem(file, field, problem)),
      file_(file),
      field_(field) {}

std::string target_macro(const DeviceInfo& info) {
  if (info.intel_fpga) return "RF_TARGET_INTEL_FPGA";
  if (info.xilinx_fpga) return "RF_TARGET_XILINX_FPGA";
  return "";
}

nlohmann::json host_kernel_parameters() { return nlohmann::json::parse(RF_PARAMETERS_JSON); }

ManifestExpectation host_manifest_expectation(const DeviceInfo& info) {
  ManifestExpectation expected;
  expected.parameters = host_kernel_parameters();
  expected.source_sha256 = std::string(embedded_kernel_sources_sha256());
  expected.hls_source_sha256 = std::string(embedded_hls_sources_sha256());
  for (const auto name : embedded_kernel_names()) {
    constexpr std::string_view kSingle = "_single";
    if (name.size() > kSingle.size() && name.substr(name.size() - kSingle.size()) == kSingle) {
      expected.kernels.emplace_back(name);
    }
  }
  expected.target_macros = {target_macro(info)};
  if (info.xilinx_fpga) expected.target_macros.emplace_back("RF_TARGET_HLS");
  if (info.intel_fpga) {
    const bool emulated = info.fpga_emulation == "emulator";
    expected.target = emulated ? "emulator" : "hardware";
    expected.target_device = emulated ? "the Intel FPGA emulator"
                                      : "an Intel FPGA board: the emulator shows an emulation platform or device, or "
                                        "runs with CL_CONTEXT_EMULATOR_DEVICE_INTELFPGA=1";
  } else if (info.xilinx_fpga) {
    expected.target = info.fpga_emulation.empty() ? "hw" : info.fpga_emulation;
    expected.target_device = info.fpga_emulation.empty()
                                 ? "an AMD/Xilinx board: XCL_EMULATION_MODE is not set"
                                 : "an XRT emulation device: XCL_EMULATION_MODE=" + info.fpga_emulation;
  }
  return expected;
}

BinaryManifest check_binary_manifest(const std::filesystem::path& binary, const ManifestExpectation& expected) {
  const std::filesystem::path file = binary.string() + ".json";
  if (const auto problem = input_file_problem(binary, "no such kernel binary"); !problem.empty()) {
    fail(binary, "", problem);
  }
  if (const auto problem = input_file_problem(
          file, "missing: every board binary needs the manifest its hw/ flow writes beside it (docs/fpga.md)");
      !problem.empty()) {
    fail(file, "", problem);
  }
  std::string text;
  try {
    text = read_input_file(file, kMaxJsonBytes, "a JSON file");
  } catch (const InputError& error) {  // too large, or unreadable
    fail(file, "", std::string("not a readable manifest: ") + error.what());
  }
  std::string problem;
  auto parsed = parse_json_text(text, problem);
  if (!parsed) fail(file, "", problem);
  nlohmann::json& manifest = *parsed;
  check_format(file, manifest);
  expect_equal(file, "binary", binary.filename().string(), manifest["binary"], "the binary's file name");
  if (manifest["stand_in"].get<bool>()) {
    fail(file, "stand_in", "true: the binary was written by a stand-in compiler (tests/fpga), not by aoc or v++");
  }
  if (std::find(expected.target_macros.begin(), expected.target_macros.end(), manifest["target_macro"]) ==
      expected.target_macros.end()) {
    const nlohmann::json accepted = expected.target_macros.size() == 1 ? nlohmann::json(expected.target_macros[0])
                                                                       : nlohmann::json(expected.target_macros);
    expect_equal(file, "target_macro", accepted, manifest["target_macro"],
                 expected.target_macros.size() == 1 ? "the device's preamble" : "the ones this device runs");
  }
  if (!expected.target.empty() && manifest["target"] != expected.target) {
    const std::string found = manifest["target"].get<std::string>();
    const bool report = found == "report";
    fail(file, "target",
         "expected \"" + expected.target + "\" (" + expected.target_device + "), found \"" + excerpt(found) + "\": " +
             (report ? "a report-only compile (aoc -rtl), which no device loads"
                     : "a binary built for another target than this device's; build and load the " + expected.target +
                           " binary (docs/fpga.md)"));
  }
  const auto& parameters = manifest["parameters"];
  for (const auto& [name, value] : expected.parameters.items()) {
    const auto it = parameters.find(name);
    if (it == parameters.end()) fail(file, "parameters." + name, "missing, expected " + value.dump());
    expect_equal(file, "parameters." + name, value, *it, "the host's kernels/common/params.h");
  }
  for (const auto& [name, value] : parameters.items()) {
    if (!expected.parameters.contains(name)) {
      fail(file, "parameters." + excerpt(name),
           "found " + excerpt(value.dump()) + ", a parameter this host does not know");
    }
  }
  if (manifest["target_macro"] == "RF_TARGET_HLS") {
    expect_equal(file, "source_sha256", expected.hls_source_sha256, manifest["source_sha256"],
                 "the host's embedded kernel sources and the HLS C++ tops of hw/hls it was built with");
  } else {
    expect_equal(file, "source_sha256", expected.source_sha256, manifest["source_sha256"],
                 "the host's embedded kernel sources");
  }
  const auto& kernels = manifest["kernels"];
  for (const auto& kernel : expected.kernels) {
    if (std::find(kernels.begin(), kernels.end(), kernel) == kernels.end()) {
      fail(file, "kernels", "expected " + kernel + " among them (the host runs it), found " + excerpt(kernels.dump()));
    }
  }
  // Last, as it reads the whole binary (hundreds of MB for a board).
  expect_equal(file, "binary_sha256", file_sha256(binary), manifest["binary_sha256"],
               "the SHA-256 of " + binary.filename().string() + ": a binary rebuilt or replaced without its manifest?");
  return {binary, file, parameters, manifest["extra_flags"]};
}

std::filesystem::path find_board_binary(const std::filesystem::path& location) {
  if (!std::filesystem::is_directory(location)) return location;
  std::vector<std::filesystem::path> binaries;
  for (const auto& entry : std::filesystem::directory_iterator(location)) {
    const auto& path = entry.path();
    if (path.extension() == ".json" && entry.is_regular_file() &&
        std::filesystem::is_regular_file(path.parent_path() / path.stem())) {
      binaries.push_back(path.parent_path() / path.stem());
    }
  }
  std::sort(binaries.begin(), binaries.end());
  if (binaries.size() == 1) return binaries.front();
  std::string names;
  for (const auto& binary : binaries) names += (names.empty() ? "" : ", ") + binary.filename().string();
  fail(location, "",
       binaries.empty() ? "holds no kernel binary with a manifest beside it (FILE and FILE.json)"
                        : "holds " + std::to_string(binaries.size()) + " kernel binaries with manifests (" + names +
                              "): set RFRECON_KERNEL_BINARY to the one to load");
}

void check_options_match_manifest(const BinaryManifest& manifest, std::string_view options) {
  std::istringstream words{std::string(options)};
  std::string option;
  while (words >> option) {
    const auto equals = option.find('=');
    const bool is_define = option.compare(0, 2, "-D") == 0 && equals != std::string::npos;
    const std::string name = is_define ? option.substr(2, equals - 2) : std::string();
    const auto it = manifest.parameters.find(name);
    if (!is_define || it == manifest.parameters.end()) {
      fail(manifest.file, "parameters",
           "build option " + option + " cannot apply to the precompiled " + manifest.binary.filename().string() +
               ", which fixes only " + excerpt(manifest.parameters.dump(), 2 * kMaxQuotedChars));
    }
    if (option.substr(equals + 1) != it->dump()) {
      fail(manifest.file, "parameters." + name,
           "expected " + option.substr(equals + 1) + " (the run-time option " + option + "), found " +
               excerpt(it->dump()) + ": rebuild the binary with that value or run with the binary's");
    }
  }
}

}  // namespace rfrecon::cl
