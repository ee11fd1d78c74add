// The decoded-code and outcome maps: colours per pixel, with the previews' legend panel (host/outputs/legend.h).
#include "host/pipeline/transport_maps.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <spdlog/fmt/fmt.h>

#include "host/core/image_file.h"
#include "host/outputs/legend.h"

namespace rfrecon::pipeline {

namespace {

using transport::PixelOutcome;

// BGR of each outcome, in PixelOutcome's order: light grey, dark blue, magenta, red, yellow.
constexpr unsigned char kOutcomeBgr[transport::kPixelOutcomes][3] = {
    {200, 200, 200}, {90, 30, 0}, {200, 0, 200}, {0, 0, 230}, {0, 220, 240}};

cv::Vec3b outcome_colour(std::size_t outcome) {
  return {kOutcomeBgr[outcome][0], kOutcomeBgr[outcome][1], kOutcomeBgr[outcome][2]};
}

// The decoded map's key: red rising to the right, green downwards, as projector columns and rows colour the map.
cv::Mat projector_key() {
  cv::Mat key(256, 256, CV_8UC3);
  for (int y = 0; y < key.rows; ++y) {
    for (int x = 0; x < key.cols; ++x) key.at<cv::Vec3b>(y, x) = {0, static_cast<uchar>(y), static_cast<uchar>(x)};
  }
  return key;
}

// Bands of equal height, one per outcome, and a tick at the middle of each.
constexpr int kBandRows = 51;

std::string share(std::size_t part, std::size_t whole) {
  return fmt::format("{:.1f}%", whole == 0 ? 0.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole));
}

}  // namespace

cv::Mat draw_decoded_map(const transport::CompressedTransport& transport) {
  const cv::Size camera = transport.setup.camera_size, projector = transport.setup.projector_size;
  cv::Mat map(camera, CV_8UC3, cv::Scalar::all(0));
  const float red_per_px = 255.0f / static_cast<float>(std::max(projector.width - 1, 1));
  const float green_per_px = 255.0f / static_cast<float>(std::max(projector.height - 1, 1));
  for (int y = 0; y < camera.height; ++y) {
    auto* row = map.ptr<cv::Vec3b>(y);
    for (int x = 0; x < camera.width; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * static_cast<std::size_t>(camera.width) + x;
      const float u = transport.correspondence[2 * c], v = transport.correspondence[2 * c + 1];
      if (std::isnan(u) || std::isnan(v)) continue;
      row[x] = {0, cv::saturate_cast<uchar>(v * green_per_px), cv::saturate_cast<uchar>(u * red_per_px)};
    }
  }
  outputs::Legend legend{"projector pixel", projector_key(), {}, {}};
  legend.notes = {fmt::format("right: column 0 to {}", projector.width - 1),
                  fmt::format("down: row 0 to {}", projector.height - 1), "black: no position"};
  return outputs::with_legend(map, legend);
}

cv::Mat draw_outcome_map(const transport::CompressedTransport& transport, const transport::PixelOutcomeCounts& counts) {
  const cv::Size camera = transport.setup.camera_size;
  cv::Mat map(camera, CV_8UC3);
  for (int y = 0; y < camera.height; ++y) {
    auto* row = map.ptr<cv::Vec3b>(y);
    for (int x = 0; x < camera.width; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * static_cast<std::size_t>(camera.width) + x;
      row[x] = outcome_colour(static_cast<std::size_t>(transport::pixel_outcome(transport, c)));
    }
  }
  outputs::Legend legend{"camera pixels",
                         cv::Mat(kBandRows * static_cast<int>(transport::kPixelOutcomes), 1, CV_8UC3),
                         {},
                         {fmt::format("of {} px", transport.camera_pixels())}};
  for (std::size_t i = 0; i < transport::kPixelOutcomes; ++i) {
    const int top = kBandRows * static_cast<int>(i);
    legend.key.rowRange(top, top + kBandRows).setTo(cv::Scalar(outcome_colour(i)));
    legend.ticks.emplace_back((top + 0.5 * kBandRows) / (legend.key.rows - 1.0),
                              fmt::format("{} {}", transport::outcome_name(static_cast<PixelOutcome>(i)),
                                          share(counts[i], transport.camera_pixels())));
  }
  return outputs::with_legend(map, legend);
}

void write_transport_maps(const transport::CompressedTransport& transport, const transport::PixelOutcomeCounts& counts,
                          const std::filesystem::path& directory) {
  write_image(directory / "decoded.png", draw_decoded_map(transport));
  write_image(directory / "outcomes.png", draw_outcome_map(transport, counts));
}

}  // namespace rfrecon::pipeline
