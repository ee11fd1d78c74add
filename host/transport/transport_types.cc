// Construction of an empty compressed transport (on huge pages, host/core/huge_pages.h); the kernels' build options;
// the setup's ranges.
#include "host/transport/transport_types.h"

#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "host/core/errors.h"
#include "host/core/huge_pages.h"
#include "kernels/common/lanes.h"

namespace rfrecon::transport {

void check_setup_ranges(const TransportSetup& setup) {
  const int k = setup.entries_per_pixel;
  if (k < 1 || k > kMaxEntriesPerPixel) {
    throw UsageError("-k (entries per pixel) is " + std::to_string(k) + ": from 1 to " +
                     std::to_string(kMaxEntriesPerPixel) + " is taken");
  }
  const std::pair<const char*, float> thresholds[] = {{"--black-threshold", setup.thresholds.black},
                                                      {"--white-threshold", setup.thresholds.white},
                                                      {"--noise-threshold", setup.thresholds.noise}};
  for (const auto& [option, value] : thresholds) {
    if (!(value >= 0.0f && value <= kMaxThreshold)) {  // NaN too
      throw UsageError(std::string(option) + " is " + std::to_string(value) + ": from 0 to " +
                       std::to_string(kMaxThreshold) + " is taken");
    }
  }
}

CompressedTransport make_empty_decoding(const TransportSetup& setup, CompressedTransport storage) {
  CompressedTransport transport = std::move(storage);
  transport.setup = setup;
  const std::size_t n = transport.camera_pixels();
  assign_on_huge_pages(transport.correspondence, 2 * n, std::numeric_limits<float>::quiet_NaN());
  assign_on_huge_pages(transport.pixel_x, n, 0U);
  assign_on_huge_pages(transport.pixel_y, n, 0U);
  assign_on_huge_pages(transport.flags, n, std::uint8_t{0});
  assign_on_huge_pages(transport.direct_energy, n, 0.0f);
  transport.white.clear();
  // T's rows stay as the earlier transport left them when they have the size add_empty_rows gives them (it refills
  // them on every core); otherwise they go, their memory kept.
  const std::size_t slots = n * static_cast<std::size_t>(setup.entries_per_pixel);
  if (transport.indices.size() != slots || transport.weights.size() != slots) {
    transport.indices.clear();
    transport.weights.clear();
  }
  return transport;
}

void add_empty_rows(CompressedTransport& transport) {
  const std::size_t slots = transport.camera_pixels() * static_cast<std::size_t>(transport.k());
  assign_on_huge_pages(transport.indices, slots, -1);
  assign_on_huge_pages(transport.weights, slots, 0.0f);
}

void size_rows(CompressedTransport& transport) {
  const std::size_t slots = transport.camera_pixels() * static_cast<std::size_t>(transport.k());
  if (transport.indices.size() != slots || transport.weights.size() != slots) add_empty_rows(transport);
}

CompressedTransport make_empty_transport(const TransportSetup& setup, CompressedTransport storage) {
  CompressedTransport transport = make_empty_decoding(setup, std::move(storage));
  add_empty_rows(transport);
  return transport;
}

std::size_t transport_private_bytes(int entries_per_pixel) {
  constexpr std::size_t kLaneBytes = RF_LANES * (sizeof(std::int32_t) + sizeof(float));
  return (static_cast<std::size_t>(entries_per_pixel) + RF_FRAME_BATCH) * kLaneBytes;
}

std::string transport_build_options(int entries_per_pixel, const std::string& extra) {
  if (entries_per_pixel == RF_K) return extra;
  const std::string k = "-DRF_K=" + std::to_string(entries_per_pixel);
  return extra.empty() ? k : k + " " + extra;
}

std::vector<cl::ProgramRequest> transport_programs(const TransportSetup& setup, KernelEntry entry,
                                                   const std::string& extra) {
  std::string decode = extra;
  if (entry == KernelEntry::kNdRange && setup.frame_depth != CV_32F) {
    const std::string sample = setup.frame_depth == CV_8U ? "-DRF_SAMPLE=uchar" : "-DRF_SAMPLE=ushort";
    decode = extra.empty() ? sample : sample + " " + extra;
  }
  return {{"transport/decode.cl", decode},
          {"transport/compress.cl", transport_build_options(setup.entries_per_pixel, decode)}};
}

}  // namespace rfrecon::transport
