// Parses device selection strings and matches them against the enumerated devices.
#include "host/cl/device_selection.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <set>

#include "host/cl/error.h"

namespace rfrecon::cl {

namespace {
std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

std::string trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return std::string(text.substr(first, last - first + 1));
}

bool is_index(const std::string& term) {
  return !term.empty() && std::all_of(term.begin(), term.end(), [](unsigned char c) { return std::isdigit(c); });
}

bool matches(const DeviceInfo& info, const std::string& term) {
  if (term == "all") return true;
  if (term == "cpu") return info.kind == DeviceKind::kCpu;
  if (term == "gpu") return info.kind == DeviceKind::kGpu;
  if (term == "fpga" || term == "accelerator") return info.kind == DeviceKind::kAccelerator;
  if (is_index(term)) return std::to_string(info.index) == term;
  return lower(info.platform_name + " " + info.device_name).find(term) != std::string::npos;
}

std::string listing(const std::vector<DeviceEntry>& available) {
  if (available.empty()) {
    return "no OpenCL device is installed (is an ICD such as pocl-opencl-icd present? see `rfrecon devices`)";
  }
  std::string text = "available devices:";
  for (const auto& entry : available) text += "\n  " + std::to_string(entry.info.index) + ": " + describe(entry.info);
  return text;
}
}  // namespace

std::vector<DeviceEntry> select_devices(const std::vector<DeviceEntry>& available, std::string_view selection) {
  if (available.empty()) throw DeviceSelectionError(listing(available));
  std::set<int> chosen;
  std::string rest(selection);
  std::size_t start = 0;
  while (start <= rest.size()) {
    const auto comma = rest.find(',', start);
    const std::string term = lower(trim(rest.substr(start, comma == std::string::npos ? comma : comma - start)));
    start = comma == std::string::npos ? rest.size() + 1 : comma + 1;
    if (term.empty()) throw DeviceSelectionError("empty term in device selection '" + rest + "'");
    bool any = false;
    for (const auto& entry : available) {
      if (matches(entry.info, term)) {
        chosen.insert(entry.info.index);
        any = true;
      }
    }
    if (!any) throw DeviceSelectionError("no OpenCL device matches '" + term + "'; " + listing(available));
  }
  std::vector<DeviceEntry> out;
  for (const auto& entry : available) {
    if (chosen.count(entry.info.index) != 0) out.push_back(entry);
  }
  return out;
}

std::string effective_selection(std::string_view flag) {
  if (!flag.empty()) return std::string(flag);
  if (const char* env = std::getenv(kDevicesEnv); env != nullptr && *env != '\0') return env;
  return "all";
}

std::vector<DeviceContext> open_devices(std::string_view flag) {
  std::vector<DeviceContext> contexts;
  for (const auto& entry : select_devices(enumerate_devices(), effective_selection(flag))) {
    contexts.emplace_back(entry);
  }
  return contexts;
}

}  // namespace rfrecon::cl
