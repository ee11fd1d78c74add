// Names of the temporaries that outputs are written under, and their removal: on a signal, and by the next run when
// a process was killed before it could clean up.
#pragma once

#include <cstddef>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

namespace rfrecon {

// What make_temporary makes: an empty file ("tmp"), an empty directory ("staging"), or only a free name that an
// earlier output is moved to for the moment of a swap ("old").
enum class TemporaryKind { kFile, kDirectory, kAside };

// The longest name the file system of `directory` allows (pathconf _PC_NAME_MAX; 255 when it does not say).
std::size_t name_max(const std::filesystem::path& directory);

// The part of a temporary's name that stands for `target`: its name when that leaves room for the longest suffix
// within name_max, else the name's first bytes (whole UTF-8 characters), '~' and 16 hex digits of a hash of the
// whole name. Temporaries are named PREFIX.TAG-PID-N, so every one of them fits the file system, whatever the
// target's length.
std::string temporary_prefix(const std::filesystem::path& target);

// The longest suffix ".TAG-PID-N" a temporary's name can have.
inline constexpr std::size_t kMaxTemporarySuffix = 30;

// A fresh sibling of `target` named PREFIX.TAG-PID-N (temporary_prefix), made (`kind`) and registered for removal
// on a signal in one step under the registry's lock, so a signal's cleanup either removes it or runs before it exists
// (and then the process ends before it is made). A temporary of a registered temporary is named after the output
// the first one stands for (T.h5.tmp-PID-1 for T.h5.tmp-PID-0), so every temporary names its output alone. Stale
// temporaries of the output left by a dead process are removed first. Throws OutputError naming `target` when it
// cannot be made.
std::filesystem::path make_temporary(const std::filesystem::path& target, TemporaryKind kind);

// The temporary is renamed into place or removed: it is no longer removed on a signal.
void release_temporary(const std::filesystem::path& temporary);

// Makes the directories missing above `target` one by one, each registered like a temporary under the registry's
// lock: a signal's cleanup removes them (after the temporaries, and only while empty), so an interrupted command
// leaves no empty directory behind either. Returns the ones it made, shallowest first. Throws OutputError naming the
// directory that cannot be made (or that is not a directory).
std::vector<std::filesystem::path> make_parent_directories(const std::filesystem::path& target);

// The output is in place (`keep`: they stay) or was given up (each is removed while empty, deepest first); either
// way they are no longer removed on a signal.
void release_parent_directories(const std::vector<std::filesystem::path>& made, bool keep);

// Held while an output's final renames run: a signal's cleanup waits for it, so it never sees half of a commit
// (an earlier directory moved aside and the new one not yet in its place). Recursive: make_temporary and
// release_temporary may be called while it is held.
std::unique_lock<std::recursive_mutex> hold_temporaries();

// Removes the temporaries of `target` whose process no longer runs (what kill -9 left): every name
// PREFIX(.TAG-PID-N)+ beside it, the nested names of earlier versions included (T.h5.tmp-PID-0.tmp-PID-1), when
// none of the PIDs in it runs. An "old" directory whose target is missing is renamed back instead.
void remove_stale_temporaries(const std::filesystem::path& target);

// Renames `from` to `to` unless something has the name `to` (renameat2 RENAME_NOREPLACE; where the file system
// lacks it, link then unlink for a file, and for a directory an empty directory made at `to` and renamed over).
// Returns 0, or the errno: EEXIST (ENOTEMPTY) when `to` exists.
int rename_no_replace(const std::filesystem::path& from, const std::filesystem::path& to);

// Swaps the names `a` and `b` in one step (renameat2 RENAME_EXCHANGE): 0, or the errno (EINVAL where the file
// system lacks it).
int exchange_paths(const std::filesystem::path& a, const std::filesystem::path& b);

// Removes a file, a link (not what it points to) or a whole directory with system calls alone; true when it is gone.
bool remove_path(const std::filesystem::path& path);

// Removes every registered temporary. Called by the signal handler thread of install_signal_cleanup().
void remove_registered_temporaries();

// Blocks SIGINT, SIGTERM and SIGHUP in this thread (call before starting threads: they inherit it) and starts a
// thread that, on one of them, takes the registry's lock (waiting for a commit in progress), stops every other
// thread of the process (a real-time signal whose handler never returns, so nothing can create a file or directory
// any more), removes the registered temporaries with plain system calls and exits with 128 + the signal number.
void install_signal_cleanup();

}  // namespace rfrecon
