// Checks of output paths against devices, directories, the command's inputs and --force.
#include "host/core/output_path.h"

#include <iterator>
#include <map>
#include <mutex>
#include <system_error>
#include <vector>

#include "host/core/errors.h"
#include "host/core/input_file.h"

namespace rfrecon {

namespace fs = std::filesystem;

namespace {
std::string quoted(const OutputPath& output) { return output.option + " " + output.path.string(); }

// A name longer than the file system allows, or a path longer than the kernel takes with a temporary's suffix, is
// refused before any work: writing it could only fail at the end.
void check_named(const OutputPath& output) {
  if (output.path.empty()) throw UsageError(output.option + ": the output path is empty");
  const std::string text = output.path.string();
  if (text.size() > kMaxOutputPathBytes) {
    throw UsageError(output.option + ": the output path is " + std::to_string(text.size()) + " bytes long; at most " +
                     std::to_string(kMaxOutputPathBytes) + " are allowed");
  }
  fs::path directory;
  for (auto part = output.path.begin(); part != output.path.end(); ++part) {
    const std::string name = part->string();
    if (!part->has_root_path() && name != "." && name != "..") {
      const std::size_t limit = name_max(directory);
      if (name.size() > limit) {
        const bool last = std::next(part) == output.path.end();
        throw UsageError(quoted(output) + ": " + (last ? "its name" : "a directory name in it") + " is " +
                         std::to_string(name.size()) + " bytes long; the file system allows at most " +
                         std::to_string(limit) + " bytes in a name");
      }
    }
    directory /= *part;
  }
}

// The form a path is recorded under: absolute, normal, without a trailing separator.
std::string record_key(const fs::path& path) {
  std::error_code ec;
  fs::path key = fs::absolute(path, ec).lexically_normal();
  if (ec) key = path.lexically_normal();
  if (key.filename().empty() && key.has_relative_path()) key = key.parent_path();
  return key.string();
}

std::mutex& starts_mutex() {
  static std::mutex mutex;
  return mutex;
}

std::map<std::string, OutputStart>& starts() {
  static std::map<std::string, OutputStart> recorded;
  return recorded;
}

void record_start(const OutputPath& output, OutputStart start) {
  start.option = output.option;
  start.force = output.force;
  const std::lock_guard<std::mutex> lock(starts_mutex());
  starts()[record_key(output.path)] = std::move(start);
}

// The absolute, normalised form of `path` with its existing part's links resolved.
fs::path resolved(const fs::path& path) {
  std::error_code ec;
  fs::path result = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? fs::absolute(path).lexically_normal() : result;
}

// Whether `path` is `directory` itself or lies under it, links resolved.
bool is_within(const fs::path& path, const fs::path& directory) {
  const fs::path relative = resolved(path).lexically_relative(resolved(directory));
  return !relative.empty() && *relative.begin() != "..";
}

// `input` itself, or the regular files under it when it is a directory.
std::vector<fs::path> input_files(const fs::path& input) {
  std::error_code ec;
  if (!fs::is_directory(input, ec)) return {input};
  std::vector<fs::path> files;
  for (fs::recursive_directory_iterator it(input, fs::directory_options::skip_permission_denied, ec), end;
       !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file(ec)) files.push_back(it->path());
  }
  return files;
}
}  // namespace

void check_output_file(const OutputPath& output, const std::vector<fs::path>& inputs) {
  check_named(output);
  std::error_code ec;
  const fs::file_status status = fs::status(output.path, ec);
  const bool exists = fs::exists(status);
  if (exists && !fs::is_regular_file(status)) {
    throw UsageError(quoted(output) + " is " + kind_of_file(status) + "; rfrecon writes only regular files");
  }
  if (!exists && output.path.filename().empty()) throw UsageError(quoted(output) + " names a directory, not a file");
  for (const auto& input : inputs) {
    for (const auto& file : exists ? input_files(input) : std::vector<fs::path>{}) {
      if (fs::equivalent(output.path, file, ec)) {
        throw UsageError(quoted(output) + " is also an input (" + file.string() + "); writing it would destroy it");
      }
    }
  }
  if (exists && !output.force) throw UsageError(quoted(output) + " exists (use --force to replace it)");
  const bool name_taken = fs::exists(fs::symlink_status(output.path, ec));
  OutputStart start;
  start.existed = name_taken;
  start.replace = name_taken && (output.force || !exists);
  record_start(output, start);
}

void check_output_directory(const OutputPath& output, const std::vector<fs::path>& inputs) {
  check_named(output);
  std::error_code ec;
  const fs::file_status status = fs::status(output.path, ec);
  const bool exists = fs::exists(status);
  if (exists && !fs::is_directory(status)) {
    throw UsageError(quoted(output) + " is " + kind_of_file(status) + ", not a directory");
  }
  for (const auto& input : inputs) {
    // The directory itself, or anything under it; an input the layout names but does not have (the manifest of an
    // opencv-graycode capture) is not one to name.
    if (fs::exists(input, ec) && is_within(input, output.path)) {
      throw UsageError(quoted(output) + " holds the input " + input.string() +
                       "; replacing the directory would delete it");
    }
  }
  if (exists && !output.force && !fs::is_empty(output.path, ec)) {
    throw UsageError(quoted(output) + " exists and is not empty (use --force to replace it)");
  }
  const bool name_taken = fs::exists(fs::symlink_status(output.path, ec));
  OutputStart start;
  start.existed = name_taken;
  start.replace = name_taken && (output.force || !exists);
  start.empty_directory = exists && !output.force;
  record_start(output, start);
}

std::optional<OutputStart> take_output_start(const fs::path& path) {
  const std::lock_guard<std::mutex> lock(starts_mutex());
  const auto it = starts().find(record_key(path));
  if (it == starts().end()) return std::nullopt;
  OutputStart start = std::move(it->second);
  starts().erase(it);
  return start;
}

void check_distinct_outputs(const std::vector<OutputPath>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    for (std::size_t j = 0; j < outputs.size(); ++j) {
      if (i == j || outputs[i].path.empty() || outputs[j].path.empty()) continue;
      if (is_within(outputs[j].path, outputs[i].path)) {  // the same path, or one under the other
        throw UsageError(quoted(outputs[j]) + " and " + quoted(outputs[i]) + " would overwrite each other");
      }
    }
  }
}

}  // namespace rfrecon
