// Program binaries on disk: <directory>/<16 hex digits of the key>.clbin, written atomically.
#include "host/cl/program_store.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>
#include <system_error>

#include <spdlog/spdlog.h>

#include "host/core/atomic_file.h"

namespace rfrecon::cl {

namespace {
constexpr const char* kExtension = ".clbin";

std::filesystem::path environment_path(const char* variable) {
  const char* value = std::getenv(variable);
  return value != nullptr ? std::filesystem::path(value) : std::filesystem::path();
}
}  // namespace

std::filesystem::path ProgramStore::default_directory() {
  if (const std::filesystem::path chosen = environment_path(kProgramCacheEnv); !chosen.empty()) {
    return chosen == "off" ? std::filesystem::path() : chosen;
  }
  if (const std::filesystem::path xdg = environment_path("XDG_CACHE_HOME"); xdg.is_absolute()) {
    return xdg / "rfrecon" / "programs";
  }
  if (const std::filesystem::path home = environment_path("HOME"); home.is_absolute()) {
    return home / ".cache" / "rfrecon" / "programs";
  }
  return {};
}

ProgramStore::ProgramStore(std::filesystem::path directory) : directory_(std::move(directory)) {}

std::filesystem::path ProgramStore::path(std::uint64_t key) const {
  char name[17];
  std::snprintf(name, sizeof name, "%016llx", static_cast<unsigned long long>(key));
  return directory_ / (std::string(name) + kExtension);
}

std::optional<std::vector<unsigned char>> ProgramStore::load(std::uint64_t key) const {
  if (!enabled()) return std::nullopt;
  std::ifstream in(path(key), std::ios::binary);
  if (!in) return std::nullopt;
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad() || bytes.empty()) return std::nullopt;
  return bytes;
}

void ProgramStore::save(std::uint64_t key, const std::vector<unsigned char>& binary) const {
  if (!enabled() || binary.empty()) return;
  try {
    std::filesystem::create_directories(directory_);
    // A cache entry: whatever another run stored meanwhile under the same key is replaced.
    write_file_atomically(path(key), std::string_view(reinterpret_cast<const char*>(binary.data()), binary.size()),
                          ReplacePolicy::kAlways);
  } catch (const std::exception& error) {
    spdlog::warn("program cache: not saved ({}); set {}=off to stop trying", error.what(), kProgramCacheEnv);
  }
}

std::size_t ProgramStore::clear() const {
  if (!enabled()) return 0;
  std::error_code error;
  std::size_t removed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(directory_, error)) {
    if (entry.path().extension() == kExtension && std::filesystem::remove(entry.path(), error)) ++removed;
  }
  return removed;
}

}  // namespace rfrecon::cl
