// Temporary-then-rename file and directory outputs, with no-replace renames for what was absent at the start.
#include "host/core/atomic_file.h"

#include <cerrno>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "host/core/errors.h"
#include "host/core/input_file.h"
#include "host/core/output_path.h"
#include "host/core/temporaries.h"

namespace rfrecon {

namespace fs = std::filesystem;

namespace {
// The directories missing above `target` and the temporary, made together: when the temporary cannot be made, the
// directories made for it go again.
template <typename Make>
fs::path make_with_parents(const fs::path& target, std::vector<fs::path>& made_parents, Make make) {
  made_parents = make_parent_directories(target);
  try {
    return make();
  } catch (...) {
    release_parent_directories(made_parents, false);
    throw;
  }
}

std::string error_text(int error) { return std::generic_category().message(error); }

std::mutex& hook_mutex() {
  static std::mutex mutex;
  return mutex;
}

std::function<void(const fs::path&)>& hook() {
  static std::function<void(const fs::path&)> function;
  return function;
}

void run_hook(const fs::path& target) {
  std::function<void(const fs::path&)> function;
  {
    const std::lock_guard<std::mutex> lock(hook_mutex());
    function = hook();
  }
  if (function) function(target);
}

// An output between its construction and its commit: what the final rename may replace.
struct Pending {
  fs::path target;
  std::string option = "output";
  bool directory = false;
  bool checked = false;  // a start check recorded it: an output of the command
  bool replace = false;
  bool empty_at_start = false;
};

std::mutex& pending_mutex() {
  static std::mutex mutex;
  return mutex;
}

std::map<std::uint64_t, Pending>& pending() {
  static std::map<std::uint64_t, Pending> outputs;
  return outputs;
}

std::uint64_t add_pending(Pending output) {
  static std::uint64_t next = 0;
  const std::lock_guard<std::mutex> lock(pending_mutex());
  pending().emplace(++next, std::move(output));
  return next;
}

void remove_pending(std::uint64_t id) {
  const std::lock_guard<std::mutex> lock(pending_mutex());
  pending().erase(id);
}

Pending pending_output(std::uint64_t id) {
  const std::lock_guard<std::mutex> lock(pending_mutex());
  return pending().at(id);
}

std::string named(const Pending& output) { return output.option + " " + output.target.string(); }

constexpr const char* kNothingWritten = "; it is left as it is and nothing was written";

// Why what has `output`'s name now may not be replaced; empty when it may (or nothing has it).
std::string refusal(const Pending& output) {
  std::error_code ec;
  const fs::file_status link = fs::symlink_status(output.target, ec);
  if (!fs::exists(link)) return "";
  const fs::file_status status = fs::status(output.target, ec);
  const bool is_directory = fs::is_directory(status);
  // Something (not a link to nothing) of the wrong kind: never replaced, whatever --force said at the start.
  if (fs::exists(status) &&
      (output.directory ? !is_directory && (output.replace || output.empty_at_start) : is_directory)) {
    return named(output) + " became " + kind_of_file(status) + " while the command ran" + kNothingWritten;
  }
  if (output.replace) return "";
  if (output.empty_at_start && is_directory) {
    if (fs::is_empty(output.target, ec) && !ec) return "";
    return named(output) + " was an empty directory when the command started and now holds files" + kNothingWritten +
           " (run the command again, with --force to replace it)";
  }
  return named(output) + " appeared while the command ran (another program wrote it)" + kNothingWritten +
         " (run the command again, with --force to replace it)";
}

// The same refusal when a no-replace rename found the name taken, even if it is gone again by now.
std::string refusal_after_rename(const Pending& output) {
  std::string reason = refusal(output);
  if (reason.empty()) {
    reason = named(output) + " appeared while the command ran (another program wrote it)" + kNothingWritten;
  }
  return reason;
}

// Before a commit renames anything: every output of the command still pending (its start check recorded it) whose
// target appeared is refused now, so that a command does not put its main output in place and then fail on its
// summary. Outputs without a start check are left to their own no-replace rename.
void refuse_if_any_appeared() {
  std::vector<Pending> checked;
  {
    const std::lock_guard<std::mutex> lock(pending_mutex());
    for (const auto& entry : pending()) {
      if (entry.second.checked) checked.push_back(entry.second);
    }
  }
  for (const auto& output : checked) {
    if (std::string reason = refusal(output); !reason.empty()) throw UsageError(reason);
  }
}

bool name_taken(const fs::path& path) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(path, ec));
}
}  // namespace

void set_before_commit_hook(std::function<void(const fs::path& target)> function) {
  const std::lock_guard<std::mutex> lock(hook_mutex());
  hook() = std::move(function);
}

AtomicFile::AtomicFile(fs::path target, ReplacePolicy policy) : target_(std::move(target)) {
  const std::optional<OutputStart> start = take_output_start(target_);
  Pending output;
  output.target = target_;
  output.checked = start.has_value();
  if (start) output.option = start->option;
  replace_ = policy == ReplacePolicy::kAlways || (start ? start->replace : name_taken(target_));
  output.replace = replace_;
  if (start) {
    if (std::string reason = refusal(output); !reason.empty()) throw UsageError(reason);
  }
  temp_ = make_with_parents(target_, made_parents_, [&] { return make_temporary(target_, TemporaryKind::kFile); });
  pending_ = add_pending(std::move(output));
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
    release_temporary(temp_);
    release_parent_directories(made_parents_, false);
  }
  remove_pending(pending_);
}

void AtomicFile::commit() {
  run_hook(target_);
  refuse_if_any_appeared();
  const auto lock = hold_temporaries();
  int error = 0;
  if (replace_) {
    if (::rename(temp_.c_str(), target_.c_str()) != 0) error = errno;
  } else {
    error = rename_no_replace(temp_, target_);
  }
  if (!replace_ && (error == EEXIST || error == ENOTEMPTY)) {
    throw UsageError(refusal_after_rename(pending_output(pending_)));
  }
  if (error != 0) {
    throw OutputError("cannot move " + temp_.string() + " to " + target_.string() + ": " + error_text(error));
  }
  committed_ = true;
  release_temporary(temp_);
  release_parent_directories(made_parents_, true);
  remove_pending(pending_);  // in place: no longer an output that could appear
}

void AtomicFile::write(std::string_view bytes) const {
  // Without O_CREAT: a temporary that a signal's cleanup removed is not made again.
  const int fd = ::open(temp_.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  int error = fd < 0 ? errno : 0;
  for (std::size_t done = 0; error == 0 && done < bytes.size();) {
    const ssize_t written = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (written < 0 && errno != EINTR) error = errno;
    if (written > 0) done += static_cast<std::size_t>(written);
  }
  if (fd >= 0 && ::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) {
    throw OutputError("cannot write " + target_.string() +
                      " (permission, read-only file system or disk full): " + error_text(error));
  }
}

void write_file_atomically(const fs::path& path, std::string_view bytes, ReplacePolicy policy) {
  AtomicFile file(path, policy);
  file.write(bytes);
  file.commit();
}

StagingDirectory::StagingDirectory(fs::path target, bool replace_existing)
    : target_(std::move(target)), replace_existing_(replace_existing) {
  const std::optional<OutputStart> start = take_output_start(target_);
  Pending output;
  output.target = target_;
  output.directory = true;
  output.checked = start.has_value();
  if (start) {
    output.option = start->option;
    replace_ = replace_existing_ && start->replace;
    empty_at_start_ = start->empty_directory || (start->existed && !replace_);
    output.replace = replace_;
    output.empty_at_start = empty_at_start_;
    if (std::string reason = refusal(output); !reason.empty()) throw UsageError(reason);
  } else {
    // What check_output_directory refuses (a file, a non-empty directory without replace_existing) is refused here.
    check_output_directory({target_, "output directory", replace_existing_}, {});
    take_output_start(target_);
    replace_ = replace_existing_ && name_taken(target_);
    empty_at_start_ = !replace_ && name_taken(target_);
    output.replace = replace_;
    output.empty_at_start = empty_at_start_;
  }
  staging_ =
      make_with_parents(target_, made_parents_, [&] { return make_temporary(target_, TemporaryKind::kDirectory); });
  pending_ = add_pending(std::move(output));
}

StagingDirectory::~StagingDirectory() {
  if (!committed_) {
    remove_path(staging_);
    release_temporary(staging_);
    release_parent_directories(made_parents_, false);
  }
  remove_pending(pending_);
}

void StagingDirectory::commit() {
  run_hook(target_);
  refuse_if_any_appeared();
  const Pending output = pending_output(pending_);
  fs::path replaced;  // where the replaced directory lies after the swap, removed once the lock is let go
  {
    const auto lock = hold_temporaries();
    if (std::string reason = refusal(output); !reason.empty()) throw UsageError(reason);
    std::error_code ec;
    const fs::file_status link = fs::symlink_status(target_, ec);
    int error = 0;
    if (!fs::exists(link)) {
      error = rename_no_replace(staging_, target_);
    } else if (empty_at_start_ && fs::is_directory(link)) {
      // Still empty (refusal above): it goes, and the new one takes its name unless something took it meanwhile.
      if (::rmdir(target_.c_str()) != 0 && errno != ENOENT) error = errno == EEXIST ? ENOTEMPTY : errno;
      if (error == 0) error = rename_no_replace(staging_, target_);
    } else {
      // With --force (or a link to an empty directory, or a link to nothing): the two swap names in one step, so
      // the target's name is never free; the earlier one, now under the staging name, is removed after.
      error = exchange_paths(staging_, target_);
      if (error == 0) {
        replaced = staging_;
      } else if (error == EINVAL || error == ENOSYS || error == EOPNOTSUPP) {
        const fs::path old = make_temporary(target_, TemporaryKind::kAside);
        if (::rename(target_.c_str(), old.c_str()) != 0) {
          error = errno;
          release_temporary(old);
          throw OutputError("cannot move aside " + target_.string() + ": " + error_text(error));
        }
        error = rename_no_replace(staging_, target_);
        if (error == 0) {
          replaced = old;
          release_temporary(staging_);
        } else if (rename_no_replace(old, target_) == 0) {
          release_temporary(old);
        } else {
          release_temporary(old);  // kept, not removed by a signal: the message says where it is
          throw UsageError(refusal_after_rename(output) + "; the earlier " + target_.string() + " is now " +
                           old.string());
        }
      }
    }
    if (error == EEXIST || error == ENOTEMPTY) throw UsageError(refusal_after_rename(output));
    if (error != 0) {
      throw OutputError("cannot move " + staging_.string() + " to " + target_.string() + ": " + error_text(error));
    }
    committed_ = true;
    if (replaced.empty()) release_temporary(staging_);
    release_parent_directories(made_parents_, true);
  }
  remove_pending(pending_);
  if (!replaced.empty()) {
    remove_path(replaced);
    release_temporary(replaced);
  }
}

}  // namespace rfrecon
