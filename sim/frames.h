// Camera frames of the capture protocol computed from T: I_k = T L_k + ambient, then shot and read noise, the
// camera response curve and quantisation (docs/sim.md, "Noise model"); written with the capture manifest.
#pragma once

#include <cstdint>
#include <filesystem>

#include <opencv2/core.hpp>

#include "host/capture/manifest.h"
#include "host/core/progress.h"
#include "sim/render.h"

namespace rfrecon::sim {

// The linear camera image (CV_32F, full scale 1, before noise and ambient) under a projector image `pattern`
// (CV_8UC1 of the projector size, 255 = fully lit).
cv::Mat transport_image(const TransportMatrix& T, const cv::Mat& pattern, cv::Size camera_size);

// A raw camera reading (CV_8U for bit_depth 8, else CV_16U holding 0..2^bits-1) of `linear` plus ambient, with
// noise drawn from a generator seeded by (seed, frame_index): identical inputs give identical bytes.
cv::Mat camera_reading(const cv::Mat& linear, const CaptureSettings& settings, std::uint64_t seed,
                       std::size_t frame_index);

// The manifest describing frames rendered with `settings` for the given devices (file names included).
capture::CaptureManifest make_manifest(const CaptureSettings& settings, cv::Size camera_size, cv::Size projector_size);

// Renders and writes every frame of the manifest and manifest.json into `capture_dir` (which must exist),
// `threads` frames at a time. `progress` (optional) advances by one per frame.
void write_capture(const TransportMatrix& T, const CaptureSettings& settings, cv::Size camera_size,
                   cv::Size projector_size, std::uint64_t seed, int threads, const std::filesystem::path& capture_dir,
                   Progress* progress = nullptr);

}  // namespace rfrecon::sim
