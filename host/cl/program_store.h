// Built program binaries kept on disk, so that a second run loads its kernels instead of compiling them: one file
// per device, driver, source and build options (docs/performance.md#program-cache).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

namespace rfrecon::cl {

// $RFRECON_PROGRAM_CACHE names the store's directory; "off" disables it.
inline constexpr const char* kProgramCacheEnv = "RFRECON_PROGRAM_CACHE";

class ProgramStore {
 public:
  // $RFRECON_PROGRAM_CACHE, else $XDG_CACHE_HOME/rfrecon/programs, else $HOME/.cache/rfrecon/programs; empty (no
  // store) for "off" or without a home directory.
  static std::filesystem::path default_directory();

  // An empty directory disables the store: load() finds nothing and save() writes nothing.
  explicit ProgramStore(std::filesystem::path directory = default_directory());

  bool enabled() const { return !directory_.empty(); }
  const std::filesystem::path& directory() const { return directory_; }

  // The binary stored under key, or nothing (no file, an unreadable or an empty one).
  std::optional<std::vector<unsigned char>> load(std::uint64_t key) const;
  // Stores binary under key atomically. The store only saves time, so a failure to write is logged, not thrown.
  void save(std::uint64_t key, const std::vector<unsigned char>& binary) const;
  // Removes every stored binary (files named as save() names them); returns how many.
  std::size_t clear() const;

 private:
  std::filesystem::path path(std::uint64_t key) const;
  std::filesystem::path directory_;
};

}  // namespace rfrecon::cl
