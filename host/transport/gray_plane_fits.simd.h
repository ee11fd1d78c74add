// The body of gray_fits::fit_rows for one instruction set, in OpenCV's widest universal intrinsics of the including
// file's build; that file names the namespace (RFRECON_SIMD_NAMESPACE). Everything here is either in that namespace
// or a C function (std::sqrt and std::fabs of a double are C's), never an inline function of a library: its copy
// built for AVX2 could stand in for the baseline's at link time.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>

#include <opencv2/core/hal/hal.hpp>
#include <opencv2/core/hal/intrin.hpp>

#include "host/transport/gray_plane_fits.h"
#include "kernels/transport/flags.h"

namespace rfrecon::transport::gray_fits::RFRECON_SIMD_NAMESPACE {

namespace {

// The fits work a lane's width of points at a time, in float: offsets of a few camera px and values of a few
// projector px from the pixel's own lose about 1e-7 px, far below the float correspondence's own step (6e-5 px at
// 1000 px). Each sum over a window is one partial sum per lane, added in a fixed order at the end.
using Floats = cv::v_float32;
using Ints = cv::v_int32;
constexpr std::size_t kLanes = Floats::nlanes;
static_assert(kLanes <= kMaxLanes, "the arrays' padding covers a lane");
static_assert(kScratchFields == 7, "BoundaryPoints takes its seven fields from Band::scratch");
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// The candidate boundary points of one window, field by field in slots padded to whole lanes (Band::scratch). A
// point outside the window or across an occlusion edge keeps its slot with `in` = 0, so no loop over the slots has a
// branch.
struct BoundaryPoints {
  float* dx;              // camera px from the fitted pixel's centre, along x
  float* dy;              // and along y
  float* value;           // projector px, less the fitted pixel's decoded position
  float* exponent;        // -distance^2 / (2 sigma^2)
  float* weight;          // its exponential
  float* in;              // 1 where the point is fitted, else 0
  float* explained;       // 1 where it is also within max_residual_px of the first plane, else 0
  std::size_t slots = 0;  // candidates, rounded up to whole lanes

  explicit BoundaryPoints(const Band& band)
      : dx(band.scratch),
        dy(dx + band.field_slots),
        value(dy + band.field_slots),
        exponent(value + band.field_slots),
        weight(exponent + band.field_slots),
        in(weight + band.field_slots),
        explained(in + band.field_slots) {}
};

// value = a + b dx + c dy.
struct Plane {
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;
};

double total(const Floats& lanes) {
  float stored[kLanes];
  cv::v_store(stored, lanes);
  double sum = 0.0;
  for (const float lane : stored) sum += lane;
  return sum;
}

// Weighted sums of a window's points for the plane through them. The values are relative to the pixel's decoded
// position (a few px), so the moments about the means lose nothing to cancellation.
struct Moments {
  int count = 0;
  double w = 0, x = 0, y = 0, v = 0, xx = 0, xy = 0, yy = 0, xv = 0, yv = 0;
  double lo = kInfinity, hi = -kInfinity;

  // The points whose `mask` is 1 (the window's `in`, or a mask of fewer).
  Moments(const BoundaryPoints& points, const float* mask) {
    const Floats zero = cv::vx_setzero_f32(), inf = cv::vx_setall_f32(kInfinity), minus_inf = zero - inf;
    Floats n = zero, sw = zero, sx = zero, sy = zero, sv = zero, sxx = zero, sxy = zero, syy = zero, sxv = zero,
           syv = zero, slo = inf, shi = minus_inf;
    for (std::size_t i = 0; i < points.slots; i += kLanes) {
      const Floats in = cv::vx_load(mask + i), weight = cv::vx_load(points.weight + i) * in;
      const Floats dx = cv::vx_load(points.dx + i), dy = cv::vx_load(points.dy + i);
      const Floats value = cv::vx_load(points.value + i);
      const Floats wx = weight * dx, wy = weight * dy;
      const Floats fitted = in > zero;
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
      shi = cv::v_max(shi, cv::v_select(fitted, value, minus_inf));
    }
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
  std::optional<Plane> plane(const FitSettings& settings) const {
    if (count < settings.min_points || !(hi > lo)) return std::nullopt;
    const double mx = x / w, my = y / w, mv = v / w;
    const double cxx = xx / w - mx * mx, cxy = xy / w - mx * my, cyy = yy / w - my * my;
    const double cxv = xv / w - mx * mv, cyv = yv / w - my * mv;
    const double min_eigen = 0.5 * (cxx + cyy) - std::sqrt(0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy);
    if (min_eigen < settings.min_spread_px2) return std::nullopt;
    const double det = cxx * cyy - cxy * cxy;
    Plane fitted;
    fitted.b = (cyy * cxv - cxy * cyv) / det;
    fitted.c = (cxx * cyv - cxy * cxv) / det;
    fitted.a = mv - fitted.b * mx - fitted.c * my;
    return fitted;
  }
};

// Row v's points whose pair's first pixel is in [from, to].
struct Span {
  std::size_t first;
  std::size_t last;
};
Span points_of(const BoundaryRowsView& rows, int v, int from, int to) {
  const std::size_t row = static_cast<std::size_t>(v) * (rows.width + 1);
  return {rows.first_at[row + from], rows.first_at[row + to + 1]};
}

// Points within radius_px (in x and y) of pixel (x, y) whose value lies within 1 + max_slope * distance of the pixel's
// decoded position `own` (the others belong to another surface, across an occlusion edge), their values less `own`,
// weighted by distance. Each row's candidates are tested a lane's width at a time, the weights all at once after
// them; the slope test compares squares, so no point takes a square root.
void gather(const BoundaryRowsView& rows, const FitSettings& settings, int x, int y, float own,
            BoundaryPoints& points) {
  const int r = settings.radius_px;
  // Pairs start at most one pixel left of or above the window, where their crossing may lie inside it.
  const int top = y - r - 1 > 0 ? y - r - 1 : 0;
  const int bottom = y + r < rows.height - 1 ? y + r : rows.height - 1;
  const int left = x - r - 1 > 0 ? x - r - 1 : 0;
  const int right = x + r < rows.width - 1 ? x + r : rows.width - 1;
  const Floats zero = cv::vx_setzero_f32(), one = cv::vx_setall_f32(1.0f);
  const Floats radius = cv::vx_setall_f32(static_cast<float>(r));
  const Floats exponent_per_px2 = cv::vx_setall_f32(settings.exponent_per_px2);
  const Floats slope2 = cv::vx_setall_f32(settings.max_slope2);
  const Floats own_lanes = cv::vx_setall_f32(own);
  const Ints x_lanes = cv::vx_setall_s32(x);
  std::size_t n = 0;
  for (int v = top; v <= bottom; ++v) {
    const Span span = points_of(rows, v, left, right);
    const Floats row_dy = cv::vx_setall_f32(static_cast<float>(v - y));
    // Whole lanes: the slots past this row's are overwritten by the next row's or the padding.
    for (std::size_t k = span.first, slot = n; k < span.last; k += kLanes, slot += kLanes) {
      const Floats dx = cv::v_cvt_f32(cv::vx_load(rows.u + k) - x_lanes) + cv::vx_load(rows.x_fraction + k);
      const Floats dy = row_dy + cv::vx_load(rows.y_fraction + k);
      const Floats offset = cv::vx_load(rows.value + k) - own_lanes;
      const Floats d2 = dx * dx + dy * dy;
      const Floats excess = cv::v_abs(offset) - one;  // over the 1 px every point is allowed
      const Floats inside = (cv::v_abs(dx) <= radius) & (cv::v_abs(dy) <= radius);
      const Floats same_surface = (excess <= zero) | (excess * excess <= slope2 * d2);
      cv::v_store(points.dx + slot, dx);
      cv::v_store(points.dy + slot, dy);
      cv::v_store(points.value + slot, offset);
      cv::v_store(points.exponent + slot, d2 * exponent_per_px2);
      cv::v_store(points.in + slot, cv::v_select(inside & same_surface, one, zero));
    }
    n += span.last - span.first;
  }
  points.slots = (n + kLanes - 1) / kLanes * kLanes;
  for (std::size_t k = n; k < points.slots; ++k) {  // padding: fitted by no plane
    points.dx[k] = points.dy[k] = points.value[k] = points.exponent[k] = points.in[k] = 0.0f;
  }
  cv::hal::exp32f(points.exponent, points.weight, static_cast<int>(points.slots));
}

// The number of points the plane explains among those it was fitted to, marked in `explained`.
int explain(const Plane& plane, const FitSettings& settings, BoundaryPoints& points) {
  const Floats a = cv::vx_setall_f32(static_cast<float>(plane.a));
  const Floats b = cv::vx_setall_f32(static_cast<float>(plane.b));
  const Floats c = cv::vx_setall_f32(static_cast<float>(plane.c));
  const Floats max_residual = cv::vx_setall_f32(settings.max_residual_px);
  Floats count = cv::vx_setzero_f32();
  for (std::size_t i = 0; i < points.slots; i += kLanes) {
    const Floats residual =
        cv::v_abs(a + b * cv::vx_load(points.dx + i) + c * cv::vx_load(points.dy + i) - cv::vx_load(points.value + i));
    const Floats explained = cv::v_select(residual <= max_residual, cv::vx_load(points.in + i), cv::vx_setzero_f32());
    cv::v_store(points.explained + i, explained);
    count += explained;
  }
  return static_cast<int>(cv::v_reduce_sum(count));
}

}  // namespace

void fit_rows(const BoundaryRowsView& rows, const FitSettings& settings, const Band& band) {
  BoundaryPoints points(band);
  for (int y = band.y_begin; y < band.y_end; ++y) {
    for (int x = 0; x < rows.width; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * rows.width + x;
      float& out = band.correspondence[2 * c + band.axis];
      // __builtin_isnan, not std::isnan: see the file's comment.
      if ((band.flags[c] & RF_FLAG_VALID) == 0 || __builtin_isnan(out)) continue;
      const float own = out;  // the decision's code, or a position between two adjacent codes
      gather(rows, settings, x, y, own, points);
      const Moments all(points, points.in);
      const std::optional<Plane> first = all.plane(settings);
      if (!first) continue;
      std::optional<Plane> plane = first;
      if (explain(*first, settings, points) < all.count) {  // once more without the points it does not explain
        plane = Moments(points, points.explained).plane(settings);
      }
      if (plane && std::fabs(plane->a) <= settings.max_code_offset_px) out = static_cast<float>(own + plane->a);
    }
  }
}

}  // namespace rfrecon::transport::gray_fits::RFRECON_SIMD_NAMESPACE
