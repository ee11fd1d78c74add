// Injected device failures and hangs for testing failover and the tile timeout: "fail (or hang) device D at its
// N-th tile", from code or an environment variable.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "host/cl/error.h"

namespace rfrecon::sched {

// Read by FaultPolicy::from_environment(): comma-separated [hang:]DEVICE:TILE terms, DEVICE a position in the
// command's device list (0-based) or `*` for every device, TILE the 1-based count of tiles that device has started
// in the stage. "1:3" fails the second device at its third tile; "*:1" fails every device at once; "hang:1:1" makes
// the second device's first tile never return (what the tile timeout is for).
inline constexpr const char* kInjectFaultEnv = "RFRECON_INJECT_FAULT";

// Thrown in place of a device's tile by an injected fault; a cl::ClError (CL_DEVICE_NOT_AVAILABLE), so the scheduler
// handles it exactly like a real device error.
class InjectedFault : public cl::ClError {
 public:
  InjectedFault(std::size_t device, std::size_t tile);
};

class FaultPolicy {
 public:
  struct Term {
    bool hang = false;  // else fail
    bool every_device = false;
    std::size_t device = 0;
    std::size_t tile = 1;
  };

  FaultPolicy() = default;
  explicit FaultPolicy(std::vector<Term> terms) : terms_(std::move(terms)) {}

  // Parses the grammar above; throws InputError naming RFRECON_INJECT_FAULT on a malformed term.
  static FaultPolicy parse(std::string_view spec);
  // parse($RFRECON_INJECT_FAULT), empty when unset.
  static FaultPolicy from_environment();

  bool empty() const { return terms_.empty(); }
  // Throws InjectedFault when a fail term names this device and tile (1-based); never returns when a hang term does.
  void check(std::size_t device, std::size_t tile) const;

 private:
  std::vector<Term> terms_;
};

}  // namespace rfrecon::sched
