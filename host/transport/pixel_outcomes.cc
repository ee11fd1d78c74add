// Per-pixel outcomes of the transport stage from its flags and correspondences.
#include "host/transport/pixel_outcomes.h"

#include <cmath>

namespace rfrecon::transport {

PixelOutcome pixel_outcome(const CompressedTransport& transport, std::size_t c) {
  const std::uint8_t flags = transport.flags[c];
  if (!std::isnan(transport.correspondence[2 * c])) return PixelOutcome::kDecoded;
  if ((flags & kFlagShadow) != 0) return PixelOutcome::kShadow;
  if ((flags & kFlagOutOfRange) != 0) return PixelOutcome::kOutOfRange;
  // A dot capture's Gray bits may well be undecided: there the dots, not the code, failed to give a position.
  const bool gray_only = transport.setup.dot_spacing == 0;
  if (gray_only && (flags & kFlagLowContrast) != 0) return PixelOutcome::kUndecided;
  return PixelOutcome::kNoSignal;
}

const char* outcome_name(PixelOutcome outcome) {
  switch (outcome) {
    case PixelOutcome::kDecoded:
      return "decoded";
    case PixelOutcome::kShadow:
      return "shadow";
    case PixelOutcome::kOutOfRange:
      return "out_of_range";
    case PixelOutcome::kUndecided:
      return "undecided";
    case PixelOutcome::kNoSignal:
      break;
  }
  return "no_signal";
}

PixelOutcomeCounts count_outcomes(const CompressedTransport& transport) {
  PixelOutcomeCounts counts{};
  for (std::size_t c = 0; c < transport.camera_pixels(); ++c) {
    ++counts[static_cast<std::size_t>(pixel_outcome(transport, c))];
  }
  return counts;
}

}  // namespace rfrecon::transport
