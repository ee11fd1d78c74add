// Per-camera-pixel flag bits of the light transport stage, shared by the OpenCL kernels and the host
// (host/transport/transport_types.h). Stored as uint8 in T.h5 (docs/formats.md).
#ifndef RFRECON_KERNELS_TRANSPORT_FLAGS_H
#define RFRECON_KERNELS_TRANSPORT_FLAGS_H

#define RF_FLAG_VALID 1u         // decoded: lit, every Gray pair contrasted, coordinate inside the projector
#define RF_FLAG_SHADOW 2u        // white - black <= black_threshold (not lit by the projector)
#define RF_FLAG_LOW_CONTRAST 4u  // some Gray pair had |pattern - inverse| <= white_threshold
#define RF_FLAG_OUT_OF_RANGE 8u  // decoded coordinate outside the projector image
#define RF_FLAG_NO_SIGNAL 16u    // lit and in range, but no transport entry above the noise threshold

// Pixels the dot-grid compression uses: lit and in range. Low-contrast pixels are included: their one undecided
// Gray bit moves the coarse coordinate by at most one projector pixel, and the s x s window (s >= 3) around it
// still holds the spot. Gray-code-only captures use RF_FLAG_VALID pixels only, after the host redecides both flags
// from each pixel's noise (host/transport/gray_decision.h).
#define RF_COMPRESSIBLE(flags) (((flags) & (RF_FLAG_SHADOW | RF_FLAG_OUT_OF_RANGE)) == 0)

#endif  // RFRECON_KERNELS_TRANSPORT_FLAGS_H
