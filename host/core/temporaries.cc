// Registry of live temporaries, removal of stale ones by PID, and the signal thread that cleans up on SIGINT/SIGTERM.
#include "host/core/temporaries.h"

#include <atomic>
#include <cerrno>
#include <charconv>
#include <csignal>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include <pthread.h>
#include <unistd.h>

namespace rfrecon {

namespace fs = std::filesystem;

namespace {
constexpr std::string_view kTags[] = {"tmp", "staging", "old"};

std::mutex& registry_mutex() {
  static std::mutex mutex;
  return mutex;
}

// Live temporaries and the targets they stand for.
std::map<fs::path, fs::path>& registry() {
  static std::map<fs::path, fs::path> paths;
  return paths;
}

struct Owner {
  pid_t pid = 0;  // 0: not a temporary of the name
  bool old = false;
};

// The owner of "NAME.TAG-PID-N" when `candidate` is a temporary of `name`.
Owner temporary_owner(std::string_view candidate, std::string_view name) {
  if (candidate.size() <= name.size() + 1 || candidate.substr(0, name.size()) != name ||
      candidate[name.size()] != '.') {
    return {};
  }
  std::string_view rest = candidate.substr(name.size() + 1);
  for (const auto tag : kTags) {
    if (rest.size() <= tag.size() + 1 || rest.substr(0, tag.size()) != tag || rest[tag.size()] != '-') continue;
    rest.remove_prefix(tag.size() + 1);
    pid_t pid = 0;
    const auto [end, error] = std::from_chars(rest.data(), rest.data() + rest.size(), pid);
    if (error != std::errc() || pid <= 0 || end == rest.data() + rest.size() || *end != '-') return {};
    std::size_t counter = 0;
    const auto [counter_end, counter_error] = std::from_chars(end + 1, rest.data() + rest.size(), counter);
    if (counter_error != std::errc() || counter_end != rest.data() + rest.size()) return {};
    return {pid, tag == "old"};
  }
  return {};
}

bool process_is_gone(pid_t pid) { return pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH; }

// Removes a temporary; an old version moved aside goes back to `target` when nothing replaced it.
void dispose(const fs::path& temporary, const fs::path& target, bool old) {
  std::error_code ec;
  if (old && !fs::exists(fs::symlink_status(target, ec))) {
    fs::rename(temporary, target, ec);
    if (!ec) return;
  }
  fs::remove_all(temporary, ec);
}
}  // namespace

void remove_stale_temporaries(const fs::path& target) {
  const std::string name = target.filename().string();
  const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::vector<std::pair<fs::path, bool>> stale;
  std::error_code ec;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const Owner owner = temporary_owner(it->path().filename().string(), name);
    if (owner.pid != 0 && process_is_gone(owner.pid)) stale.emplace_back(it->path(), owner.old);
  }
  for (const auto& [temporary, old] : stale) dispose(temporary, target, old);
}

fs::path make_temporary(const fs::path& target, std::string_view tag) {
  static std::atomic<unsigned> counter{0};
  remove_stale_temporaries(target);
  fs::path name = target.filename();
  name += "." + std::string(tag) + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  fs::path temporary = target.parent_path() / name;
  const std::lock_guard<std::mutex> lock(registry_mutex());
  registry().emplace(temporary, target);
  return temporary;
}

void release_temporary(const fs::path& temporary) {
  const std::lock_guard<std::mutex> lock(registry_mutex());
  registry().erase(temporary);
}

void remove_registered_temporaries() {
  const std::lock_guard<std::mutex> lock(registry_mutex());
  for (const auto& [temporary, target] : registry()) {
    dispose(temporary, target, temporary_owner(temporary.filename().string(), target.filename().string()).old);
  }
  registry().clear();
}

void install_signal_cleanup() {
  static sigset_t signals;
  sigemptyset(&signals);
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&signals, signal);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread([] {
    int signal = 0;
    if (sigwait(&signals, &signal) != 0) return;
    std::fprintf(stderr, "rfrecon: interrupted by signal %d; removing temporaries\n", signal);
    remove_registered_temporaries();
    std::_Exit(128 + signal);
  }).detach();
}

}  // namespace rfrecon
