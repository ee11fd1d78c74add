// The compressed light transport file (T.h5, HDF5): written atomically, validated on reading.
// Layout documented in docs/formats.md; readable with h5py and MATLAB's h5read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>

#include "host/transport/transport_types.h"

namespace rfrecon::transport {

// 2: every dataset carries a Fletcher32 checksum, the metadata HDF5's own (1.8 format). Version 1 files (no
// checksums) are still read.
inline constexpr int kTransportFileVersion = 2;

// What a T.h5 may state (docs/formats.md); the reader refuses more before allocating anything.
inline constexpr int kMaxTransportImageSide = 16384;  // camera and projector width and height, pixels
// Camera pixels x K: entries are addressed by int32 (the dual's CSR offsets).
inline constexpr std::int64_t kMaxTransportEntries = std::numeric_limits<std::int32_t>::max();

// zlib level of T.h5's datasets by default: measured in docs/performance.md. 0 stores them uncompressed.
inline constexpr int kDefaultDeflateLevel = 1;

// Writes `transport` to `file` through a temporary (AtomicFile): a failed write leaves no file. `deflate_level` (0 to
// 9) is zlib's level for every dataset, 0 for none; `white` is written when it is not empty. Throws OutputError naming
// the file when it cannot be written (its directory cannot be created, the disk is full).
void write_transport(const CompressedTransport& transport, const std::filesystem::path& file,
                     int deflate_level = kDefaultDeflateLevel);

// Reads a T.h5: either returns a transport that passes every check of docs/formats.md or throws InputError naming
// the file and the attribute or dataset at fault (and its first bad element): missing, truncated, failing a
// checksum, not a transport file, of the wrong type or shape, sizes beyond the maxima above, or values outside their
// ranges. The dataset `white` is optional: a file without it reads with `white` empty. Damage to a version 1 file's
// metadata (no checksums) can still crash HDF5 1.10 itself.
CompressedTransport read_transport(const std::filesystem::path& file);

}  // namespace rfrecon::transport
