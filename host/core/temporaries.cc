// Registry of live temporaries, removal of stale ones by PID, and the signal thread that cleans up on SIGINT/SIGTERM.
#include "host/core/temporaries.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <map>
#include <string_view>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <pthread.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "host/core/errors.h"

namespace rfrecon {

namespace fs = std::filesystem;

namespace {
constexpr std::string_view kTags[] = {"tmp", "staging", "old"};  // by TemporaryKind
constexpr std::size_t kDefaultNameMax = 255;
constexpr std::size_t kHashedNameBytes = 1 + 16;  // '~' and 16 hex digits

std::string_view tag_of(TemporaryKind kind) { return kTags[static_cast<int>(kind)]; }

struct Entry {
  fs::path target;  // the output the temporary stands for
  bool aside = false;
  bool parent = false;  // a directory made above an output: removed only while empty, after the temporaries
};

std::recursive_mutex& registry_mutex() {
  static std::recursive_mutex mutex;
  return mutex;
}

// Live temporaries and the outputs they stand for.
std::map<fs::path, Entry>& registry() {
  static std::map<fs::path, Entry> paths;
  return paths;
}

std::uint64_t fnv1a(std::string_view text) {
  std::uint64_t hash = 1469598103934665603ULL;
  for (const unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ULL;
  }
  return hash;
}

fs::path directory_of(const fs::path& target) {
  return target.parent_path().empty() ? fs::path(".") : target.parent_path();
}

// ".TAG-PID-N" repeated once or more: the PIDs in it, and whether it is a single "old" suffix. Empty when `rest` is
// not such a list.
struct Suffixes {
  std::vector<pid_t> pids;
  bool aside = false;
};
Suffixes parse_suffixes(std::string_view rest) {
  Suffixes result;
  std::size_t count = 0;
  bool old = false;
  while (!rest.empty()) {
    if (rest.front() != '.') return {};
    rest.remove_prefix(1);
    bool matched = false;
    for (const auto tag : kTags) {
      if (rest.size() <= tag.size() + 1 || rest.substr(0, tag.size()) != tag || rest[tag.size()] != '-') continue;
      const char* begin = rest.data() + tag.size() + 1;
      const char* end = rest.data() + rest.size();
      pid_t pid = 0;
      const auto [pid_end, pid_error] = std::from_chars(begin, end, pid);
      if (pid_error != std::errc() || pid <= 0 || pid_end == end || *pid_end != '-') return {};
      unsigned long long counter = 0;
      const auto [counter_end, counter_error] = std::from_chars(pid_end + 1, end, counter);
      if (counter_error != std::errc() || counter_end == pid_end + 1) return {};
      result.pids.push_back(pid);
      old = tag == "old";
      ++count;
      rest.remove_prefix(static_cast<std::size_t>(counter_end - rest.data()));
      matched = true;
      break;
    }
    if (!matched) return {};
  }
  result.aside = count == 1 && old;
  return result;
}

bool process_is_gone(pid_t pid) { return pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH; }

// ---- Removal with system calls alone: no memory is allocated and no lock taken, so it may run while the other
// threads are stopped anywhere (inside malloc, holding stdio's lock).

// The entries of a directory from getdents64: d_reclen at byte 16, d_name from byte 19.
constexpr std::size_t kDirentReclen = 16;
constexpr std::size_t kDirentName = 19;

template <typename Visit>
void for_each_entry(int directory, Visit visit) {
  alignas(8) char buffer[4096];
  for (;;) {
    const long bytes = ::syscall(SYS_getdents64, directory, buffer, sizeof buffer);
    if (bytes <= 0) return;
    for (long offset = 0; offset < bytes;) {
      unsigned short length = 0;
      std::memcpy(&length, buffer + offset + kDirentReclen, sizeof length);
      const char* name = buffer + offset + kDirentName;
      offset += length;
      if (length == 0) return;
      if (std::strcmp(name, ".") != 0 && std::strcmp(name, "..") != 0) visit(name);
    }
  }
}

bool remove_at(int directory, const char* name);

// Empties the open directory `fd`. Reading it again from the start until a pass finds nothing it can remove: entries
// removed while it is read can hide others.
void remove_contents(int fd) {
  for (int pass = 0; pass < 16; ++pass) {
    bool seen = false;
    bool removed = false;
    ::lseek(fd, 0, SEEK_SET);
    for_each_entry(fd, [&](const char* name) {
      seen = true;
      removed = remove_at(fd, name) || removed;
    });
    if (!seen || !removed) return;
  }
}

// Removes `name` in `directory`: a file, a link (not what it points to) or a whole directory. True when it is gone.
bool remove_at(int directory, const char* name) {
  if (::unlinkat(directory, name, 0) == 0 || errno == ENOENT) return true;
  if (errno != EISDIR && errno != EPERM) return false;  // Linux says EISDIR for a directory, POSIX allows EPERM
  const int fd = ::openat(directory, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return errno == ENOENT;
  remove_contents(fd);
  ::close(fd);
  return ::unlinkat(directory, name, AT_REMOVEDIR) == 0 || errno == ENOENT;
}

bool remove_tree(const char* path) { return remove_at(AT_FDCWD, path); }

int rename2(const char* from, const char* to, unsigned flags) {
#ifdef SYS_renameat2
  if (::syscall(SYS_renameat2, AT_FDCWD, from, AT_FDCWD, to, flags) == 0) return 0;
  return errno;
#else
  (void)from, (void)to, (void)flags;
  return ENOSYS;
#endif
}
constexpr unsigned kNoReplace = 1;  // RENAME_NOREPLACE
constexpr unsigned kExchange = 2;   // RENAME_EXCHANGE

bool unsupported(int error) { return error == EINVAL || error == ENOSYS || error == EOPNOTSUPP; }

// Removes a temporary; an old version moved aside goes back to `target` when nothing replaced it.
void dispose(const char* temporary, const char* target, bool aside) {
  struct stat status {};
  if (aside && ::lstat(target, &status) != 0 && errno == ENOENT) {
    const int error = rename2(temporary, target, kNoReplace);
    if (error == 0 || (unsupported(error) && ::rename(temporary, target) == 0)) return;
  }
  remove_tree(temporary);
}

// ---- Stopping the other threads before the signal's cleanup.

std::atomic<int> g_freeze_signal{0};
constexpr int kMaxThreads = 4096;
std::atomic<int> g_frozen_count{0};
std::atomic<pid_t> g_frozen[kMaxThreads];

pid_t this_thread_id() { return static_cast<pid_t>(::syscall(SYS_gettid)); }

// The handler of the freeze signal: the thread records itself and never runs again (the process is about to end).
void freeze_this_thread(int /*signal*/) {
  const int slot = g_frozen_count.fetch_add(1);
  if (slot < kMaxThreads) g_frozen[slot].store(this_thread_id());
  for (;;) ::pause();
}

// A real-time signal nobody handles, now the freeze signal; 0 when there is none.
int install_freeze_signal() {
  for (int signal = SIGRTMAX; signal >= SIGRTMIN; --signal) {
    struct sigaction current {};
    if (::sigaction(signal, nullptr, &current) != 0) continue;
    if ((current.sa_flags & SA_SIGINFO) != 0 || current.sa_handler != SIG_DFL) continue;
    struct sigaction action {};
    action.sa_handler = &freeze_this_thread;
    sigfillset(&action.sa_mask);  // nothing else runs in a frozen thread
    if (::sigaction(signal, &action, nullptr) == 0) return signal;
  }
  return 0;
}

// Writes the decimal digits of `value` at `out`; returns the end.
char* format_number(char* out, long value) {
  char digits[24];
  int count = 0;
  do {
    digits[count++] = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value > 0 && count < 24);
  while (count > 0) *out++ = digits[--count];
  return out;
}

// Whether thread `tid` blocks `signal` (then it would never answer the freeze): its SigBlk in /proc.
bool thread_blocks(pid_t tid, int signal) {
  char path[64] = "/proc/self/task/";
  char* end = format_number(path + std::strlen(path), tid);
  std::memcpy(end, "/status", 8);
  const int fd = ::open(path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  char text[4096];
  const long bytes = ::read(fd, text, sizeof text - 1);
  ::close(fd);
  if (bytes <= 0) return false;
  text[bytes] = '\0';
  const char* line = std::strstr(text, "\nSigBlk:");
  if (line == nullptr) return false;
  const char* digits = line + 8;
  while (*digits == ' ' || *digits == '\t') ++digits;
  std::uint64_t mask = 0;
  for (;; ++digits) {
    const char c = static_cast<char>(*digits | 0x20);  // lower case
    if (c >= '0' && c <= '9') {
      mask = mask << 4 | static_cast<std::uint64_t>(c - '0');
    } else if (c >= 'a' && c <= 'f') {
      mask = mask << 4 | static_cast<std::uint64_t>(c - 'a' + 10);
    } else {
      break;
    }
  }
  return signal <= 64 && (mask >> (signal - 1) & 1) != 0;
}

double monotonic_seconds() {
  timespec now{};
  ::clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Stops every other thread of the process in the freeze signal's handler and waits (2 s at most) until each one is
// there, has ended or blocks the signal for good: after this, no thread of the process can create a file any more
// (a system call under way completes first). Threads started meanwhile are found by reading the thread list again.
void stop_other_threads() {
  const int signal = g_freeze_signal.load();
  if (signal == 0) return;
  static pid_t signalled[kMaxThreads];
  int count = 0;
  const pid_t process = ::getpid();
  const pid_t self = this_thread_id();
  const double deadline = monotonic_seconds() + 2.0;
  for (int round = 0; round < 16; ++round) {
    const int fd = ::open("/proc/self/task", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    bool added = false;
    for_each_entry(fd, [&](const char* name) {
      pid_t tid = 0;
      const auto [end, error] = std::from_chars(name, name + std::strlen(name), tid);
      if (error != std::errc() || *end != '\0' || tid == self || count == kMaxThreads) return;
      if (std::find(signalled, signalled + count, tid) != signalled + count) return;
      signalled[count++] = tid;
      added = true;
      ::syscall(SYS_tgkill, process, tid, signal);  // pending, if the thread blocks it for now
    });
    ::close(fd);
    if (!added) return;
    // A thread blocks every signal while it starts (pthread_create) and answers right after; one that blocks the
    // signal for good (some libraries' threads) is not waited for beyond a moment.
    const double blocked_grace = monotonic_seconds() + 0.1;
    for (;;) {
      bool all = true;
      for (int i = 0; i < count && all; ++i) {
        const int frozen = std::min(g_frozen_count.load(), kMaxThreads);
        bool done = false;
        for (int j = 0; j < frozen && !done; ++j) done = g_frozen[j].load() == signalled[i];
        done = done || (::syscall(SYS_tgkill, process, signalled[i], 0) != 0 && errno == ESRCH) ||
               (monotonic_seconds() > blocked_grace && thread_blocks(signalled[i], signal));
        all = done;
      }
      if (all || monotonic_seconds() > deadline) break;
      const timespec pause{0, 1000000};
      ::nanosleep(&pause, nullptr);
    }
  }
}

// Removes every registered temporary, then the directories made above outputs that are empty by then, deepest
// first (a path sorts after its parent). Registry locked by the caller.
void dispose_registered() {
  for (const auto& [temporary, entry] : registry()) {
    if (!entry.parent) dispose(temporary.c_str(), entry.target.c_str(), entry.aside);
  }
  for (auto it = registry().rbegin(); it != registry().rend(); ++it) {
    if (it->second.parent) ::rmdir(it->first.c_str());
  }
}

// What the signal thread does: with the registry locked for good (no temporary is made or committed any more) and
// every other thread stopped, removes the registered temporaries and ends the process.
[[noreturn]] void clean_up_after_signal(int signal) {
  registry_mutex().lock();  // never unlocked: the process ends holding it
  char message[96] = "rfrecon: interrupted by signal ";
  char* end = format_number(message + std::strlen(message), signal);
  constexpr std::string_view kTail = "; removing temporaries\n";
  std::memcpy(end, kTail.data(), kTail.size());
  end += kTail.size();
  [[maybe_unused]] const auto written = ::write(STDERR_FILENO, message, static_cast<std::size_t>(end - message));
  stop_other_threads();
  dispose_registered();
  std::_Exit(128 + signal);
}
}  // namespace

std::size_t name_max(const fs::path& directory) {
  std::error_code ec;
  fs::path existing = directory.empty() ? fs::path(".") : directory;
  while (!fs::exists(existing, ec) && existing.has_relative_path() && existing != existing.parent_path()) {
    existing = existing.parent_path().empty() ? fs::path(".") : existing.parent_path();
  }
  const long limit = ::pathconf(existing.c_str(), _PC_NAME_MAX);
  // Too small a limit for any temporary is treated as unknown.
  return limit >= 64 ? static_cast<std::size_t>(limit) : kDefaultNameMax;
}

std::string temporary_prefix(const fs::path& target) {
  std::string name = target.filename().string();
  const std::size_t limit = name_max(directory_of(target));
  if (name.size() + kMaxTemporarySuffix <= limit) return name;
  std::size_t keep = limit - kMaxTemporarySuffix - kHashedNameBytes;
  while (keep > 0 && (static_cast<unsigned char>(name[keep]) & 0xC0) == 0x80) --keep;  // whole UTF-8 characters
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a(name)));
  return name.substr(0, keep) + "~" + hash;
}

void remove_stale_temporaries(const fs::path& target) {
  const std::string prefix = temporary_prefix(target);
  std::vector<std::pair<fs::path, bool>> stale;
  std::error_code ec;
  for (fs::directory_iterator it(directory_of(target), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    const Suffixes suffixes = parse_suffixes(std::string_view(name).substr(prefix.size()));
    if (!suffixes.pids.empty() && std::all_of(suffixes.pids.begin(), suffixes.pids.end(), process_is_gone)) {
      stale.emplace_back(it->path(), suffixes.aside);
    }
  }
  for (const auto& [temporary, aside] : stale) dispose(temporary.c_str(), target.c_str(), aside);
}

fs::path make_temporary(const fs::path& target, TemporaryKind kind) {
  static std::atomic<unsigned> counter{0};
  fs::path output = target;
  {
    const std::lock_guard<std::recursive_mutex> lock(registry_mutex());
    if (const auto it = registry().find(target); it != registry().end()) output = it->second.target;
  }
  remove_stale_temporaries(output);
  const std::string stem =
      temporary_prefix(output) + "." + std::string(tag_of(kind)) + "-" + std::to_string(::getpid()) + "-";
  const std::lock_guard<std::recursive_mutex> lock(registry_mutex());
  for (;;) {
    fs::path temporary = output.parent_path() / (stem + std::to_string(counter++));
    int error = 0;
    if (kind == TemporaryKind::kFile) {
      const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (fd < 0) {
        error = errno;
      } else {
        ::close(fd);
      }
    } else if (kind == TemporaryKind::kDirectory) {
      if (::mkdir(temporary.c_str(), 0777) != 0) error = errno;
    } else {
      struct stat status {};
      if (::lstat(temporary.c_str(), &status) == 0) error = EEXIST;
    }
    if (error == EEXIST) continue;  // left by an earlier process with this PID (another PID namespace, a reboot)
    if (error != 0) {
      throw OutputError("cannot write " + output.string() + ": cannot create " + temporary.string() + ": " +
                        std::generic_category().message(error));
    }
    registry().emplace(temporary, Entry{output, kind == TemporaryKind::kAside, false});
    return temporary;
  }
}

void release_temporary(const fs::path& temporary) {
  const std::lock_guard<std::recursive_mutex> lock(registry_mutex());
  registry().erase(temporary);
}

std::unique_lock<std::recursive_mutex> hold_temporaries() {
  return std::unique_lock<std::recursive_mutex>(registry_mutex());
}

int rename_no_replace(const fs::path& from, const fs::path& to) {
  const int error = rename2(from.c_str(), to.c_str(), kNoReplace);
  if (!unsupported(error)) return error;
  struct stat status {};
  if (::lstat(from.c_str(), &status) != 0) return errno;
  if (!S_ISDIR(status.st_mode)) {
    if (::link(from.c_str(), to.c_str()) == 0) {
      ::unlink(from.c_str());
      return 0;
    }
    if (errno == EEXIST) return EEXIST;
    // No hard links either (FAT, some FUSE file systems): a check, then the rename.
    if (::lstat(to.c_str(), &status) == 0) return EEXIST;
    return ::rename(from.c_str(), to.c_str()) == 0 ? 0 : errno;
  }
  // A directory: the name is taken by an empty directory, which the rename replaces unless something was put in it.
  if (::mkdir(to.c_str(), 0700) != 0) return errno;
  if (::rename(from.c_str(), to.c_str()) == 0) return 0;
  const int rename_error = errno;
  ::rmdir(to.c_str());
  return rename_error == ENOTEMPTY ? EEXIST : rename_error;
}

int exchange_paths(const fs::path& a, const fs::path& b) { return rename2(a.c_str(), b.c_str(), kExchange); }

bool remove_path(const fs::path& path) { return remove_tree(path.c_str()); }

void remove_registered_temporaries() {
  const std::lock_guard<std::recursive_mutex> lock(registry_mutex());
  dispose_registered();
  registry().clear();
}

std::vector<fs::path> make_parent_directories(const fs::path& target) {
  std::vector<fs::path> missing;  // deepest first
  std::error_code ec;
  for (fs::path directory = target.parent_path(); !directory.empty() && !fs::exists(directory, ec);
       directory = directory.parent_path()) {
    missing.push_back(directory);
    if (directory == directory.parent_path()) break;
  }
  std::vector<fs::path> made;
  const std::lock_guard<std::recursive_mutex> lock(registry_mutex());
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (::mkdir(it->c_str(), 0777) != 0) {
      if (errno == EEXIST && fs::is_directory(*it, ec)) continue;  // made by someone else meanwhile: not ours
      const int error = errno;
      for (auto m = made.rbegin(); m != made.rend(); ++m) {
        ::rmdir(m->c_str());
        registry().erase(*m);
      }
      throw OutputError("cannot create directory " + it->string() + ": " + std::generic_category().message(error));
    }
    registry().emplace(*it, Entry{target, false, true});
    made.push_back(*it);
  }
  if (!target.parent_path().empty() && !fs::is_directory(target.parent_path(), ec)) {
    throw OutputError("cannot create directory " + target.parent_path().string() + ": " +
                      std::generic_category().message(ENOTDIR));
  }
  return made;
}

void release_parent_directories(const std::vector<fs::path>& made, bool keep) {
  const std::lock_guard<std::recursive_mutex> lock(registry_mutex());
  for (auto it = made.rbegin(); it != made.rend(); ++it) {
    if (!keep) ::rmdir(it->c_str());
    registry().erase(*it);
  }
}

void install_signal_cleanup() {
  static sigset_t signals;
  sigemptyset(&signals);
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&signals, signal);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  // Once per process (a forked child that calls it again gets its own thread).
  static std::atomic<pid_t> installed{0};
  if (installed.exchange(::getpid()) == ::getpid()) return;
  if (g_freeze_signal.load() == 0) g_freeze_signal.store(install_freeze_signal());
  std::thread([] {
    int signal = 0;
    if (sigwait(&signals, &signal) != 0) return;
    clean_up_after_signal(signal);
  }).detach();
}

}  // namespace rfrecon
