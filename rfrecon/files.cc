// The front door's files: T.h5, rig.yaml and the reconstruction directory, as the tool writes them.
#include "host/core/atomic_file.h"
#include "host/core/output_path.h"
#include "host/outputs/reconstruction_files.h"
#include "host/transport/transport_file.h"
#include "rfrecon/rfrecon.h"

namespace rfrecon {

Transport read_transport(const std::filesystem::path& file) { return transport::read_transport(file); }

void write_transport(const Transport& transport, const std::filesystem::path& file, bool force) {
  check_output_file({file, "write_transport", force}, {});
  AtomicFile output(file);
  transport::write_transport(transport, output.temp_path());
  output.commit();
}

void write_rig(const Rig& rig, const std::filesystem::path& file, bool force) {
  check_output_file({file, "write_rig", force}, {});
  calib::write_rig(rig, file);
}

void write_reconstruction(const ReconstructResult& result, const std::filesystem::path& dir, bool force) {
  outputs::write_reconstruction(result.maps, result.summary, dir, force);
}

}  // namespace rfrecon
