// Gray bit boundaries between neighbouring camera pixels, and the plane fits through them (gray_plane_fits.h).
#include "host/transport/gray_subpixel.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include <opencv2/core/hal/intrin.hpp>

#include "host/transport/gray_plane_fits.h"

namespace rfrecon::transport {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

const float* pixels(const cv::Mat& frame, cv::Size camera_size) {
  if (frame.type() != CV_32FC1 || frame.size() != camera_size || !frame.isContinuous()) {
    throw std::invalid_argument("gray subpixel: frames must be continuous CV_32FC1 of the camera size");
  }
  return frame.ptr<float>();
}

// The crossings are computed a lane's width at a time in OpenCV's 128-bit universal intrinsics (SSE2 on x86-64, NEON
// on ARM).
constexpr std::size_t kLanes = cv::v_float32x4::nlanes;

// The usable boundary points of one axis code, row by row (gray_fits::BoundaryRowsView): where a pixel's code and its
// right (or lower) neighbour's are one apart, the boundary between them (c + 0.5 between codes c and c + 1, projector
// px) at the crossing of the bit that differs. Only the points that exist are kept, in the order of their pair's first
// pixel, right before down, so a window reads no empty pair (the empty ones' branches cost more than the fits). A
// point's camera position is its pair's first pixel plus the crossing's fraction along x (right) or y (down), so a
// window's offsets are small integers plus a fraction, as precise in float at the image's far corner as at its origin.
struct BoundaryRows {
  cv::Size size;
  std::vector<std::uint32_t> first_at;
  std::vector<std::int32_t> u;
  std::vector<float> x_fraction;
  std::vector<float> y_fraction;
  std::vector<float> value;

  BoundaryRows(const std::array<std::vector<float>, 2>& crossing, const std::vector<std::uint32_t>& code,
               const std::vector<std::uint8_t>& flags, cv::Size camera_size)
      : size(camera_size) {
    first_at.reserve(static_cast<std::size_t>(size.height) * (size.width + 1));
    for (int v = 0; v < size.height; ++v) {
      for (int pixel = 0; pixel <= size.width; ++pixel) {
        first_at.push_back(static_cast<std::uint32_t>(u.size()));
        if (pixel == size.width) break;
        for (int direction = 0; direction < 2; ++direction) {
          if (direction == 0 ? pixel + 1 >= size.width : v + 1 >= size.height) continue;
          const std::size_t c = static_cast<std::size_t>(v) * size.width + pixel;
          const std::size_t next = c + (direction == 0 ? 1 : static_cast<std::size_t>(size.width));
          const float crossed = crossing[direction][c];
          if (std::isnan(crossed) || (flags[c] & kFlagValid) == 0 || (flags[next] & kFlagValid) == 0) continue;
          const std::uint32_t lo = std::min(code[c], code[next]);
          const std::uint32_t hi = std::max(code[c], code[next]);
          // Codes one apart differ in exactly one Gray bit: the one whose crossing was kept.
          if (hi - lo != 1) continue;
          u.push_back(pixel);
          x_fraction.push_back(direction == 0 ? crossed : 0.0f);
          y_fraction.push_back(direction == 0 ? 0.0f : crossed);
          value.push_back(static_cast<float>(hi) - 0.5f);
        }
      }
    }
    // Whole lanes read from any row's first point stay inside the arrays.
    u.resize(u.size() + gray_fits::kMaxLanes, 0);
    for (auto* field : {&x_fraction, &y_fraction, &value}) field->resize(field->size() + gray_fits::kMaxLanes, 0.0f);
  }

  gray_fits::BoundaryRowsView view() const {
    return {size.width, size.height, first_at.data(), u.data(), x_fraction.data(), y_fraction.data(), value.data()};
  }
};

}  // namespace

GraySubpixel::GraySubpixel(cv::Size camera_size, GraySubpixelOptions options)
    : camera_size_(camera_size), options_(options) {
  for (auto& axis : crossing_) {
    for (auto& direction : axis) direction.assign(static_cast<std::size_t>(camera_size.area()), kNaN);
  }
}

void GraySubpixel::add_gray_pair(GrayAxis axis, const cv::Mat& pattern, const cv::Mat& inverse) {
  const float* p = pixels(pattern, camera_size_);
  const float* inv = pixels(inverse, camera_size_);
  auto& crossing = crossing_[axis == GrayAxis::kColumns ? 0 : 1];
  const int width = camera_size_.width;
  // pattern - inverse relative to pattern + inverse: the pixels' reflectances cancel from the crossing position. The
  // decoders' bit is set where pattern > inverse; where it flips between pixel c and the next, the crossing lies at
  // the fraction d0 / (d0 - d1) of the way. Four pixels at a time, every fraction computed and kept only where the bit
  // flips: where it does is not predictable, so a branch would be mispredicted.
  const cv::v_float32x4 least = cv::v_setall_f32(1e-6f);
  const auto contrast = [&](std::size_t c) {
    const cv::v_float32x4 pv = cv::v_load(p + c), iv = cv::v_load(inv + c);
    return std::pair{pv > iv, (pv - iv) / cv::v_max(pv + iv, least)};
  };
  const auto contrast_of = [&](std::size_t c) { return (p[c] - inv[c]) / std::max(p[c] + inv[c], 1e-6f); };
  // Rows in parallel: each pixel's crossings are its own.
  cv::parallel_for_(cv::Range(0, camera_size_.height), [&](const cv::Range& rows) {
    for (int direction = 0; direction < 2; ++direction) {
      const std::size_t step = direction == 0 ? 1 : static_cast<std::size_t>(width);
      float* crossed = crossing[direction].data();
      for (int y = rows.start; y < std::min(rows.end, camera_size_.height - direction); ++y) {
        const std::size_t row = static_cast<std::size_t>(y) * width;
        const std::size_t end = row + width - (1 - direction);
        std::size_t c = row;
        for (; c + kLanes <= end; c += kLanes) {
          const auto [bit, d0] = contrast(c);
          const auto [next_bit, d1] = contrast(c + step);
          const cv::v_float32x4 flips = bit ^ next_bit;
          cv::v_store(crossed + c, cv::v_select(flips, d0 / (d0 - d1), cv::v_load(crossed + c)));
        }
        for (; c < end; ++c) {
          if ((p[c] > inv[c]) == (p[c + step] > inv[c + step])) continue;
          const float d0 = contrast_of(c);
          crossed[c] = d0 / (d0 - contrast_of(c + step));
        }
      }
    }
  });
}

void GraySubpixel::refine(CompressedTransport& transport) const {
  if (transport.setup.camera_size != camera_size_) {
    throw std::invalid_argument("gray subpixel: transport and frames differ in camera size");
  }
  const gray_fits::FitSettings settings = gray_fits::fit_settings(options_);
  const gray_fits::FitRows fit_rows = gray_fits::builds_for_this_cpu().front().fit_rows;
  const std::size_t field_slots = gray_fits::window_slots(options_.radius_px);
  for (int axis = 0; axis < 2; ++axis) {
    const auto& code = axis == 0 ? transport.pixel_x : transport.pixel_y;
    const BoundaryRows boundaries(crossing_[axis], code, transport.flags, camera_size_);
    const gray_fits::BoundaryRowsView rows = boundaries.view();
    // Rows in parallel: each pixel's fit reads the boundaries and writes only its own correspondence.
    cv::parallel_for_(cv::Range(0, camera_size_.height), [&](const cv::Range& band_rows) {
      std::vector<float> scratch(gray_fits::kScratchFields * field_slots);
      gray_fits::Band band;
      band.flags = transport.flags.data();
      band.correspondence = transport.correspondence.data();
      band.axis = axis;
      band.y_begin = band_rows.start;
      band.y_end = band_rows.end;
      band.scratch = scratch.data();
      band.field_slots = field_slots;
      fit_rows(rows, settings, band);
    });
  }
}

}  // namespace rfrecon::transport
