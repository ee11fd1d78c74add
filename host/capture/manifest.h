// The capture manifest (manifest.json): what a capture directory holds and how to read its frames.
// Written by `rfrecon patterns` (projector side) and by the synthetic rig (camera side); read by every stage.
// Format documented in docs/formats.md.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "host/capture/protocol.h"

namespace rfrecon::capture {

inline constexpr const char* kManifestFileName = "manifest.json";

struct Frame {
  Pattern pattern;
  std::string file;  // relative to the capture directory
};

struct CaptureManifest {
  cv::Size projector_size;
  std::string family = kDefaultFamily;      // the pattern family (host/capture/pattern_family.h)
  cv::Size camera_size;                     // {0, 0} in a projector-side (patterns) manifest
  int dot_spacing = 0;                      // the dot grid after the family's patterns; 0 when there is none
  std::map<std::string, int> parameters{};  // the family's parameters (host/capture/pattern_family.h)
  int bit_depth = 8;                        // bits per camera sample: 8, 10, 12 or 16 (stored in 8- or 16-bit files)
  double black_level = 0.0;                 // camera reading with no light, in digital numbers
  std::string camera_response = "linear";   // "linear" or "gamma:<g>" (reading = linear^(1/g))
  std::vector<double> exposures_us;         // as captured: one exposure, or several merged into each frame (HDR)
  std::vector<Frame> frames;
};

// The options that made the manifest's sequence: its projector size, family and dot spacing.
ProtocolOptions protocol_options(const CaptureManifest& manifest);

// Where a manifest's frames may lie: inside the capture directory (relative paths without "..", links that stay
// inside), or anywhere (`--allow-outside-frames`).
enum class FramePaths { kInsideCapture, kAnywhere };

// Reads DIR/manifest.json; throws InputError naming the file and the field when it is malformed or inconsistent
// (e.g. Gray code bit count that does not match the projector size, sizes over host/core/limits.h), when a frame
// is missing, lies outside DIR (unless kAnywhere) or is the same file as another frame.
CaptureManifest read_manifest(const std::filesystem::path& capture_dir,
                              FramePaths frame_paths = FramePaths::kInsideCapture);

// Checks that the values are in range and that the frames form the family's complete sequence for the projector size
// (one white, one black, and what the family's validate asks: for graycode every Gray code bit of both axes with its
// inverse and, with a dot grid, every offset once); throws InputError starting with `where` (the manifest's file or
// the frame source's name). read_manifest calls it.
void validate_manifest(const CaptureManifest& manifest, const std::string& where);

// The files reading the capture touches: DIR/manifest.json (when there is one) and every frame. Outputs are checked
// against them (host/core/output_path.h).
std::vector<std::filesystem::path> capture_files(const std::filesystem::path& capture_dir,
                                                 const CaptureManifest& manifest);

// Writes DIR/manifest.json atomically.
void write_manifest(const CaptureManifest& manifest, const std::filesystem::path& capture_dir);

// A manifest for a directory without one, laid out as OpenCV capture scripts save it (`--layout opencv-graycode`):
// image files sorted by name are opencv_graycode_protocol(projector_size). `bit_depth` is the camera's (8 for 8-bit
// files; 10, 12 or 16 for 16-bit files holding 0..2^bits-1), 0 for the files' own (8 or 16). Throws InputError when
// the file count does not match, or the files' depth does not fit `bit_depth`.
CaptureManifest manifest_from_opencv_layout(const std::filesystem::path& capture_dir, cv::Size projector_size,
                                            int bit_depth = 0);

// Raw camera samples to linear units: (sample - black) * scale in float arithmetic, so the black level is 0 exactly and
// full scale 1. The transport kernels apply it to raw frames in registers (kernels/common/frame_batch.h).
struct SampleMap {
  float black = 0.0f;
  float scale = 1.0f;
};
SampleMap sample_map(const CaptureManifest& manifest);
// Whether the camera response is linear: frames are linear after sample_map alone (no response curve to undo).
bool linear_response(const CaptureManifest& manifest);
// `raw` (one channel, CV_8U or CV_16U) as CV_32F (sample - map.black) * map.scale, as the kernels compute it.
cv::Mat linearize_samples(const cv::Mat& raw, SampleMap map);

// Throws InputError naming `file` when a raw frame's size, depth or channel count does not match the manifest.
void check_raw_frame(const cv::Mat& raw, const CaptureManifest& manifest, const std::string& file);

// Linear camera response in [0, 1] (black level removed, response curve undone) from a raw frame (CV_8U/CV_16U):
// check_raw_frame, linearize_samples, then the response curve.
cv::Mat linearize_frame(const cv::Mat& raw, const CaptureManifest& manifest, const std::string& file);

// What loading gives: linear CV_32F frames, or the camera's raw samples (checked, not converted).
enum class FrameForm { kLinear, kRaw };
// A raw frame in `form`: linearize_frame, or check_raw_frame and `raw` itself.
cv::Mat frame_in_form(const cv::Mat& raw, const CaptureManifest& manifest, const std::string& file, FrameForm form);

// Reads one frame of the manifest (any format imgcodecs reads) and returns it linearized (CV_32F, [0, 1]) or raw.
// Throws InputError naming the file when it is missing, unreadable, mis-sized or of the wrong bit depth.
cv::Mat load_frame(const std::filesystem::path& capture_dir, const CaptureManifest& manifest, std::size_t index,
                   FrameForm form = FrameForm::kLinear);

}  // namespace rfrecon::capture
