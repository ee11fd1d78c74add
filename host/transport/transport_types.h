// The compressed light transport T of one capture (fixed-K "ELL" rows, structs of arrays) and its parameters.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "host/capture/camera_noise.h"
#include "host/capture/manifest.h"
#include "host/cl/kernel_entry.h"
#include "host/cl/program_cache.h"
#include "kernels/common/params.h"
#include "kernels/transport/flags.h"

namespace rfrecon::transport {

// Per-camera-pixel flag bits (stored as uint8); values shared with the kernels (kernels/transport/flags.h).
enum PixelFlag : std::uint8_t {
  // Gray-code-only captures redecide valid and low contrast per pixel on the host (host/transport/gray_decision.h):
  // valid includes pixels between two adjacent codes, low contrast is an axis left undecided.
  kFlagValid = RF_FLAG_VALID,               // lit, every Gray pair contrasted, coordinate inside the projector
  kFlagShadow = RF_FLAG_SHADOW,             // white - black <= black threshold
  kFlagLowContrast = RF_FLAG_LOW_CONTRAST,  // some Gray pair had |pattern - inverse| <= white threshold
  kFlagOutOfRange = RF_FLAG_OUT_OF_RANGE,   // decoded coordinate outside the projector
  kFlagNoSignal = RF_FLAG_NO_SIGNAL,        // lit and in range, but no transport entry above the noise threshold
};

// Lit and in range: the pixels the dot-grid compression uses (low contrast included, see kernels/transport/flags.h).
inline bool compressible(std::uint8_t flags) { return RF_COMPRESSIBLE(flags); }

using cl::KernelEntry;

// Thresholds in linear camera units (1.0 = full scale, black level removed; host/capture/manifest.h).
// Defaults: black 0.04 ~ 10 DN of an 8-bit camera (OpenCV's GrayCodePattern uses 40 DN); white and noise:
// automatic, default_white_threshold() and default_noise_threshold() of the capture's bit depth. Gray-code-only
// captures decide each bit against the pixel's own noise and contrast as well (host/transport/gray_decision.h).
struct Thresholds {
  float black = 0.04f;  // a pixel is lit when white - black > black
  float white = 0.0f;   // a Gray bit is trusted when |pattern - inverse| > white; <= 0: automatic
  float noise = 0.0f;   // transport entries (black subtracted) at or below are dropped; <= 0: automatic
};

// 4.5 DN at the camera's bit depth: the floor under which no Gray bit is trusted, however quiet the camera; on whole
// digital numbers, pattern and inverse 5 DN apart are trusted as OpenCV's GrayCodePattern trusts them. Gray-code-only
// captures raise it per pixel to 3 sigma of the pixel's measured noise and 2 % of its contrast
// (host/transport/gray_decision.h).
inline float default_white_threshold(int bit_depth) { return 4.5f / static_cast<float>((1 << bit_depth) - 1); }

// 2.5 DN at the camera's bit depth (0.0098 at 8 bits, 0.0024 at 10 bits): about 3 sigma of 1 DN read noise in the
// difference of a dot frame and the black frame. A fixed threshold in linear units would be either too low for
// 8-bit cameras (keeping noise) or too high for deeper ones, dropping the faint tails of each pixel's spot, which
// biases the primal and dual images (T 1, T^T 1) low by a few per cent and the depth stage's slopes with them.
inline float default_noise_threshold(int bit_depth) { return 2.5f / static_cast<float>((1 << bit_depth) - 1); }

// `thresholds` with automatic white and noise thresholds (<= 0) replaced by their defaults at `bit_depth`.
inline Thresholds resolve_thresholds(Thresholds thresholds, int bit_depth) {
  if (thresholds.white <= 0.0f) thresholds.white = default_white_threshold(bit_depth);
  if (thresholds.noise <= 0.0f) thresholds.noise = default_noise_threshold(bit_depth);
  return thresholds;
}

// What the compression needs to know before the first frame.
struct TransportSetup {
  cv::Size camera_size;
  cv::Size projector_size;
  int dot_spacing = 0;                           // s of the s x s dot grid; 0 = Gray code only (one entry per row)
  std::string family = capture::kDefaultFamily;  // the capture's pattern family
  std::map<std::string, int> parameters{};       // the pattern family's parameters, defaults included
  int entries_per_pixel = RF_K;                  // K, by default the kernels' (kernels/common/params.h)
  Thresholds thresholds;
  // The Gray and dot frames the accumulators take: linear CV_32F, or the camera's raw CV_8U or CV_16U samples, made
  // linear with `samples` by the kernels (white and black are linear CV_32F either way).
  int frame_depth = CV_32F;
  capture::SampleMap samples;
};

// The documented ranges of the setup's options (docs/cli.md#option-ranges): K from 1, each threshold from 0 (linear,
// 1 = full scale; 0 for white and noise: automatic) to half of full scale, above which no pixel of any capture could
// pass.
inline constexpr int kMaxEntriesPerPixel = 64;
inline constexpr float kMaxThreshold = 0.5f;

// Throws UsageError naming the option (-k, --black-threshold, --white-threshold, --noise-threshold) and its range
// when K or a threshold lies outside it, as the command line refuses it.
void check_setup_ranges(const TransportSetup& setup);

// The build options of the transport kernels for K entries per pixel, then `extra`: "-DRF_K=16" for another K than
// the parameters header's, nothing for RF_K itself, so that every stage shares one program per kernel file then (and
// a board binary needs no option).
std::string transport_build_options(int entries_per_pixel, const std::string& extra = {});

// The programs of the transport accumulators running `entry` for `setup`, each with its build options (then
// `extra`): decode.cl and compress.cl, built for K and, for NDRange entries, the frames' sample type (-DRF_SAMPLE=uchar
// or ushort for raw frames). Single work-item entries take linear frames and no sample option, which a board
// binary could not take (it fixes only the parameters of kernels/common/params.h).
std::vector<cl::ProgramRequest> transport_programs(const TransportSetup& setup, KernelEntry entry,
                                                   const std::string& extra = {});

// The private arrays of one NDRange work-item of the transport kernels, in bytes: the compression's RF_LANES ELL rows
// of K entries and its batch's RF_FRAME_BATCH samples and thresholds (an int and a float per lane each), the largest
// of them. What bounds a CPU work-group (cl::private_work_group).
std::size_t transport_private_bytes(int entries_per_pixel);

// Compressed T: row c = camera pixel y * W + x, column q = projector pixel y * Wp + x. Entry k of row c is at
// c * K + k, strongest first; index -1 (weight 0) marks an empty slot. Weights are T's values: linear camera
// response to the projector pixel at full level, black frame subtracted.
struct CompressedTransport {
  TransportSetup setup;
  std::vector<std::int32_t> indices;   // N * K projector pixel indices
  std::vector<float> weights;          // N * K
  std::vector<float> correspondence;   // N * 2 sub-pixel projector (x, y), pixel centres at integers; NaN if none
  std::vector<std::uint32_t> pixel_x;  // N decoded (integer) projector column; meaningful where kFlagValid
  std::vector<std::uint32_t> pixel_y;  // N decoded projector row
  std::vector<std::uint8_t> flags;     // N PixelFlag bits
  std::vector<float> direct_energy;    // N sum of all entries above noise in the window (kept or not)
  std::vector<float> white;            // N linear white frame (1 = full scale, black level off); empty: unknown
  capture::CameraNoise camera_noise;   // the frames' noise, as the capture checks fitted it; unknown: not measured

  std::size_t camera_pixels() const { return static_cast<std::size_t>(setup.camera_size.area()); }
  std::size_t projector_pixels() const { return static_cast<std::size_t>(setup.projector_size.area()); }
  int k() const { return setup.entries_per_pixel; }
  // The graycode family's "gray+dots" or "gray" (Gray code only), or another family's name ("+dots" with the grid).
  std::string protocol() const {
    const std::string family = setup.family == capture::kDefaultFamily ? "gray" : setup.family;
    return setup.dot_spacing > 0 ? family + "+dots" : family;
  }
};

// An empty transport for `setup`: gray codes 0, flags 0, every slot empty, energy 0, correspondence NaN. `storage`:
// an earlier transport whose arrays' memory is reused (its contents are discarded), so that a scanner's repeated
// scans do not map, zero and fault in a new hundred megabytes each time; the arrays grow where it is too small.
CompressedTransport make_empty_transport(const TransportSetup& setup, CompressedTransport storage = {});

// The same without T's rows: the decoding's state, which add_empty_rows completes when the compression needs them,
// so that decoding does not pay for the rows' memory (N * K entries). Rows of `storage` of that size already are
// kept as they are (stale) for add_empty_rows to refill on every core, or for a kernel to overwrite (size_rows);
// others are dropped, their memory kept.
CompressedTransport make_empty_decoding(const TransportSetup& setup, CompressedTransport storage = {});
void add_empty_rows(CompressedTransport& transport);
// The rows at their size, their contents left as they are when they have it already (stale rows of `storage`, for a
// kernel that writes every row), otherwise made empty.
void size_rows(CompressedTransport& transport);

}  // namespace rfrecon::transport
