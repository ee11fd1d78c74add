// Why each camera pixel of a transport has a correspondence or none: one outcome per pixel and their counts, the
// figures `rfrecon transport` prints, writes to its summary and draws (host/pipeline/transport_maps.h).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "host/transport/transport_types.h"

namespace rfrecon::transport {

// In order of precedence: a pixel with a correspondence is decoded whatever its flags (a dot capture's low-contrast
// pixels get theirs from the dots); one without takes the first of its flags' reasons (undecided only on Gray-code-only
// captures: a dot capture's pixel without a position lacks the dots' signal).
enum class PixelOutcome : std::uint8_t { kDecoded, kShadow, kOutOfRange, kUndecided, kNoSignal };
inline constexpr std::size_t kPixelOutcomes = 5;

PixelOutcome pixel_outcome(const CompressedTransport& transport, std::size_t c);

// "decoded", "shadow", "out_of_range", "undecided", "no_signal".
const char* outcome_name(PixelOutcome outcome);

// Pixels of each outcome, indexed by PixelOutcome; they add up to the camera's pixels.
using PixelOutcomeCounts = std::array<std::size_t, kPixelOutcomes>;
PixelOutcomeCounts count_outcomes(const CompressedTransport& transport);

}  // namespace rfrecon::transport
