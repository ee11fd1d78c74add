// Temporary-then-rename file and directory outputs.
#include "host/core/atomic_file.h"

#include <atomic>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include <unistd.h>

#include "host/core/errors.h"

namespace rfrecon {

namespace fs = std::filesystem;

namespace {
fs::path sibling_temp(const fs::path& target, const char* tag) {
  static std::atomic<unsigned> counter{0};
  fs::path name = target.filename();
  name += std::string(".") + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  return target.parent_path() / name;
}

bool is_empty_dir(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec) && fs::is_empty(path, ec);
}
}  // namespace

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)), temp_(sibling_temp(target_, "tmp")) {
  if (!target_.parent_path().empty()) {
    std::error_code ec;
    fs::create_directories(target_.parent_path(), ec);
    if (ec) throw std::runtime_error("cannot create directory " + target_.parent_path().string() + ": " + ec.message());
  }
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

void AtomicFile::commit() {
  std::error_code ec;
  fs::rename(temp_, target_, ec);
  if (ec) throw std::runtime_error("cannot move " + temp_.string() + " to " + target_.string() + ": " + ec.message());
  committed_ = true;
}

void write_file_atomically(const fs::path& path, std::string_view bytes) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temp_path(), std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw std::runtime_error("cannot write " + path.string());
  }
  file.commit();
}

StagingDirectory::StagingDirectory(fs::path target, bool replace_existing)
    : target_(std::move(target)), staging_(sibling_temp(target_, "staging")), replace_existing_(replace_existing) {
  std::error_code ec;
  if (fs::exists(target_, ec) && !replace_existing_ && !is_empty_dir(target_)) {
    throw InputError("output directory " + target_.string() + " exists and is not empty (use --force)");
  }
  fs::create_directories(staging_, ec);
  if (ec) throw std::runtime_error("cannot create directory " + staging_.string() + ": " + ec.message());
}

StagingDirectory::~StagingDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
  }
}

void StagingDirectory::commit() {
  std::error_code ec;
  fs::path old;
  if (fs::exists(target_, ec)) {
    old = sibling_temp(target_, "old");
    fs::rename(target_, old, ec);
    if (ec) throw std::runtime_error("cannot move aside " + target_.string() + ": " + ec.message());
  }
  fs::rename(staging_, target_, ec);
  if (ec) {
    if (!old.empty()) fs::rename(old, target_, ec);
    throw std::runtime_error("cannot move " + staging_.string() + " to " + target_.string());
  }
  committed_ = true;
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace rfrecon
