// Include resolution for embedded kernel sources.
#include "host/cl/kernel_sources.h"

#include <algorithm>
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
// The path of a `#include "path"` line, or an empty view for any other line.
std::string_view quoted_include(std::string_view line) {
  const auto skip_blanks = [&line] { line.remove_prefix(std::min(line.find_first_not_of(" \t"), line.size())); };
  skip_blanks();
  if (line.empty() || line.front() != '#') return {};
  line.remove_prefix(1);
  skip_blanks();
  constexpr std::string_view kInclude = "include";
  if (line.substr(0, kInclude.size()) != kInclude) return {};
  line.remove_prefix(kInclude.size());
  skip_blanks();
  if (line.empty() || line.front() != '"') return {};
  const auto close = line.find('"', 1);
  return close == std::string_view::npos ? std::string_view{} : line.substr(1, close - 1);
}

// Inlines path's text and its includes, recursively. `open` holds the files being inlined: a file that includes
// itself through a cycle is not inlined again; any other include is, as the preprocessor does (the headers' include
// guards then keep them single, and the unguarded *_rows.h of kernels/depth/ are instantiated once per include).
void append_resolved(std::string_view path, std::set<std::string, std::less<>>& open, std::string& out) {
  if (!open.insert(std::string(path)).second) return;
  std::istringstream lines{std::string(embedded_kernel_file(path))};
  std::string line;
  while (std::getline(lines, line)) {
    if (const auto included = quoted_include(line); !included.empty()) {
      append_resolved(included, open, out);
    } else {
      out += line;
      out += '\n';
    }
  }
  open.erase(open.find(path));
}
}  // namespace

std::string resolve_kernel_source(std::string_view path) {
  std::set<std::string, std::less<>> open;
  std::string out;
  append_resolved(path, open, out);
  return out;
}

}  // namespace rfrecon::cl
