// The front door's capture hardware: the drivers opened by the command line's specs.
#include "host/drivers/open_devices.h"
#include "rfrecon/rfrecon.h"

namespace rfrecon {

std::unique_ptr<Camera> open_camera(const std::string& spec) { return drivers::open_camera(spec); }

std::unique_ptr<Projector> open_projector(const std::string& spec) { return drivers::open_projector(spec); }

}  // namespace rfrecon
