// The dot grid's rows on the host, and the checks of dot frames.
#include "host/transport/dot_rows.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/core/errors.h"

namespace rfrecon::transport {

void check_dot_offsets(const TransportSetup& setup, int offset_x, int offset_y) {
  const int s = setup.dot_spacing;
  if (s <= 0 || offset_x < 0 || offset_x >= s || offset_y < 0 || offset_y >= s) {
    throw std::invalid_argument("transport: dot offsets (" + std::to_string(offset_x) + ", " +
                                std::to_string(offset_y) + ") outside [0, " + std::to_string(s) + ")");
  }
}

void check_kernel_dot_spacing(int dot_spacing) {
  const std::vector<int> supported RF_DOT_SPACINGS;
  if (dot_spacing == 0 || std::find(supported.begin(), supported.end(), dot_spacing) != supported.end()) return;
  std::string list;
  for (const int s : supported) list += (list.empty() ? "" : ", ") + std::to_string(s);
  throw ProcessingError("transport: the capture's dot spacing " + std::to_string(dot_spacing) +
                        " is not one the kernels were built for (RF_DOT_SPACINGS = {" + list +
                        "}; configure with -DRFRECON_DOT_SPACINGS, docs/fpga.md)");
}

namespace {

// x = offset + s * floor((coordinate - offset + floor(s / 2)) / s): the lit dot nearest to `coordinate`.
int nearest_dot(int coordinate, int offset, int spacing) {
  const int shifted = coordinate - offset + spacing / 2;
  return offset + spacing * static_cast<int>(std::floor(static_cast<double>(shifted) / spacing));
}

// Keeps the row sorted by decreasing weight; a new entry goes after equal weights, the weakest falls out.
void insert(CompressedTransport& t, std::size_t c, int q, float v) {
  const std::size_t row = c * static_cast<std::size_t>(t.k());
  int slot = t.k();
  while (slot > 0 && t.weights[row + slot - 1] < v) --slot;
  if (slot == t.k()) return;
  for (int k = t.k() - 1; k > slot; --k) {
    t.weights[row + k] = t.weights[row + k - 1];
    t.indices[row + k] = t.indices[row + k - 1];
  }
  t.weights[row + slot] = v;
  t.indices[row + slot] = q;
}

}  // namespace

void add_dot_frame_to_rows(CompressedTransport& t, int offset_x, int offset_y, const float* frame, const float* black) {
  check_dot_offsets(t.setup, offset_x, offset_y);
  const int s = t.setup.dot_spacing;
  const cv::Size projector = t.setup.projector_size;
  for (std::size_t c = 0; c < t.camera_pixels(); ++c) {
    const float v = frame[c] - black[c];
    if (!compressible(t.flags[c]) || !(v > t.setup.thresholds.noise)) continue;
    const int qx = nearest_dot(static_cast<int>(t.pixel_x[c]), offset_x, s);
    const int qy = nearest_dot(static_cast<int>(t.pixel_y[c]), offset_y, s);
    if (qx < 0 || qx >= projector.width || qy < 0 || qy >= projector.height) continue;
    t.direct_energy[c] += v;
    insert(t, c, qy * projector.width + qx, v);
  }
}

void finish_rows(CompressedTransport& t, bool centroids) {
  const int k_max = t.k();
  const int width = t.setup.projector_size.width;
  for (std::size_t c = 0; c < t.camera_pixels(); ++c) {
    const std::size_t row = c * static_cast<std::size_t>(k_max);
    float sum = 0.0f;
    float sum_x = 0.0f;
    float sum_y = 0.0f;
    for (int k = 0; k < k_max; ++k) {
      const int q = t.indices[row + k];
      if (q < 0) continue;
      const int y = q / width;
      sum += t.weights[row + k];
      sum_x += t.weights[row + k] * static_cast<float>(q - y * width);
      sum_y += t.weights[row + k] * static_cast<float>(y);
    }
    if (sum > 0.0f) {
      if (!centroids) continue;
      t.correspondence[2 * c] = sum_x / sum;
      t.correspondence[2 * c + 1] = sum_y / sum;
    } else if (compressible(t.flags[c])) {
      t.flags[c] |= kFlagNoSignal;
    }
  }
}

bool correspondences_are_centroids(const TransportSetup& setup) {
  return setup.family == capture::kDefaultFamily && setup.dot_spacing > 0;
}

}  // namespace rfrecon::transport
