// OpenCV FileStorage YAML files opened only in the layout that OpenCV 4.6's parser is known to finish on.
#pragma once

#include <cstddef>
#include <filesystem>

#include <opencv2/core.hpp>

namespace rfrecon {

inline constexpr std::size_t kMaxYamlBytes = 1 << 20;  // a rig file is about 4 KB

// Reads `file` (at most kMaxYamlBytes) and opens it as OpenCV YAML. OpenCV 4.6 loops forever on some malformed
// files (a second document that does not start with "---", found by fuzzing), so the text must first have the
// layout cv::FileStorage writes: printable ASCII lines (LF or CRLF, no tabs; a comment may hold any other byte),
// "%YAML:1.x" or "%YAML 1.x" first (OpenCV reads nothing else as YAML), then besides blank and comment ("#") lines
// an optional "---" line and a top-level key (a letter, digit or "_" in the first column) followed by indented
// lines and more top-level keys. Nor may the text nest deeper than kMaxNestingDepth (limits.h) by the bound
// check_nesting computes: the parser recurses once per level and a 100 KB line of "[" overflowed the stack. The file
// must be a regular file (check_input_file). Throws InputError naming the file and line.
cv::FileStorage open_opencv_yaml(const std::filesystem::path& file);

}  // namespace rfrecon
