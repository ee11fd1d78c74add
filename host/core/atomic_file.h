// Outputs that appear whole or not at all: write to a temporary beside the target, then rename; and never replace
// an output that appeared while the command ran.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rfrecon {

// What the final rename may replace.
enum class ReplacePolicy {
  // What the output's start check (check_output_file, check_output_directory) found and allowed: an output that
  // existed at the start with --force. Without a start check, what has the name when the AtomicFile is made (a
  // StagingDirectory: when `replace_existing`). Anything else, in particular anything that appeared since, is
  // refused with UsageError (exit 2) naming the output, and the temporary removed.
  kAsStarted,
  // Whatever has the name at the end (a cache entry that any run may write).
  kAlways,
};

// A temporary file next to `target` (made empty and registered: host/core/temporaries.h); commit() renames it onto
// target as the ReplacePolicy allows: no-replace renames (renameat2 RENAME_NOREPLACE, or link then unlink), so
// nothing that appears before the rename is replaced. Destroyed uncommitted, it removes the temporary (and the
// directories it made above the target, while empty), so a failed run never leaves a partial file under the final
// name. The temporary is removed on SIGINT/SIGTERM, and by a later
// run when this process was killed. Failures to create, write or rename throw OutputError naming the path.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target, ReplacePolicy policy = ReplacePolicy::kAsStarted);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  const std::filesystem::path& temp_path() const { return temp_; }
  const std::filesystem::path& target() const { return target_; }
  // Writes `bytes` to the temporary (which must still exist: a removed one is not made again); throws OutputError
  // naming the target on failure.
  void write(std::string_view bytes) const;
  // Renames the temporary onto the target. Throws UsageError when the target, or another output of the command
  // that is still pending, appeared since the start (nothing is renamed then).
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  std::vector<std::filesystem::path> made_parents_;  // directories made above the target, removed if it fails
  bool replace_ = false;
  std::uint64_t pending_ = 0;
  bool committed_ = false;
};

// Writes bytes to path through an AtomicFile; throws OutputError naming the path on failure, UsageError when the
// output appeared meanwhile.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes,
                           ReplacePolicy policy = ReplacePolicy::kAsStarted);

// A staging directory next to `target` for outputs made of many files. commit() moves it into place: a target
// that does not exist (or is an empty directory) is replaced; an existing non-empty target is replaced only when
// `replace_existing` is set (and, after a start check, --force was given), and then only after the new one is
// complete, by swapping the two in one step (renameat2 RENAME_EXCHANGE; moving the old one aside where the file
// system lacks it). A target that was absent at the start is never replaced: what appeared there meanwhile is
// refused (UsageError) and kept; one that was an empty directory is replaced only while it is still empty.
// Constructing throws UsageError for a target that is not a directory, or holds something and `replace_existing`
// is not set (check_output_directory). Destroyed uncommitted, the staging directory (and the directories made
// above the target, while empty) is removed and the target is untouched.
class StagingDirectory {
 public:
  StagingDirectory(std::filesystem::path target, bool replace_existing);
  StagingDirectory(const StagingDirectory&) = delete;
  StagingDirectory& operator=(const StagingDirectory&) = delete;
  ~StagingDirectory();

  const std::filesystem::path& path() const { return staging_; }
  const std::filesystem::path& target() const { return target_; }
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  std::vector<std::filesystem::path> made_parents_;  // directories made above the target, removed if it fails
  bool replace_existing_;
  bool replace_ = false;
  bool empty_at_start_ = false;
  std::uint64_t pending_ = 0;
  bool committed_ = false;
};

// For tests only: `hook` is called with the target at the start of every AtomicFile::commit and
// StagingDirectory::commit, after the output's work and before anything is renamed, so that a test can make the
// output appear between the start check and the final rename, or signal the process there, without timing luck.
// A temporary of a temporary (T.h5's HDF5 image inside its AtomicFile) calls it with the outer temporary. An empty
// function removes it.
void set_before_commit_hook(std::function<void(const std::filesystem::path& target)> hook);

}  // namespace rfrecon
