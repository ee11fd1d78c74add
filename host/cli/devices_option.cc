// The `--devices` option shared by every command that runs kernels.
#include "host/cli/commands.h"

namespace rfrecon::cli {

CLI::Option* add_devices_option(CLI::App* command, std::string& selection) {
  return command->add_option("--devices", selection,
                             "OpenCL devices to use: all|cpu|gpu|fpga|INDEX|NAME, comma-separated "
                             "(default: $RFRECON_DEVICES, else all)");
}

}  // namespace rfrecon::cli
