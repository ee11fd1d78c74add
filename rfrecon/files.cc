// The front door's files: T.h5 and the reconstruction directory, written atomically.
#include "host/core/atomic_file.h"
#include "host/outputs/reconstruction_files.h"
#include "host/transport/transport_file.h"
#include "rfrecon/rfrecon.h"

namespace rfrecon {

Transport read_transport(const std::filesystem::path& file) { return transport::read_transport(file); }

void write_transport(const Transport& transport, const std::filesystem::path& file) {
  AtomicFile output(file);
  transport::write_transport(transport, output.temp_path());
  output.commit();
}

void write_reconstruction(const ReconstructResult& result, const std::filesystem::path& dir, bool force) {
  outputs::write_reconstruction(result.maps, result.summary, dir, force);
}

}  // namespace rfrecon
