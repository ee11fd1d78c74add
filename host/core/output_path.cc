// Checks of output paths against devices, directories, the command's inputs and --force.
#include "host/core/output_path.h"

#include <system_error>
#include <vector>

#include "host/core/errors.h"

namespace rfrecon {

namespace fs = std::filesystem;

namespace {
std::string quoted(const OutputPath& output) { return output.option + " " + output.path.string(); }

const char* kind_of(fs::file_type type) {
  switch (type) {
    case fs::file_type::regular:
      return "a file";
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::character:
      return "a character device";
    case fs::file_type::block:
      return "a block device";
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::socket:
      return "a socket";
    default:
      return "not a regular file";
  }
}

void check_named(const OutputPath& output) {
  if (output.path.empty()) throw UsageError(output.option + ": the output path is empty");
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
    throw UsageError(quoted(output) + " is " + kind_of(status.type()) + "; rfrecon writes only regular files");
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
}

void check_output_directory(const OutputPath& output, const std::vector<fs::path>& inputs) {
  check_named(output);
  std::error_code ec;
  const fs::file_status status = fs::status(output.path, ec);
  const bool exists = fs::exists(status);
  if (exists && !fs::is_directory(status)) {
    throw UsageError(quoted(output) + " is " + kind_of(status.type()) + ", not a directory");
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
