// The rules every command's outputs follow: only regular files and directories are written, never one of the
// command's inputs, and an existing output only with --force (docs/cli.md).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "host/core/temporaries.h"

namespace rfrecon {

// One output of a command: its path, the option that named it (for messages) and whether it may replace an
// existing one (--force).
struct OutputPath {
  std::filesystem::path path;
  std::string option = "output";
  bool force = false;
};

// The longest output path, in bytes: the kernel's PATH_MAX (4096 with the terminating NUL) less room for a
// temporary's suffix (kMaxTemporarySuffix).
inline constexpr std::size_t kMaxOutputPathBytes = 4095 - kMaxTemporarySuffix;

// Throws UsageError unless `output` may be written as a file: a non-empty path that is not a directory, a device,
// a FIFO or a socket (nor a link to one), not the same file as any of `inputs` (compared by inode; an input that is
// a directory stands for every file under it), and absent unless output.force. A name in the path longer than its
// file system allows (name_max, 255 bytes on most) or a path longer than kMaxOutputPathBytes is refused too.
// What it found is recorded for the final step (take_output_start).
void check_output_file(const OutputPath& output, const std::vector<std::filesystem::path>& inputs);

// Throws UsageError unless `output` may be written as a directory that replaces what is there: a non-empty path
// that is not a file, holding none of `inputs` (replacing it would delete them), and absent or empty unless
// output.force; names and length as for check_output_file. What it found is recorded for the final step.
void check_output_directory(const OutputPath& output, const std::vector<std::filesystem::path>& inputs);

// What a start check found for an output, for the final step of AtomicFile and StagingDirectory: what may be
// replaced then is only what was there at the start, and only with --force, so an output that appears while the
// command runs is never replaced.
struct OutputStart {
  std::string option;            // for messages, e.g. "--output"
  bool existed = false;          // the name was taken (links not followed)
  bool force = false;            // --force was given
  bool replace = false;          // what has the name at the end may be replaced: it existed and --force, or it was a
                                 // link to nothing (which the check lets a command replace)
  bool empty_directory = false;  // a directory output that was an empty directory, no --force: replaced only while
                                 // it is still empty
};

// Takes (and forgets) what the last check_output_file or check_output_directory of `path` recorded; nothing when
// no check recorded it. Paths are compared in absolute, normal form.
std::optional<OutputStart> take_output_start(const std::filesystem::path& path);

// Throws UsageError when two of `outputs` name the same path (or one lies inside another that is a directory).
void check_distinct_outputs(const std::vector<OutputPath>& outputs);

}  // namespace rfrecon
