// T's rows from the dot grid's frames (host/capture/dot_grid.h), whichever family decoded each pixel's projector pixel
// first: the checks both implementations share and the plain C++ reference of kernels/transport/compress.cl.
#pragma once

#include "host/transport/transport_types.h"

namespace rfrecon::transport {

// A dot frame's offsets lie in [0, s), as host/capture/dot_grid.h makes them; std::invalid_argument otherwise.
void check_dot_offsets(const TransportSetup& setup, int offset_x, int offset_y);

// The kernels support the dot spacings of RF_DOT_SPACINGS (kernels/common/params.h, fixed in a board binary); any
// other spacing but 0 (no dot grid) is a ProcessingError naming it and the supported ones.
void check_kernel_dot_spacing(int dot_spacing);

// Dot frame (offset_x, offset_y), linear, into the rows of the compressible pixels: frame - black above the noise
// threshold goes to the dot nearest each pixel's decoded projector pixel (pixel_x, pixel_y) and adds to its direct
// energy; a row keeps its K strongest entries by decreasing weight, a new entry after equal ones.
void add_dot_frame_to_rows(CompressedTransport& t, int offset_x, int offset_y, const float* frame, const float* black);

// After the last frame: a compressible pixel whose row is empty is flagged kFlagNoSignal; with `centroids`, the others'
// correspondence becomes their row's weighted centroid.
void finish_rows(CompressedTransport& t, bool centroids);

// Whether a T of `setup` has its rows' dot centroids as correspondences: the graycode family's with the dot grid
// (other families keep their own, e.g. the phases).
bool correspondences_are_centroids(const TransportSetup& setup);

}  // namespace rfrecon::transport
