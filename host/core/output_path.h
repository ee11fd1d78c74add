// The rules every command's outputs follow: only regular files and directories are written, never one of the
// command's inputs, and an existing output only with --force (docs/cli.md).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rfrecon {

// One output of a command: its path, the option that named it (for messages) and whether it may replace an
// existing one (--force).
struct OutputPath {
  std::filesystem::path path;
  std::string option = "output";
  bool force = false;
};

// Throws UsageError unless `output` may be written as a file: a non-empty path that is not a directory, a device,
// a FIFO or a socket (nor a link to one), not the same file as any of `inputs` (compared by inode; an input that is
// a directory stands for every file under it), and absent unless output.force.
void check_output_file(const OutputPath& output, const std::vector<std::filesystem::path>& inputs);

// Throws UsageError unless `output` may be written as a directory that replaces what is there: a non-empty path
// that is not a file, holding none of `inputs` (replacing it would delete them), and absent or empty unless
// output.force.
void check_output_directory(const OutputPath& output, const std::vector<std::filesystem::path>& inputs);

// Throws UsageError when two of `outputs` name the same path (or one lies inside another that is a directory).
void check_distinct_outputs(const std::vector<OutputPath>& outputs);

}  // namespace rfrecon
