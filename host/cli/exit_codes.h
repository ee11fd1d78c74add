// The command line's exit codes, documented in docs/cli.md; scripts may rely on them.
#pragma once

namespace rfrecon::cli {

enum ExitCode : int {
  kExitOk = 0,
  kExitInternal = 1,    // an unexpected error (a bug): please report it
  kExitUsage = 2,       // bad command line: unknown flag, missing argument, invalid value
  kExitInput = 3,       // bad input file or value: missing, unreadable, malformed, mis-sized
  kExitNoDevice = 4,    // no OpenCL device matches the selection (--devices / RFRECON_DEVICES)
  kExitOpenCl = 5,      // an OpenCL call or kernel build failed on every device that was tried
  kExitProcessing = 6,  // valid input the method cannot process (no board found, too few poses, all masked)
  kExitSelfcheck = 7,   // `rfrecon selfcheck` found a device whose results differ from the C++ reference
  kExitOutput = 8,      // an output could not be written (permission, read-only file system, disk full)
  kExitCheck = 9,       // `rfrecon check` found a problem in the capture
  kExitHardware = 10,   // a camera or display is missing, refuses a setting, stops answering or drops frames
};

}  // namespace rfrecon::cli
