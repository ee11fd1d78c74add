// The layout check of an OpenCV YAML file, then cv::FileStorage over the checked text.
#include "host/core/opencv_yaml.h"

#include <algorithm>
#include <cctype>
#include <regex>
#include <string>
#include <vector>

#include "host/core/errors.h"
#include "host/core/limits.h"

namespace rfrecon {

namespace {

[[noreturn]] void throw_layout_error(const std::string& name, int line_number, const std::string& what) {
  throw InputError(name + ": line " + std::to_string(line_number) + ": " + what +
                   " (rig files have the layout cv::FileStorage writes, docs/calibration.md#the-rig-file)");
}

// Calls `visit(line_number, line)` for each line of `text`, without its LF or CRLF.
template <typename Visit>
void for_each_line(const std::string& text, Visit visit) {
  std::size_t line_start = 0;
  for (int line_number = 1; line_start < text.size(); ++line_number) {
    std::size_t line_end = text.find('\n', line_start);
    if (line_end == std::string::npos) line_end = text.size();
    std::string line = text.substr(line_start, line_end - line_start);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    line_start = line_end + 1;
    visit(line_number, line);
  }
}

// Throws unless `text` has the layout documented in opencv_yaml.h.
void check_layout(const std::string& text, const std::string& name) {
  static const std::regex directive(R"(%YAML[: ]1\.[0-9]+ *)");
  bool dashes_seen = false, keys_started = false;
  for_each_line(text, [&](int line_number, const std::string& line) {
    const auto fail = [&](const std::string& what) { throw_layout_error(name, line_number, what); };
    // OpenCV skips a comment unread, so only the text before it must be printable ASCII ("# Jörg" is fine).
    const std::string text_before_comment = line.substr(0, line.find('#'));
    for (const char c : text_before_comment) {
      if (c < ' ' || c > '~') fail(c == '\t' ? "a tab" : "a byte that is not printable ASCII outside a comment");
    }
    if (line_number == 1) {
      if (!std::regex_match(line, directive)) fail("the first line is not %YAML:1.0 (nor %YAML 1.x)");
      return;
    }
    const std::size_t indent = line.find_first_not_of(' ');
    if (indent == std::string::npos || line[indent] == '#') return;  // blank or a comment
    if (!keys_started && !dashes_seen && line.find_first_not_of(' ', 3) == std::string::npos &&
        line.rfind("---", 0) == 0) {
      dashes_seen = true;
      return;
    }
    if (indent > 0) {
      if (!keys_started) fail("the first key is indented: keys start in the first column");
      return;
    }
    const char first = line.front();
    if (first == '%') fail("a second directive");
    if (first != '_' && !std::isalnum(static_cast<unsigned char>(first))) {
      fail(std::string("'") + first + "' in the first column: one YAML document of keys is expected");
    }
    keys_started = true;
  });
}

// Block collections that a line opens in OpenCV's parser: one per key (':') and one per '-' that does not start a
// number. Counted anywhere in the line, strings and comments included: an upper bound.
int block_openers(const std::string& line) {
  int openers = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char next = i + 1 < line.size() ? line[i + 1] : ' ';
    if (line[i] == ':' || (line[i] == '-' && !std::isdigit(static_cast<unsigned char>(next)) && next != '.')) {
      ++openers;
    }
  }
  return openers;
}

// Flow collections open after `line`, given `open` before it: every '[' and '{' counts (in a quoted string or a
// comment too), a ']' or '}' only outside them, never below zero; so the count is never below the parser's.
// `deepest` is the most open at any point of the line.
int flow_after(const std::string& line, int open, int& deepest) {
  char quote = 0;
  deepest = open;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '[' || c == '{') deepest = std::max(deepest, ++open);
    if (quote != 0) {
      if (c == '\\' && quote == '"') {
        ++i;  // an escaped character
      } else if (c == quote) {
        quote = 0;
      }
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '#') {
      for (const char rest : line.substr(i)) {
        if (rest == '[' || rest == '{') deepest = std::max(deepest, ++open);
      }
      break;
    } else if ((c == ']' || c == '}') && open > 0) {
      --open;
    }
  }
  return open;
}

// Throws when the text may nest deeper than kMaxNestingDepth: OpenCV's parser recurses once per level, and a line
// of brackets or dashes well under kMaxYamlBytes overflows the stack. A bound, not a parse: a block line nests one
// level inside the nearest less indented line plus its own openers, flow collections add what is open; a line in the
// first column (a top-level key) starts again, as the parser refuses a flow collection continued there.
void check_nesting(const std::string& text, const std::string& name) {
  struct BlockLine {
    std::size_t indent;
    int depth;  // the deepest block level the line opens
  };
  std::vector<BlockLine> parents;
  int flow = 0;
  for_each_line(text, [&](int line_number, const std::string& line) {
    const std::size_t indent = line.find_first_not_of(' ');
    if (line_number == 1 || indent == std::string::npos || line[indent] == '#' || line.rfind("---", 0) == 0) return;
    if (indent == 0) {
      parents.clear();
      flow = 0;
    }
    while (!parents.empty() && parents.back().indent >= indent) parents.pop_back();
    const int block = (parents.empty() ? 1 : parents.back().depth + 1) + block_openers(line);
    parents.push_back({indent, block});
    int deepest_flow = 0;
    flow = flow_after(line, flow, deepest_flow);
    if (block + deepest_flow > kMaxNestingDepth) {
      throw InputError(name + ": line " + std::to_string(line_number) + ": may nest deeper than " +
                       std::to_string(kMaxNestingDepth) + " levels, the limit (docs/formats.md#limits)");
    }
  });
}

}  // namespace

cv::FileStorage open_opencv_yaml(const std::filesystem::path& file) {
  const std::string name = file.string();
  const std::string text = read_input_file(file, kMaxYamlBytes, "a rig or camera YAML file");
  check_layout(text, name);
  check_nesting(text, name);
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
