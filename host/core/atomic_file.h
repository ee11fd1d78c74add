// Outputs that appear whole or not at all: write to a temporary beside the target, then rename.
#pragma once

#include <filesystem>
#include <string_view>

namespace rfrecon {

// A temporary path next to `target`; commit() renames it onto target. Destroyed uncommitted, it removes the
// temporary, so a failed run never leaves a partial file under the final name. The temporary's name is registered
// (host/core/temporaries.h): removed on SIGINT/SIGTERM, and by a later run when this process was killed. Failures
// to create, write or rename throw OutputError naming the path.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  const std::filesystem::path& temp_path() const { return temp_; }
  const std::filesystem::path& target() const { return target_; }
  // Writes `bytes` to the temporary; throws OutputError naming the target on failure.
  void write(std::string_view bytes) const;
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  bool committed_ = false;
};

// Writes bytes to path through an AtomicFile; throws OutputError naming the path on failure.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

// A staging directory next to `target` for outputs made of many files. commit() moves it into place: a target
// that does not exist (or is an empty directory) is replaced; an existing non-empty target is replaced only when
// `replace_existing` is set, and then only after the new one is complete. Constructing throws UsageError for a
// target that is not a directory, or holds something and `replace_existing` is not set (check_output_directory).
// Destroyed uncommitted, the staging directory is removed and the target is untouched.
class StagingDirectory {
 public:
  StagingDirectory(std::filesystem::path target, bool replace_existing);
  StagingDirectory(const StagingDirectory&) = delete;
  StagingDirectory& operator=(const StagingDirectory&) = delete;
  ~StagingDirectory();

  const std::filesystem::path& path() const { return staging_; }
  const std::filesystem::path& target() const { return target_; }
  // Writes `bytes` to the temporary; throws OutputError naming the target on failure.
  void write(std::string_view bytes) const;
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  bool replace_existing_;
  bool committed_ = false;
};

}  // namespace rfrecon
