// Gray bit boundaries between neighbouring camera pixels and the local plane fits through them.
#include "host/transport/gray_subpixel.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include <opencv2/core/hal/hal.hpp>
#include <opencv2/core/hal/intrin.hpp>

namespace rfrecon::transport {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

const float* pixels(const cv::Mat& frame, cv::Size camera_size) {
  if (frame.type() != CV_32FC1 || frame.size() != camera_size || !frame.isContinuous()) {
    throw std::invalid_argument("gray subpixel: frames must be continuous CV_32FC1 of the camera size");
  }
  return frame.ptr<float>();
}

// The fits work four points at a time in OpenCV's 128-bit universal intrinsics (SSE2 on x86-64, NEON on ARM), in
// float: offsets of a few camera px and values of a few projector px from the pixel's own lose about 1e-7 px, far
// below the float correspondence's own step (6e-5 px at 1000 px). Each sum over a window is four partial sums, added
// in a fixed order at the end.
constexpr std::size_t kLanes = cv::v_float32x4::nlanes;

// The usable boundary points of one axis code, row by row: where a pixel's code and its right (or lower) neighbour's
// are one apart, the boundary between them (c + 0.5 between codes c and c + 1, projector px) at the crossing of the
// bit that differs. Only the points that exist are kept, in the order of their pair's first pixel, right before down,
// so a window reads no empty pair (the empty ones' branches cost more than the fits). A point's camera position is its
// pair's first pixel plus the crossing's fraction along x (right) or y (down), so a window's offsets are small
// integers plus a fraction, as precise in float at the image's far corner as at its origin.
struct BoundaryRows {
  int width = 0;
  // Row v's points whose pair's first pixel is u or right of it start at first_at[v (width + 1) + u]; u = width: the
  // row's end. A window finds each row's candidates with two reads, whatever their number.
  std::vector<std::uint32_t> first_at;
  std::vector<std::int32_t> u;    // the pair's first pixel (u, v)
  std::vector<float> x_fraction;  // camera px right of u: the crossing's fraction t (right) or 0 (down)
  std::vector<float> y_fraction;  // camera px below v: 0 (right) or t (down)
  std::vector<float> value;       // projector px

  BoundaryRows(const std::array<std::vector<float>, 2>& crossing, const std::vector<std::uint32_t>& code,
               const std::vector<std::uint8_t>& flags, cv::Size size)
      : width(size.width) {
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
    u.resize(u.size() + kLanes, 0);
    for (auto* field : {&x_fraction, &y_fraction, &value}) field->resize(field->size() + kLanes, 0.0f);
  }

  // Row v's points whose pair's first pixel is in [from, to].
  std::pair<std::size_t, std::size_t> points_of(int v, int from, int to) const {
    const std::size_t row = static_cast<std::size_t>(v) * (width + 1);
    return {first_at[row + from], first_at[row + to + 1]};
  }
};

// The candidate boundary points of one window, field by field in slots padded to whole lanes. A point outside the
// window or across an occlusion edge keeps its slot with `in` = 0, so no loop over the slots has a branch.
struct BoundaryPoints {
  std::vector<float> dx;         // camera px from the fitted pixel's centre, along x
  std::vector<float> dy;         // and along y
  std::vector<float> value;      // projector px, less the fitted pixel's decoded position
  std::vector<float> exponent;   // -distance^2 / (2 sigma^2)
  std::vector<float> weight;     // its exponential
  std::vector<float> in;         // 1 where the point is fitted, else 0
  std::vector<float> explained;  // 1 where it is also within max_residual_px of the first plane, else 0
  std::size_t slots = 0;         // candidates, rounded up to whole lanes

  void make_room(std::size_t candidates) {
    const std::size_t padded = (candidates + kLanes - 1) / kLanes * kLanes;
    if (dx.size() >= padded) return;
    for (auto* field : {&dx, &dy, &value, &exponent, &weight, &in, &explained}) field->resize(padded);
  }
};

// value = a + b dx + c dy.
struct Plane {
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;
};

// Weighted sums of a window's points for the plane through them, each in kLanes partial sums. The values are
// relative to the pixel's decoded position (a few px), so the moments about the means lose nothing to cancellation.
struct Moments {
  int count = 0;
  double w = 0, x = 0, y = 0, v = 0, xx = 0, xy = 0, yy = 0, xv = 0, yv = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();

  // The points whose `mask` is 1 (the window's `in`, or a mask of fewer).
  Moments(const BoundaryPoints& points, const float* mask) {
    const cv::v_float32x4 zero = cv::v_setzero_f32(), inf = cv::v_setall_f32(std::numeric_limits<float>::infinity());
    cv::v_float32x4 n = zero, sw = zero, sx = zero, sy = zero, sv = zero, sxx = zero, sxy = zero, syy = zero,
                    sxv = zero, syv = zero, slo = inf, shi = zero - inf;
    for (std::size_t i = 0; i < points.slots; i += kLanes) {
      const cv::v_float32x4 in = cv::v_load(mask + i), weight = cv::v_load(points.weight.data() + i) * in;
      const cv::v_float32x4 dx = cv::v_load(points.dx.data() + i), dy = cv::v_load(points.dy.data() + i);
      const cv::v_float32x4 value = cv::v_load(points.value.data() + i);
      const cv::v_float32x4 wx = weight * dx, wy = weight * dy;
      const cv::v_float32x4 fitted = in > zero;
      n += in;
      sw += weight;
      sx += wx;
      sy += wy;
      sv += weight * value;
      sxx += wx * dx;
      sxy += wx * dy;
      syy += wy * dy;
      sxv += wx * value;
      syv += wy * value;
      slo = cv::v_min(slo, cv::v_select(fitted, value, inf));
      shi = cv::v_max(shi, cv::v_select(fitted, value, zero - inf));
    }
    const auto total = [](const cv::v_float32x4& lanes) {
      std::array<float, kLanes> stored{};
      cv::v_store(stored.data(), lanes);
      double sum = 0.0;
      for (const float lane : stored) sum += lane;
      return sum;
    };
    count = static_cast<int>(total(n));
    w = total(sw);
    x = total(sx);
    y = total(sy);
    v = total(sv);
    xx = total(sxx);
    xy = total(sxy);
    yy = total(syy);
    xv = total(sxv);
    yv = total(syv);
    lo = cv::v_reduce_min(slo);
    hi = cv::v_reduce_max(shi);
  }

  // The weighted least-squares plane, when there are enough points, with two values at least, spread in both
  // directions (the weighted covariance of their positions).
  std::optional<Plane> plane(const GraySubpixelOptions& options) const {
    if (count < options.min_points || !(hi > lo)) return std::nullopt;
    const double mx = x / w, my = y / w, mv = v / w;
    const double cxx = xx / w - mx * mx, cxy = xy / w - mx * my, cyy = yy / w - my * my;
    const double cxv = xv / w - mx * mv, cyv = yv / w - my * mv;
    const double min_eigen = 0.5 * (cxx + cyy) - std::sqrt(0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy);
    if (min_eigen < options.min_spread_px2) return std::nullopt;
    const double det = cxx * cyy - cxy * cxy;
    Plane fitted;
    fitted.b = (cyy * cxv - cxy * cyv) / det;
    fitted.c = (cxx * cyv - cxy * cxv) / det;
    fitted.a = mv - fitted.b * mx - fitted.c * my;
    return fitted;
  }
};

// The boundary points of one axis code around a camera pixel.
struct Window {
  const BoundaryRows& rows;
  cv::Size size;
  const GraySubpixelOptions& options;

  // Points within radius_px (in x and y) of pixel (x, y) whose value lies within 1 + max_slope * distance of the
  // pixel's decoded position `own` (the others belong to another surface, across an occlusion edge), their values less
  // `own`, weighted by distance. Each row's candidates are tested a lane's width at a time, the weights all at once
  // after them; the slope test compares squares, so no point takes a square root.
  void gather(int x, int y, float own, BoundaryPoints& points) const {
    const int r = options.radius_px;
    // Pairs start at most one pixel left of or above the window, where their crossing may lie inside it.
    const int top = std::max(y - r - 1, 0);
    const int bottom = std::min(y + r, size.height - 1);
    const int left = std::max(x - r - 1, 0);
    const int right = std::min(x + r, size.width - 1);
    std::size_t candidates = 0;
    for (int v = top; v <= bottom; ++v) {
      const auto [first, last] = rows.points_of(v, left, right);
      candidates += last - first;
    }
    points.make_room(candidates + kLanes);
    const cv::v_float32x4 zero = cv::v_setzero_f32(), one = cv::v_setall_f32(1.0f);
    const cv::v_float32x4 radius = cv::v_setall_f32(static_cast<float>(r));
    const cv::v_float32x4 exponent_per_px2 =
        cv::v_setall_f32(static_cast<float>(-0.5 / (options.weight_sigma_px * options.weight_sigma_px)));
    const cv::v_float32x4 slope2 = cv::v_setall_f32(static_cast<float>(options.max_slope * options.max_slope));
    const cv::v_float32x4 own_lanes = cv::v_setall_f32(own);
    const cv::v_int32x4 x_lanes = cv::v_setall_s32(x);
    std::size_t n = 0;
    for (int v = top; v <= bottom; ++v) {
      const auto [first, last] = rows.points_of(v, left, right);
      const cv::v_float32x4 row_dy = cv::v_setall_f32(static_cast<float>(v - y));
      // Whole lanes: the slots past this row's are overwritten by the next row's or the padding.
      for (std::size_t k = first, slot = n; k < last; k += kLanes, slot += kLanes) {
        const cv::v_float32x4 dx =
            cv::v_cvt_f32(cv::v_load(rows.u.data() + k) - x_lanes) + cv::v_load(rows.x_fraction.data() + k);
        const cv::v_float32x4 dy = row_dy + cv::v_load(rows.y_fraction.data() + k);
        const cv::v_float32x4 offset = cv::v_load(rows.value.data() + k) - own_lanes;
        const cv::v_float32x4 d2 = dx * dx + dy * dy;
        const cv::v_float32x4 excess = cv::v_abs(offset) - one;  // over the 1 px every point is allowed
        const cv::v_float32x4 inside = (cv::v_abs(dx) <= radius) & (cv::v_abs(dy) <= radius);
        const cv::v_float32x4 same_surface = (excess <= zero) | (excess * excess <= slope2 * d2);
        cv::v_store(points.dx.data() + slot, dx);
        cv::v_store(points.dy.data() + slot, dy);
        cv::v_store(points.value.data() + slot, offset);
        cv::v_store(points.exponent.data() + slot, d2 * exponent_per_px2);
        cv::v_store(points.in.data() + slot, cv::v_select(inside & same_surface, one, zero));
      }
      n += last - first;
    }
    points.slots = (n + kLanes - 1) / kLanes * kLanes;
    for (std::size_t k = n; k < points.slots; ++k) {  // padding: fitted by no plane
      points.dx[k] = points.dy[k] = points.value[k] = points.exponent[k] = points.in[k] = 0.0f;
    }
    cv::hal::exp32f(points.exponent.data(), points.weight.data(), static_cast<int>(points.slots));
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
  const int width = camera_size_.width;
  for (int axis = 0; axis < 2; ++axis) {
    const auto& code = axis == 0 ? transport.pixel_x : transport.pixel_y;
    const BoundaryRows boundaries(crossing_[axis], code, transport.flags, camera_size_);
    const Window window{boundaries, camera_size_, options_};
    // Rows in parallel: each pixel's fit reads the boundaries and writes only its own correspondence.
    cv::parallel_for_(cv::Range(0, camera_size_.height), [&](const cv::Range& rows) {
      BoundaryPoints points;
      for (int y = rows.start; y < rows.end; ++y) {
        for (int x = 0; x < width; ++x) {
          const std::size_t c = static_cast<std::size_t>(y) * width + x;
          float& out = transport.correspondence[2 * c + axis];
          if ((transport.flags[c] & kFlagValid) == 0 || std::isnan(out)) continue;
          const float own = out;  // the decision's code, or a position between two adjacent codes
          window.gather(x, y, own, points);
          const Moments all(points, points.in.data());
          const std::optional<Plane> first = all.plane(options_);
          if (!first) continue;
          // The points the first plane explains, among those it was fitted to.
          const cv::v_float32x4 a = cv::v_setall_f32(static_cast<float>(first->a));
          const cv::v_float32x4 b = cv::v_setall_f32(static_cast<float>(first->b));
          const cv::v_float32x4 c_y = cv::v_setall_f32(static_cast<float>(first->c));
          const cv::v_float32x4 max_residual = cv::v_setall_f32(static_cast<float>(options_.max_residual_px));
          cv::v_float32x4 explained_lanes = cv::v_setzero_f32();
          for (std::size_t i = 0; i < points.slots; i += kLanes) {
            const cv::v_float32x4 residual =
                cv::v_abs(a + b * cv::v_load(points.dx.data() + i) + c_y * cv::v_load(points.dy.data() + i) -
                          cv::v_load(points.value.data() + i));
            const cv::v_float32x4 explained =
                cv::v_select(residual <= max_residual, cv::v_load(points.in.data() + i), cv::v_setzero_f32());
            cv::v_store(points.explained.data() + i, explained);
            explained_lanes += explained;
          }
          const auto explained_count = static_cast<int>(cv::v_reduce_sum(explained_lanes));
          std::optional<Plane> plane = first;
          if (explained_count < all.count) {  // once more without the others
            plane = Moments(points, points.explained.data()).plane(options_);
          }
          if (plane && std::fabs(plane->a) <= options_.max_code_offset_px) out = static_cast<float>(own + plane->a);
        }
      }
    });
  }
}

}  // namespace rfrecon::transport
