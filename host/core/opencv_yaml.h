// OpenCV FileStorage YAML files opened only in the layout that OpenCV 4.6's parser is known to finish on.
#pragma once

#include <filesystem>

#include <opencv2/core.hpp>

namespace rfrecon {

inline constexpr std::size_t kMaxYamlBytes = 1 << 20;  // a rig file is about 4 KB

// Reads `file` (at most kMaxYamlBytes) and opens it as OpenCV YAML. OpenCV 4.6 loops forever on some malformed
// files (a second document that does not start with "---", found by fuzzing), so the text must first have the
// layout cv::FileStorage writes: printable ASCII lines (LF or CRLF, no tabs; a comment may hold any other byte),
// "%YAML:1.x" or "%YAML 1.x" first (OpenCV reads nothing else as YAML), then besides blank and comment ("#") lines
// an optional "---" line and a top-level key (a letter, digit or "_" in the first column) followed by indented
// lines and more top-level keys. Throws InputError naming the file and line.
cv::FileStorage open_opencv_yaml(const std::filesystem::path& file);

}  // namespace rfrecon
