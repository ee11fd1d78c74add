// Include resolution for embedded kernel sources.
#include "host/cl/kernel_sources.h"

#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

namespace rfrecon::cl {

std::string_view embedded_kernel_file(std::string_view path) {
  for (const auto& file : embedded_kernel_files()) {
    if (file.path == path) return file.text;
  }
  throw std::out_of_range("kernel source '" + std::string(path) + "' is not embedded in this build of rfrecon");
}

namespace {
void append_resolved(std::string_view path, std::set<std::string, std::less<>>& seen, std::string& out) {
  if (!seen.insert(std::string(path)).second) return;
  static const std::regex include_line(R"re(^\s*#\s*include\s*"([^"]+)"\s*$)re");
  std::istringstream lines{std::string(embedded_kernel_file(path))};
  std::string line;
  std::smatch match;
  while (std::getline(lines, line)) {
    if (std::regex_match(line, match, include_line)) {
      append_resolved(match[1].str(), seen, out);
    } else {
      out += line;
      out += '\n';
    }
  }
}
}  // namespace

std::string resolve_kernel_source(std::string_view path) {
  std::set<std::string, std::less<>> seen;
  std::string out;
  append_resolved(path, seen, out);
  return out;
}

}  // namespace rfrecon::cl
