// The tile timeout: per-device threads whose calls into a stage are timed; a thread whose call runs past the timeout
// is abandoned (detached, never joined, its device dropped by the runner), and from then on it can neither deliver
// results nor reach the runner's state.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "host/cl/device_context.h"

namespace rfrecon::sched {

// Read by tile_timeout_from_environment(): seconds (a decimal number), 0 disables the timeout.
inline constexpr const char* kTileTimeoutEnv = "RFRECON_TILE_TIMEOUT";
// Far above any healthy call (kernel builds and first tiles take seconds), short enough to end a hung run within a
// minute; docs/scheduler.md ("Hung devices") has the figures.
inline constexpr double kDefaultTileTimeoutS = 60.0;

// $RFRECON_TILE_TIMEOUT, kDefaultTileTimeoutS when unset; throws InputError naming the variable unless it is a
// number >= 0.
double tile_timeout_from_environment();

// Thrown in a thread whose call was abandoned, at its next contact with the scheduler (Worker::deliver, the end of
// the call), so that it unwinds without delivering. Not a device error: stages let it pass.
class TileAbandoned : public std::exception {
 public:
  const char* what() const noexcept override;
};

// Whether the device's runtime runs kernels only from the thread that made its context (oclgrind 21.10 crashes
// otherwise): alone, such a device works on the calling thread, where its calls cannot be timed.
bool needs_calling_thread(const cl::DeviceInfo& info);

class Watchdog {
 public:
  // timeout_s <= 0: calls are never abandoned.
  Watchdog(const std::vector<cl::DeviceContext>& devices, double timeout_s);

  // Runs body(position) for each of `positions` on a thread of its own and returns when each thread has returned
  // or been abandoned; abandoned threads are detached. When a call runs past the timeout, on_timeout(position,
  // elapsed_s) runs on the calling thread: the runner drops the device and gives its work to the others. A single
  // position runs on the calling thread, untimed, when the timeout is off or needs_calling_thread says so. An
  // abandoned thread may go on running body: body must keep alive (shared_ptr) what it touches, this watchdog
  // included.
  void run(const std::vector<std::size_t>& positions, const std::function<void(std::size_t)>& body,
           const std::function<void(std::size_t, double)>& on_timeout);

  // In body: one timed call into the stage (prepare, an upload, a tile, a block step). Throws TileAbandoned in
  // place of returning or of passing on the call's exception when the call was abandoned meanwhile; between calls
  // a thread is never abandoned, so the runner's bookkeeping there needs no check.
  void call(std::size_t position, const std::function<void()>& stage_call);

  // Runs `copy` (results from the calling thread's own memory into the stage's output) unless the position's call
  // was abandoned, else throws TileAbandoned. Abandoning waits for a copy in progress, so a copy either ends
  // before the tile goes to another device or never starts.
  void deliver(std::size_t position, const std::function<void()>& copy);

  double timeout_s() const { return timeout_s_; }

 private:
  struct Lane {
    bool calling_thread = false;  // needs_calling_thread(its device)
    bool busy = false;            // in a call since `since`
    bool finished = false;
    bool abandoned = false;
    std::chrono::steady_clock::time_point since;
  };

  void begin_call(std::size_t position);
  void end_call(std::size_t position);
  void finish(std::size_t position);

  double timeout_s_;
  std::chrono::steady_clock::duration timeout_;
  std::mutex mutex_;
  std::condition_variable finished_;
  std::vector<Lane> lanes_;
};

// The error text of a timed-out call, for the failure report and the warning.
std::string timeout_error(double elapsed_s, double timeout_s);

}  // namespace rfrecon::sched
