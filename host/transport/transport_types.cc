// Construction of an empty compressed transport; the kernels' K build option.
#include "host/transport/transport_types.h"

#include <limits>

namespace rfrecon::transport {

CompressedTransport make_empty_transport(const TransportSetup& setup) {
  CompressedTransport transport;
  transport.setup = setup;
  const std::size_t n = transport.camera_pixels();
  const std::size_t slots = n * static_cast<std::size_t>(setup.entries_per_pixel);
  transport.indices.assign(slots, -1);
  transport.weights.assign(slots, 0.0f);
  transport.correspondence.assign(2 * n, std::numeric_limits<float>::quiet_NaN());
  transport.gray_x.assign(n, 0);
  transport.gray_y.assign(n, 0);
  transport.flags.assign(n, 0);
  transport.direct_energy.assign(n, 0.0f);
  return transport;
}

std::string transport_build_options(int entries_per_pixel, const std::string& extra) {
  if (entries_per_pixel == RF_K) return extra;
  const std::string k = "-DRF_K=" + std::to_string(entries_per_pixel);
  return extra.empty() ? k : k + " " + extra;
}

}  // namespace rfrecon::transport
