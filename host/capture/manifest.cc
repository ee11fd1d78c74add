// Reading, writing and validating capture manifests, and loading linearized frames.
#include "host/capture/manifest.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "host/capture/graycode_patterns.h"
#include "host/capture/pattern_family.h"
#include "host/core/atomic_file.h"
#include "host/core/errors.h"
#include "host/core/image_file.h"
#include "host/core/input_file.h"
#include "host/core/json_file.h"
#include "host/core/limits.h"
#include "host/core/message_text.h"

namespace rfrecon::capture {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
constexpr int kManifestVersion = 1;

// The g of "gamma:<g>", or 1 for "linear"; throws InputError for anything else.
double response_gamma(const std::string& response, const std::string& file) {
  if (response == "linear") return 1.0;
  const std::string prefix = "gamma:";
  if (response.rfind(prefix, 0) == 0) {
    try {
      const double gamma = std::stod(response.substr(prefix.size()));
      if (gamma > 0.0) return gamma;
    } catch (const std::exception&) {
    }
  }
  throw InputError(file + ": camera_response '" + excerpt(response) + "' is not 'linear' or 'gamma:<g>' with g > 0");
}

json size_to_json(cv::Size size) { return json::array({size.width, size.height}); }

// The registered family of that name; InputError starting with `where` listing the families otherwise.
const PatternFamily& family_of(const std::string& name, const std::string& where) {
  try {
    return pattern_family(name);
  } catch (const InputError& error) {
    throw InputError(where + ": family: " + error.what());
  }
}

json frame_to_json(const Frame& frame, const PatternFamily& family) {
  json item{{"file", frame.file}, {"pattern", frame.pattern.kind}};
  family.write_entry(frame.pattern, item);
  return item;
}

// Reads a field with a message naming the manifest and the field when it is missing or of the wrong type.
template <typename T>
T field(const json& object, const std::string& key, const std::string& where, const fs::path& file) {
  if (!object.contains(key)) throw InputError(file.string() + ": missing field '" + where + key + "'");
  std::string problem;
  auto value = json_as<T>(object.at(key), problem);
  if (!value) throw InputError(file.string() + ": field '" + where + key + "' has the wrong type: must be " + problem);
  return std::move(*value);
}

// An optional field: `fallback` when absent, else read as field() does.
template <typename T>
T optional_field(const json& object, const std::string& key, T fallback, const fs::path& file) {
  return object.contains(key) ? field<T>(object, key, "", file) : fallback;
}

cv::Size size_field(const json& object, const std::string& key, const fs::path& file) {
  const auto values = field<std::vector<int>>(object, key, "", file);
  if (values.size() != 2 || values[0] < 0 || values[1] < 0) {
    throw InputError(file.string() + ": field '" + key + "' must be [width, height] with non-negative values");
  }
  const cv::Size size(values[0], values[1]);
  check_image_size(size, file.string() + ": field '" + key + "'");
  return size;
}

// The optional object "parameters": whole numbers by name.
std::map<std::string, int> parameters_field(const json& root, const fs::path& file) {
  std::map<std::string, int> parameters;
  if (!root.contains("parameters")) return parameters;
  const json& object = root.at("parameters");
  if (!object.is_object()) throw InputError(file.string() + ": field 'parameters' must be an object");
  for (const auto& [name, value] : object.items()) parameters[name] = field<int>(object, name, "parameters.", file);
  return parameters;
}

// A frame's file: a relative path without "..", NUL or empty parts, that stays inside the capture directory after
// links are resolved (unless `paths` allows anywhere).
void check_frame_path(const std::string& name, const fs::path& dir, FramePaths paths, const std::string& where,
                      const fs::path& file) {
  const auto fail = [&](const std::string& what) {
    throw InputError(file.string() + ": " + where + "file '" + excerpt(name) + "' " + what);
  };
  if (name.empty()) fail("is empty");
  if (name.find('\0') != std::string::npos) fail("contains a NUL character");
  if (paths == FramePaths::kAnywhere) return;
  const fs::path path(name);
  if (path.is_absolute())
    fail("is absolute; frames must lie in the capture directory (or pass --allow-outside-frames)");
  for (const auto& part : path) {
    if (part == "..") fail("leaves the capture directory; frames must lie in it (or pass --allow-outside-frames)");
  }
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(dir / path, ec);
  const fs::path root = fs::weakly_canonical(dir, ec);
  const fs::path relative = resolved.lexically_relative(root);
  if (ec || relative.empty() || *relative.begin() == "..") {
    fail("resolves outside the capture directory (a link?); frames must lie in it (or pass --allow-outside-frames)");
  }
}

Frame frame_from_json(const json& item, std::size_t index, const PatternFamily& family, const fs::path& file) {
  const std::string where = "frames[" + std::to_string(index) + "].";
  Frame frame;
  frame.file = field<std::string>(item, "file", where, file);
  frame.pattern.kind = field<std::string>(item, "pattern", where, file);
  family.read_entry(item, file.string() + ": frames[" + std::to_string(index) + "]", frame.pattern);
  return frame;
}

}  // namespace

ProtocolOptions protocol_options(const CaptureManifest& manifest) {
  return {manifest.projector_size, manifest.dot_spacing, manifest.family, manifest.parameters};
}

void validate_manifest(const CaptureManifest& manifest, const std::string& where) {
  const auto fail = [&](const std::string& what) { throw InputError(where + ": " + what); };
  if (manifest.projector_size.width < 2 || manifest.projector_size.height < 2) {
    fail("projector_size must be at least 2x2");
  }
  if (manifest.bit_depth != 8 && manifest.bit_depth != 10 && manifest.bit_depth != 12 && manifest.bit_depth != 16) {
    fail("bit_depth must be 8, 10, 12 or 16, got " + std::to_string(manifest.bit_depth));
  }
  const double full_scale = std::ldexp(1.0, manifest.bit_depth) - 1.0;
  if (manifest.black_level < 0 || manifest.black_level >= full_scale) {
    fail("black_level must be in [0, " + std::to_string(full_scale) + ")");
  }
  (void)response_gamma(manifest.camera_response, where);
  for (double exposure : manifest.exposures_us) {
    if (!(exposure > 0.0 && std::isfinite(exposure))) fail("exposures_us must hold positive microseconds");
  }
  const PatternFamily& family = family_of(manifest.family, where);
  const auto count = [&](const char* kind) {
    return std::count_if(manifest.frames.begin(), manifest.frames.end(),
                         [&](const Frame& frame) { return frame.pattern.kind == kind; });
  };
  if (count(pattern_kind::kWhite) != 1 || count(pattern_kind::kBlack) != 1) {
    fail("needs exactly one white and one black frame");
  }
  check_family_parameters(family, manifest.parameters, where);
  family.validate(manifest, where);
}

namespace {

// Every frame is a regular file, and no file stands for two patterns.
void check_frame_files(const CaptureManifest& manifest, const fs::path& dir, const fs::path& file) {
  std::map<fs::path, std::size_t> first_use;
  for (std::size_t i = 0; i < manifest.frames.size(); ++i) {
    const fs::path path = dir / manifest.frames[i].file;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (status.type() == fs::file_type::not_found) {
      throw InputError("missing frame: " + excerpt(path.string(), 2 * kMaxQuotedChars) + " (listed in " +
                       file.string() + ")");
    }
    if (!fs::is_regular_file(status)) {
      throw InputError("unreadable frame: " + excerpt(path.string(), 2 * kMaxQuotedChars) + " (listed in " +
                       file.string() + "): " + (ec ? ec.message() : "is " + kind_of_file(status)) +
                       "; rfrecon reads only regular files");
    }
    const auto [it, fresh] = first_use.emplace(fs::canonical(path, ec), i);
    if (!fresh) {
      throw InputError(file.string() + ": frames[" + std::to_string(it->second) + "] and frames[" + std::to_string(i) +
                       "] are the same file (" + excerpt(manifest.frames[i].file) +
                       "); every pattern needs its own capture");
    }
  }
}
}  // namespace

CaptureManifest read_manifest(const fs::path& capture_dir, FramePaths frame_paths) {
  const fs::path file = capture_dir / kManifestFileName;
  std::error_code ec;
  if (!fs::exists(file, ec)) {
    throw InputError("cannot read " + file.string() +
                     " (a capture directory needs a manifest; for OpenCV-style captures pass --layout "
                     "opencv-graycode --projector WxH)");
  }
  const json root = read_json_file(file);
  if (!root.is_object()) throw InputError(file.string() + ": the top level must be a JSON object");
  const int version = field<int>(root, "version", "", file);
  if (version != kManifestVersion) {
    throw InputError(file.string() + ": manifest version " + std::to_string(version) + " is not supported (expected " +
                     std::to_string(kManifestVersion) + ")");
  }
  CaptureManifest manifest;
  manifest.projector_size = size_field(root, "projector_size", file);
  manifest.camera_size = root.contains("camera_size") ? size_field(root, "camera_size", file) : cv::Size();
  manifest.family = optional_field(root, "family", std::string(kDefaultFamily), file);
  manifest.dot_spacing = optional_field(root, "dot_spacing", 0, file);
  manifest.parameters = parameters_field(root, file);
  manifest.bit_depth = optional_field(root, "bit_depth", 8, file);
  manifest.black_level = optional_field(root, "black_level", 0.0, file);
  manifest.camera_response = optional_field(root, "camera_response", std::string("linear"), file);
  manifest.exposures_us = optional_field(root, "exposures_us", std::vector<double>{}, file);
  const PatternFamily& family = family_of(manifest.family, file.string());
  const auto frames = field<json>(root, "frames", "", file);
  if (!frames.is_array()) throw InputError(file.string() + ": field 'frames' must be an array");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (!frames[i].is_object())
      throw InputError(file.string() + ": frames[" + std::to_string(i) + "] is not an object");
    manifest.frames.push_back(frame_from_json(frames[i], i, family, file));
    check_frame_path(manifest.frames.back().file, capture_dir, frame_paths, "frames[" + std::to_string(i) + "].", file);
  }
  validate_manifest(manifest, file.string());
  check_frame_files(manifest, capture_dir, file);
  return manifest;
}

std::vector<fs::path> capture_files(const fs::path& capture_dir, const CaptureManifest& manifest) {
  std::vector<fs::path> files{capture_dir / kManifestFileName};
  for (const auto& frame : manifest.frames) files.push_back(capture_dir / frame.file);
  return files;
}

void write_manifest(const CaptureManifest& manifest, const fs::path& capture_dir) {
  const PatternFamily& family = pattern_family(manifest.family);
  json frames = json::array();
  for (const auto& frame : manifest.frames) frames.push_back(frame_to_json(frame, family));
  json root{{"format", "rfrecon-capture"},
            {"version", kManifestVersion},
            {"family", manifest.family},
            {"projector_size", size_to_json(manifest.projector_size)},
            {"camera_size", size_to_json(manifest.camera_size)},
            {"dot_spacing", manifest.dot_spacing},
            {"bit_depth", manifest.bit_depth},
            {"black_level", manifest.black_level},
            {"camera_response", manifest.camera_response},
            {"frames", frames}};
  if (!manifest.exposures_us.empty()) root["exposures_us"] = manifest.exposures_us;
  if (!manifest.parameters.empty()) root["parameters"] = manifest.parameters;
  write_file_atomically(capture_dir / kManifestFileName, root.dump(2) + "\n");
}

CaptureManifest manifest_from_opencv_layout(const fs::path& capture_dir, cv::Size projector_size, int bit_depth) {
  static const std::set<std::string> kImageExtensions{".png", ".tif", ".tiff", ".bmp", ".jpg", ".jpeg", ".pgm", ".ppm"};
  std::error_code ec;
  if (!fs::is_directory(capture_dir, ec)) {
    throw InputError("capture directory " + capture_dir.string() + " does not exist");
  }
  check_image_size(projector_size, "--projector");
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(capture_dir, ec)) {
    if (entry.is_regular_file() && kImageExtensions.count(lowercase_extension(entry.path())) != 0) {
      files.push_back(entry.path().filename().string());
    }
  }
  std::sort(files.begin(), files.end());
  const auto sequence = opencv_graycode_protocol(projector_size);
  if (files.size() != sequence.size()) {
    throw InputError(capture_dir.string() + ": the opencv-graycode layout for a " +
                     std::to_string(projector_size.width) + "x" + std::to_string(projector_size.height) +
                     " projector needs " + std::to_string(sequence.size()) +
                     " images (Gray code pairs, white, black)," + " found " + std::to_string(files.size()));
  }
  CaptureManifest manifest;
  manifest.projector_size = projector_size;
  for (std::size_t i = 0; i < files.size(); ++i) manifest.frames.push_back({sequence[i], files[i]});
  const fs::path first_file = capture_dir / files.front();
  const cv::Mat first = decode_image(first_file, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH);
  const int file_bits = first.depth() == CV_8U ? 8 : 16;
  if (bit_depth != 0 && (bit_depth == 8) != (file_bits == 8)) {
    throw InputError(first_file.string() + ": " + std::to_string(file_bits) + "-bit samples, but --bit-depth " +
                     std::to_string(bit_depth) + " (8 needs 8-bit files; 10, 12 and 16 need 16-bit files)");
  }
  manifest.bit_depth = bit_depth != 0 ? bit_depth : file_bits;
  manifest.camera_size = first.size();
  return manifest;
}

SampleMap sample_map(const CaptureManifest& manifest) {
  const double range = std::ldexp(1.0, manifest.bit_depth) - 1.0 - manifest.black_level;
  return {static_cast<float>(manifest.black_level), static_cast<float>(1.0 / range)};
}

bool linear_response(const CaptureManifest& manifest) {
  return response_gamma(manifest.camera_response, "manifest") == 1.0;
}

namespace {
template <typename Sample>
void linearize_rows(const cv::Mat& raw, cv::Mat& linear, SampleMap map) {
  for (int y = 0; y < raw.rows; ++y) {
    const Sample* in = raw.ptr<Sample>(y);
    float* out = linear.ptr<float>(y);
    for (int x = 0; x < raw.cols; ++x) out[x] = (static_cast<float>(in[x]) - map.black) * map.scale;
  }
}
}  // namespace

cv::Mat linearize_samples(const cv::Mat& raw, SampleMap map) {
  if (raw.channels() != 1 || (raw.depth() != CV_8U && raw.depth() != CV_16U)) {
    throw std::invalid_argument("linearize_samples: expected one channel of CV_8U or CV_16U samples");
  }
  cv::Mat linear(raw.size(), CV_32F);
  if (raw.depth() == CV_8U) {
    linearize_rows<std::uint8_t>(raw, linear, map);
  } else {
    linearize_rows<std::uint16_t>(raw, linear, map);
  }
  return linear;
}

void check_raw_frame(const cv::Mat& raw, const CaptureManifest& manifest, const std::string& file) {
  const int expected_depth = manifest.bit_depth == 8 ? CV_8U : CV_16U;
  if (raw.depth() != expected_depth) {
    throw InputError(file + ": " +
                     (raw.depth() == CV_8U    ? "8"
                      : raw.depth() == CV_16U ? "16"
                                              : "non-integer") +
                     "-bit samples, but the manifest says bit_depth " + std::to_string(manifest.bit_depth));
  }
  if (raw.channels() != 1) throw InputError(file + ": expected a single-channel image");
  if (!manifest.camera_size.empty() && raw.size() != manifest.camera_size) {
    throw InputError(file + ": size " + std::to_string(raw.cols) + "x" + std::to_string(raw.rows) +
                     " differs from the capture's camera size " + std::to_string(manifest.camera_size.width) + "x" +
                     std::to_string(manifest.camera_size.height));
  }
}

cv::Mat linearize_frame(const cv::Mat& raw, const CaptureManifest& manifest, const std::string& file) {
  check_raw_frame(raw, manifest, file);
  cv::Mat linear = linearize_samples(raw, sample_map(manifest));
  const double gamma = response_gamma(manifest.camera_response, file);
  if (gamma == 1.0) return linear;
  linear.forEach<float>([gamma](float& value, const int*) {
    value = std::copysign(static_cast<float>(std::pow(std::abs(value), gamma)), value);
  });
  return linear;
}

cv::Mat frame_in_form(const cv::Mat& raw, const CaptureManifest& manifest, const std::string& file, FrameForm form) {
  if (form == FrameForm::kLinear) return linearize_frame(raw, manifest, file);
  check_raw_frame(raw, manifest, file);
  return raw;
}

cv::Mat load_frame(const fs::path& capture_dir, const CaptureManifest& manifest, std::size_t index, FrameForm form) {
  const fs::path path = capture_dir / manifest.frames.at(index).file;
  return frame_in_form(decode_image(path, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH), manifest, path.string(), form);
}

}  // namespace rfrecon::capture
