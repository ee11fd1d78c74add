// Test helper: a fresh empty directory under the system temp directory, unique per process and name, removed with
// everything in it when the helper goes out of scope.
#pragma once

#include <filesystem>
#include <string>
#include <system_error>

#include <unistd.h>

namespace rfrecon::testing {

class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / ("rfrecon_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace rfrecon::testing
