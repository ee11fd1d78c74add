// The compressed light transport file (T.h5, HDF5): written atomically, validated on reading.
// Layout documented in docs/formats.md; readable with h5py and MATLAB's h5read.
#pragma once

#include <filesystem>

#include "host/transport/transport_types.h"

namespace rfrecon::transport {

inline constexpr int kTransportFileVersion = 1;

// Writes `transport` to `file` through a temporary (AtomicFile): a failed write leaves no file. Throws InputError
// naming the file when it cannot be written (e.g. its directory does not exist).
void write_transport(const CompressedTransport& transport, const std::filesystem::path& file);

// Reads a T.h5; throws InputError naming the file (and the dataset or attribute) when it is missing, truncated,
// not a transport file, or has datasets whose shapes or values disagree with its attributes.
CompressedTransport read_transport(const std::filesystem::path& file);

}  // namespace rfrecon::transport
