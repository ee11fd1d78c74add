// The layout check of an OpenCV YAML file, then cv::FileStorage over the checked text.
#include "host/core/opencv_yaml.h"

#include <cctype>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "host/core/errors.h"

namespace rfrecon {

namespace {

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("cannot read " + file.string());
  std::string text;
  text.resize(kMaxYamlBytes + 1);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxYamlBytes) {
    throw InputError(file.string() + ": larger than " + std::to_string(kMaxYamlBytes) + " bytes, not a rig file");
  }
  return text;
}

[[noreturn]] void throw_layout_error(const std::string& name, int line_number, const std::string& what) {
  throw InputError(name + ": line " + std::to_string(line_number) + ": " + what +
                   " (rig files have the layout cv::FileStorage writes, docs/calibration.md#the-rig-file)");
}

// Throws unless `text` has the layout documented in opencv_yaml.h.
void check_layout(const std::string& text, const std::string& name) {
  static const std::regex directive(R"(%YAML[: ]1\.[0-9]+ *)");
  std::size_t line_start = 0;
  bool dashes_seen = false, keys_started = false;
  for (int line_number = 1; line_start < text.size(); ++line_number) {
    std::size_t line_end = text.find('\n', line_start);
    if (line_end == std::string::npos) line_end = text.size();
    std::string line = text.substr(line_start, line_end - line_start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    line_start = line_end + 1;
    const auto fail = [&](const std::string& what) { throw_layout_error(name, line_number, what); };
    // OpenCV skips a comment unread, so only the text before it must be printable ASCII ("# Jörg" is fine).
    const std::string text_before_comment = line.substr(0, line.find('#'));
    for (const char c : text_before_comment) {
      if (c < ' ' || c > '~') fail(c == '\t' ? "a tab" : "a byte that is not printable ASCII outside a comment");
    }
    if (line_number == 1) {
      if (!std::regex_match(line, directive)) fail("the first line is not %YAML:1.0 (nor %YAML 1.x)");
      continue;
    }
    const std::size_t indent = line.find_first_not_of(' ');
    if (indent == std::string::npos || line[indent] == '#') continue;  // blank or a comment
    if (!keys_started && !dashes_seen && line.find_first_not_of(' ', 3) == std::string::npos &&
        line.rfind("---", 0) == 0) {
      dashes_seen = true;
      continue;
    }
    if (indent > 0) {
      if (!keys_started) fail("the first key is indented: keys start in the first column");
      continue;
    }
    const char first = line.front();
    if (first == '%') fail("a second directive");
    if (first != '_' && !std::isalnum(static_cast<unsigned char>(first))) {
      fail(std::string("'") + first + "' in the first column: one YAML document of keys is expected");
    }
    keys_started = true;
  }
}

}  // namespace

cv::FileStorage open_opencv_yaml(const std::filesystem::path& file) {
  const std::string name = file.string();
  const std::string text = read_text(file);
  check_layout(text, name);
  cv::FileStorage storage;
  try {
    storage.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  } catch (const cv::Exception& error) {
    throw InputError(name + ": not a readable OpenCV YAML file (" + error.err + ")");
  }
  if (!storage.isOpened()) throw InputError(name + ": not a readable OpenCV YAML file");
  return storage;
}

}  // namespace rfrecon
