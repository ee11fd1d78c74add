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

namespace rfrecon::transport {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

const float* pixels(const cv::Mat& frame, cv::Size camera_size) {
  if (frame.type() != CV_32FC1 || frame.size() != camera_size || !frame.isContinuous()) {
    throw std::invalid_argument("gray subpixel: frames must be continuous CV_32FC1 of the camera size");
  }
  return frame.ptr<float>();
}

// The usable boundary points of one axis code, row by row: where a pixel's code and its right (or lower) neighbour's
// are one apart, the boundary between them (c + 0.5 between codes c and c + 1, projector px) at the crossing of the
// bit that differs. Only the points that exist are kept, in the order of their pair's first pixel, right before down,
// so a window reads no empty pair (the empty ones' branches cost more than the fits). Each point's camera position is
// kept whole (exact in double), so a window takes its offsets with one subtraction per axis.
struct BoundaryRows {
  std::vector<std::size_t> start;  // row v's points are [start[v], start[v + 1])
  std::vector<std::int32_t> key;   // 2 u + direction (0: right, 1: down) of the pair's first pixel (u, v)
  std::vector<double> x;           // camera px of the boundary: u + t (right) or u (down), t the crossing's fraction
  std::vector<double> y;           // v (right) or v + t (down)
  std::vector<float> value;        // projector px

  BoundaryRows(const std::array<std::vector<float>, 2>& crossing, const std::vector<std::uint32_t>& code,
               const std::vector<std::uint8_t>& flags, cv::Size size) {
    start.reserve(static_cast<std::size_t>(size.height) + 1);
    for (int v = 0; v < size.height; ++v) {
      start.push_back(key.size());
      for (int u = 0; u < size.width; ++u) {
        for (int direction = 0; direction < 2; ++direction) {
          if (direction == 0 ? u + 1 >= size.width : v + 1 >= size.height) continue;
          const std::size_t c = static_cast<std::size_t>(v) * size.width + u;
          const std::size_t next = c + (direction == 0 ? 1 : static_cast<std::size_t>(size.width));
          const float crossed = crossing[direction][c];
          if (std::isnan(crossed) || (flags[c] & kFlagValid) == 0 || (flags[next] & kFlagValid) == 0) continue;
          const std::uint32_t lo = std::min(code[c], code[next]);
          const std::uint32_t hi = std::max(code[c], code[next]);
          // Codes one apart differ in exactly one Gray bit: the one whose crossing was kept.
          if (hi - lo != 1) continue;
          key.push_back(2 * u + direction);
          x.push_back(direction == 0 ? u + static_cast<double>(crossed) : u);
          y.push_back(direction == 0 ? v : v + static_cast<double>(crossed));
          value.push_back(static_cast<float>(hi) - 0.5f);
        }
      }
    }
    start.push_back(key.size());
  }
};

// The boundary points of one window, field by field (a loop that builds whole structs through the stack stalled on
// store forwarding). The fields have a slot for each candidate: each is written to the next free slot, which only a
// point that passes the window's tests takes, so the loop has no branch to mispredict.
struct BoundaryPoints {
  std::vector<double> dx;  // camera px from the fitted pixel's centre
  std::vector<double> dy;
  std::vector<double> value;     // projector px, less the fitted pixel's code
  std::vector<double> exponent;  // -distance^2 / (2 sigma^2), as distance^2 * exponent_per_px2
  std::vector<double> weight;    // its exponential
  std::size_t count = 0;         // the points are the first `count` slots

  void make_room(std::size_t candidates) {
    if (dx.size() >= candidates) return;
    for (auto* field : {&dx, &dy, &value, &exponent, &weight}) field->resize(candidates);
  }
};

// value = a + b dx + c dy.
struct Plane {
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;
  double at(double dx, double dy) const { return a + b * dx + c * dy; }
};

// Weighted sums of a set of points, added one at a time, for the plane through them. The values are relative to the
// pixel's code (a few px), so the moments about the means lose nothing to cancellation.
struct Moments {
  int count = 0;
  double w = 0, x = 0, y = 0, v = 0, xx = 0, xy = 0, yy = 0, xv = 0, yv = 0;
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();

  // Adds point i, or nothing where `in` is false: a weight of 0 leaves every sum as it was, without a branch.
  void add(const BoundaryPoints& points, std::size_t i, bool in = true) {
    const double weight = in ? points.weight[i] : 0.0, dx = points.dx[i], dy = points.dy[i], value = points.value[i];
    count += in ? 1 : 0;
    const double wx = weight * dx, wy = weight * dy;
    w += weight;
    x += wx;
    y += wy;
    v += weight * value;
    xx += wx * dx;
    xy += wx * dy;
    yy += wy * dy;
    xv += wx * value;
    yv += wy * value;
    lo = std::min(lo, in ? value : std::numeric_limits<double>::infinity());
    hi = std::max(hi, in ? value : -std::numeric_limits<double>::infinity());
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

// Where one window row's candidates lie in its BoundaryRows row: [first, last). Both only move right as the window
// does along a row of pixels.
struct RowCursor {
  std::size_t first = 0;
  std::size_t last = 0;
};

// The boundary points of one axis code around a camera pixel.
struct Window {
  const BoundaryRows& rows;
  cv::Size size;
  const GraySubpixelOptions& options;

  // Points within radius_px (in x and y) of pixel (x, y) whose value lies within 1 + max_slope * distance of the
  // pixel's decoded position `own` (the others belong to another surface, across an occlusion edge), their values less
  // `own`, weighted by distance. `cursors[i]` are window row i's candidates: pixels of one row are gathered left to
  // right, so they are found by moving the cursors on. The slope test compares squares, so no point takes a square
  // root. The weights come in a loop of their own: a call to exp among the other arithmetic made the compiler keep
  // every other value in memory around it.
  void gather(int x, int y, double own, std::vector<RowCursor>& cursors, BoundaryPoints& points) const {
    const int r = options.radius_px;
    // Pairs start at most one pixel left of or above the window, where their crossing may lie inside it.
    const int top = std::max(y - r - 1, 0);
    const int bottom = std::min(y + r, size.height - 1);
    const std::int32_t lowest_key = 2 * std::max(x - r - 1, 0);
    const std::int32_t end_key = 2 * (std::min(x + r, size.width - 1) + 1);
    std::size_t candidates = 0;
    for (int v = top; v <= bottom; ++v) {
      RowCursor& cursor = cursors[static_cast<std::size_t>(v - top)];
      const std::size_t end = rows.start[static_cast<std::size_t>(v) + 1];
      cursor.first = std::max(cursor.first, rows.start[static_cast<std::size_t>(v)]);
      while (cursor.first < end && rows.key[cursor.first] < lowest_key) ++cursor.first;
      cursor.last = std::max(cursor.last, cursor.first);
      while (cursor.last < end && rows.key[cursor.last] < end_key) ++cursor.last;
      candidates += cursor.last - cursor.first;
    }
    points.make_room(candidates);
    // A product, not a quotient (2 % of the fit on two cores); equal to it for the default sigma of 1.
    const double exponent_per_px2 = -0.5 / (options.weight_sigma_px * options.weight_sigma_px);
    const double slope2 = options.max_slope * options.max_slope;
    std::size_t n = 0;
    for (int v = top; v <= bottom; ++v) {
      const RowCursor& cursor = cursors[static_cast<std::size_t>(v - top)];
      for (std::size_t k = cursor.first; k < cursor.last; ++k) {
        const double dx = rows.x[k] - x;
        const double dy = rows.y[k] - y;
        const double d2 = dx * dx + dy * dy;
        const double offset = rows.value[k] - own;
        const double excess = std::fabs(offset) - 1.0;  // over the 1 px every point is allowed
        // Bitwise: both sides are cheap, and a branch on them would be mispredicted.
        const bool inside = (std::fabs(dx) <= r) & (std::fabs(dy) <= r);
        const bool same_surface = (excess <= 0.0) | (excess * excess <= slope2 * d2);
        points.dx[n] = dx;
        points.dy[n] = dy;
        points.value[n] = offset;
        points.exponent[n] = d2 * exponent_per_px2;
        n += inside & same_surface ? 1 : 0;
      }
    }
    points.count = n;
    cv::hal::exp64f(points.exponent.data(), points.weight.data(), static_cast<int>(n));
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
  // pattern - inverse relative to pattern + inverse: the pixels' reflectances cancel from the crossing position.
  const auto contrast = [&](std::size_t c) { return (p[c] - inv[c]) / std::max(p[c] + inv[c], 1e-6f); };
  // Rows in parallel: each pixel's crossings are its own.
  cv::parallel_for_(cv::Range(0, camera_size_.height), [&](const cv::Range& rows) {
    for (int direction = 0; direction < 2; ++direction) {
      const std::size_t step = direction == 0 ? 1 : static_cast<std::size_t>(width);
      for (int y = rows.start; y < std::min(rows.end, camera_size_.height - direction); ++y) {
        for (int x = 0; x < width - (1 - direction); ++x) {
          const std::size_t c = static_cast<std::size_t>(y) * width + x;
          const std::size_t next = c + step;
          // The decoders' bit: set where pattern > inverse.
          if ((p[c] > inv[c]) == (p[next] > inv[next])) continue;
          const float d0 = contrast(c);
          const float d1 = contrast(next);
          crossing[direction][c] = d0 / (d0 - d1);
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
      std::vector<RowCursor> cursors;
      for (int y = rows.start; y < rows.end; ++y) {
        cursors.assign(2 * static_cast<std::size_t>(options_.radius_px) + 2, RowCursor{});
        for (int x = 0; x < width; ++x) {
          const std::size_t c = static_cast<std::size_t>(y) * width + x;
          float& out = transport.correspondence[2 * c + axis];
          if ((transport.flags[c] & kFlagValid) == 0 || std::isnan(out)) continue;
          const double own = out;  // the decision's code, or a position between two adjacent codes
          window.gather(x, y, own, cursors, points);
          Moments all;
          for (std::size_t i = 0; i < points.count; ++i) all.add(points, i);
          const std::optional<Plane> first = all.plane(options_);
          if (!first) continue;
          const auto explains = [&](std::size_t i) {
            return std::fabs(first->at(points.dx[i], points.dy[i]) - points.value[i]) <= options_.max_residual_px;
          };
          int explained_count = 0;
          for (std::size_t i = 0; i < points.count; ++i) explained_count += explains(i) ? 1 : 0;
          std::optional<Plane> plane = first;
          if (explained_count < all.count) {  // once more without the points the first plane does not explain
            Moments explained;
            for (std::size_t i = 0; i < points.count; ++i) explained.add(points, i, explains(i));
            plane = explained.plane(options_);
          }
          if (plane && std::fabs(plane->a) <= options_.max_code_offset_px) out = static_cast<float>(own + plane->a);
        }
      }
    });
  }
}

}  // namespace rfrecon::transport
