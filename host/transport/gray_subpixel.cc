// Gray bit boundaries between neighbouring camera pixels and the local plane fits through them.
#include "host/transport/gray_subpixel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace rfrecon::transport {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

const float* pixels(const cv::Mat& frame, cv::Size camera_size) {
  if (frame.type() != CV_32FC1 || frame.size() != camera_size || !frame.isContinuous()) {
    throw std::invalid_argument("gray subpixel: frames must be continuous CV_32FC1 of the camera size");
  }
  return frame.ptr<float>();
}

// Boundary points of one axis code: per camera pixel and direction, the projector coordinate of the boundary
// between it and its neighbour (c + 0.5 between codes c and c + 1); NaN where the pair is unusable.
using Boundaries = std::array<std::vector<float>, 2>;  // [0: right, 1: down], projector px

Boundaries usable_boundaries(const std::array<std::vector<float>, 2>& crossing, const std::vector<std::uint32_t>& code,
                             const std::vector<std::uint8_t>& flags, cv::Size size) {
  const auto n = static_cast<std::size_t>(size.area());
  Boundaries b;
  for (int direction = 0; direction < 2; ++direction) {
    auto& value = b[direction];
    value.assign(n, kNaN);
    const std::size_t step = direction == 0 ? 1 : static_cast<std::size_t>(size.width);
    for (int y = 0; y < size.height - direction; ++y) {
      for (int x = 0; x < size.width - (1 - direction); ++x) {
        const std::size_t c = static_cast<std::size_t>(y) * size.width + x;
        const std::size_t next = c + step;
        if (std::isnan(crossing[direction][c]) || (flags[c] & kFlagValid) == 0 || (flags[next] & kFlagValid) == 0) {
          continue;
        }
        const std::uint32_t lo = std::min(code[c], code[next]);
        const std::uint32_t hi = std::max(code[c], code[next]);
        // Codes one apart differ in exactly one Gray bit: the one whose crossing was kept.
        if (hi - lo == 1) value[c] = static_cast<float>(hi) - 0.5f;
      }
    }
  }
  return b;
}

struct BoundaryPoint {
  double dx;  // camera px from the fitted pixel's centre
  double dy;
  double value;   // projector px
  double weight;  // Gaussian of the distance
};

// value = a + b dx + c dy.
struct Plane {
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;
  double at(double dx, double dy) const { return a + b * dx + c * dy; }
};

// The weighted least-squares plane through `points`, when there are enough of them, with two values at least, spread
// in both directions (the weighted covariance of their positions).
std::optional<Plane> fit_plane(const std::vector<BoundaryPoint>& points, const GraySubpixelOptions& options) {
  if (static_cast<int>(points.size()) < options.min_points) return std::nullopt;
  double n = 0, mx = 0, my = 0, mv = 0, lo = points.front().value, hi = lo;
  for (const auto& p : points) {
    n += p.weight;
    mx += p.weight * p.dx;
    my += p.weight * p.dy;
    mv += p.weight * p.value;
    lo = std::min(lo, p.value);
    hi = std::max(hi, p.value);
  }
  if (!(hi > lo)) return std::nullopt;
  mx /= n;
  my /= n;
  mv /= n;
  double cxx = 0, cxy = 0, cyy = 0, cxv = 0, cyv = 0;  // centred moments
  for (const auto& p : points) {
    const double x = p.dx - mx, y = p.dy - my, v = p.value - mv;
    cxx += p.weight * x * x;
    cxy += p.weight * x * y;
    cyy += p.weight * y * y;
    cxv += p.weight * x * v;
    cyv += p.weight * y * v;
  }
  cxx /= n;
  cxy /= n;
  cyy /= n;
  const double min_eigen = 0.5 * (cxx + cyy) - std::sqrt(0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy);
  if (min_eigen < options.min_spread_px2) return std::nullopt;
  const double det = cxx * cyy - cxy * cxy;
  Plane plane;
  plane.b = (cyy * cxv - cxy * cyv) / (det * n);
  plane.c = (cxx * cyv - cxy * cxv) / (det * n);
  plane.a = mv - plane.b * mx - plane.c * my;
  return plane;
}

// The boundary points of one axis code around a camera pixel.
struct Window {
  Boundaries boundaries;
  const std::array<std::vector<float>, 2>& crossing;
  cv::Size size;
  const GraySubpixelOptions& options;

  // Points within radius_px (in x and y) of pixel (x, y) whose value lies within 1 + max_slope * distance of the
  // pixel's code `own` (the others belong to another surface, across an occlusion edge), weighted by distance.
  void gather(int x, int y, double own, std::vector<BoundaryPoint>& points) const {
    const int r = options.radius_px;
    const double two_sigma2 = 2.0 * options.weight_sigma_px * options.weight_sigma_px;
    points.clear();
    // Pairs start at most one pixel left of or above the window, where their crossing may lie inside it.
    for (int v = std::max(y - r - 1, 0); v <= std::min(y + r, size.height - 1); ++v) {
      for (int u = std::max(x - r - 1, 0); u <= std::min(x + r, size.width - 1); ++u) {
        const std::size_t b = static_cast<std::size_t>(v) * size.width + u;
        for (int direction = 0; direction < 2; ++direction) {
          const float value = boundaries[direction][b];
          if (std::isnan(value)) continue;
          const double t = crossing[direction][b];
          const double dx = u - x + (direction == 0 ? t : 0.0);
          const double dy = v - y + (direction == 1 ? t : 0.0);
          const double distance2 = dx * dx + dy * dy;
          if (std::fabs(dx) > r || std::fabs(dy) > r) continue;
          if (std::fabs(value - own) > options.max_slope * std::sqrt(distance2) + 1.0) continue;
          points.push_back({dx, dy, value, std::exp(-distance2 / two_sigma2)});
        }
      }
    }
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
    const auto& code = axis == 0 ? transport.gray_x : transport.gray_y;
    const Window window{usable_boundaries(crossing_[axis], code, transport.flags, camera_size_), crossing_[axis],
                        camera_size_, options_};
    // Rows in parallel: each pixel's fit reads the boundaries and writes only its own correspondence.
    cv::parallel_for_(cv::Range(0, camera_size_.height), [&](const cv::Range& rows) {
      std::vector<BoundaryPoint> points;
      for (int y = rows.start; y < rows.end; ++y) {
        for (int x = 0; x < width; ++x) {
          const std::size_t c = static_cast<std::size_t>(y) * width + x;
          float& out = transport.correspondence[2 * c + axis];
          if ((transport.flags[c] & kFlagValid) == 0 || std::isnan(out)) continue;
          out = static_cast<float>(code[c]);  // exact, where the accumulators' centroid may be off by an ulp
          window.gather(x, y, code[c], points);
          std::optional<Plane> plane = fit_plane(points, options_);
          if (!plane) continue;
          // Once more without the points the first plane does not explain.
          points.erase(std::remove_if(points.begin(), points.end(),
                                      [&](const BoundaryPoint& p) {
                                        return std::fabs(plane->at(p.dx, p.dy) - p.value) > options_.max_residual_px;
                                      }),
                       points.end());
          plane = fit_plane(points, options_);
          if (plane && std::fabs(plane->a - code[c]) <= options_.max_code_offset_px) {
            out = static_cast<float>(plane->a);
          }
        }
      }
    });
  }
}

}  // namespace rfrecon::transport
