// Dropped-frame checks of the capture run: identical raw frames, and the Gray pair's linearity.
#include "host/acquire/frame_checks.h"

#include <cmath>
#include <cstring>
#include <limits>

#include "host/capture/capture_checks.h"

namespace rfrecon::acquire {

bool same_frame(const cv::Mat& a, const cv::Mat& b) {
  if (a.size() != b.size() || a.type() != b.type()) return false;
  for (int y = 0; y < a.rows; ++y) {
    if (std::memcmp(a.ptr(y), b.ptr(y), a.cols * a.elemSize()) != 0) return false;
  }
  return true;
}

namespace {
bool lit(float white, float black) { return white - black > capture::CaptureChecks::kLitLevel && white < 0.98f; }
}  // namespace

double lit_share(const cv::Mat& white, const cv::Mat& black) {
  CV_Assert(white.type() == CV_32F && black.type() == CV_32F && white.size() == black.size());
  std::size_t count = 0;
  for (int y = 0; y < white.rows; ++y) {
    for (int x = 0; x < white.cols; ++x) count += lit(white.at<float>(y, x), black.at<float>(y, x)) ? 1 : 0;
  }
  return static_cast<double>(count) / static_cast<double>(white.total());
}

double pair_mismatch_share(const cv::Mat& white, const cv::Mat& black, const cv::Mat& pattern, const cv::Mat& inverse) {
  CV_Assert(white.type() == CV_32F && black.type() == CV_32F && pattern.type() == CV_32F && inverse.type() == CV_32F);
  CV_Assert(white.size() == black.size() && white.size() == pattern.size() && white.size() == inverse.size());
  std::size_t lit_pixels = 0;
  std::size_t mismatched = 0;
  for (int y = 0; y < white.rows; ++y) {
    const float* w = white.ptr<float>(y);
    const float* b = black.ptr<float>(y);
    const float* p = pattern.ptr<float>(y);
    const float* q = inverse.ptr<float>(y);
    for (int x = 0; x < white.cols; ++x) {
      if (!lit(w[x], b[x])) continue;
      const float contrast = w[x] - b[x];
      ++lit_pixels;
      if (std::abs(p[x] + q[x] - w[x] - b[x]) > 0.25f * contrast) ++mismatched;
    }
  }
  if (lit_pixels * 1000 < white.total()) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(mismatched) / static_cast<double>(lit_pixels);
}

}  // namespace rfrecon::acquire
