// Names of the temporaries that outputs are written under, and their removal: on a signal, and by the next run when
// a process was killed before it could clean up.
#pragma once

#include <filesystem>
#include <string_view>

namespace rfrecon {

// A fresh sibling of `target` named "NAME.TAG-PID-N" (TAG: tmp, staging, old), registered for removal on a signal
// until release_temporary(). Stale temporaries of `target` left by a dead process are removed first.
std::filesystem::path make_temporary(const std::filesystem::path& target, std::string_view tag);

// The temporary is renamed into place or removed: it is no longer removed on a signal.
void release_temporary(const std::filesystem::path& temporary);

// Removes "NAME.TAG-PID-N" siblings of `target` whose process no longer runs (what kill -9 left).
void remove_stale_temporaries(const std::filesystem::path& target);

// Removes every registered temporary. Called by the signal handler thread of install_signal_cleanup().
void remove_registered_temporaries();

// Blocks SIGINT, SIGTERM and SIGHUP in this thread (call before starting threads: they inherit it) and starts a
// thread that, on one of them, removes the registered temporaries and exits with 128 + the signal number.
void install_signal_cleanup();

}  // namespace rfrecon
