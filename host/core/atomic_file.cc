// Temporary-then-rename file and directory outputs.
#include "host/core/atomic_file.h"

#include <fstream>
#include <string>
#include <system_error>

#include "host/core/errors.h"
#include "host/core/output_path.h"
#include "host/core/temporaries.h"

namespace rfrecon {

namespace fs = std::filesystem;

namespace {
void create_parent(const fs::path& target) {
  if (target.parent_path().empty()) return;
  std::error_code ec;
  fs::create_directories(target.parent_path(), ec);
  if (ec) throw OutputError("cannot create directory " + target.parent_path().string() + ": " + ec.message());
}
}  // namespace

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)) {
  create_parent(target_);
  temp_ = make_temporary(target_, "tmp");
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
    release_temporary(temp_);
  }
}

void AtomicFile::commit() {
  std::error_code ec;
  fs::rename(temp_, target_, ec);
  if (ec) throw OutputError("cannot move " + temp_.string() + " to " + target_.string() + ": " + ec.message());
  committed_ = true;
  release_temporary(temp_);
}

void AtomicFile::write(std::string_view bytes) const {
  std::ofstream out(temp_, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw OutputError("cannot write " + target_.string() + " (permission, read-only file system or disk full)");
}

void write_file_atomically(const fs::path& path, std::string_view bytes) {
  AtomicFile file(path);
  file.write(bytes);
  file.commit();
}

StagingDirectory::StagingDirectory(fs::path target, bool replace_existing)
    : target_(std::move(target)), replace_existing_(replace_existing) {
  check_output_directory({target_, "output directory", replace_existing_}, {});
  create_parent(target_);
  std::error_code ec;
  staging_ = make_temporary(target_, "staging");
  fs::create_directory(staging_, ec);
  if (ec) throw OutputError("cannot create directory " + staging_.string() + ": " + ec.message());
}

StagingDirectory::~StagingDirectory() {
  if (!committed_) {
    std::error_code ec;
    fs::remove_all(staging_, ec);
    release_temporary(staging_);
  }
}

void StagingDirectory::commit() {
  std::error_code ec;
  fs::path old;
  if (fs::exists(target_, ec)) {
    old = make_temporary(target_, "old");
    fs::rename(target_, old, ec);
    if (ec) throw OutputError("cannot move aside " + target_.string() + ": " + ec.message());
  }
  fs::rename(staging_, target_, ec);
  if (ec) {
    if (!old.empty()) fs::rename(old, target_, ec);
    throw OutputError("cannot move " + staging_.string() + " to " + target_.string());
  }
  committed_ = true;
  release_temporary(staging_);
  if (!old.empty()) {
    fs::remove_all(old, ec);
    release_temporary(old);
  }
}

}  // namespace rfrecon
