// The entry rule per device and the parsing of entry lists.
#include "host/cl/entry_choice.h"

#include <stdexcept>
#include <utility>

#include "host/core/errors.h"

namespace rfrecon::cl {

namespace {
constexpr const char* kWords = "auto, ndrange, single, or one of ndrange / single per device separated by commas";

// Surrounding spaces dropped, as in `--devices`.
std::string without_surrounding_spaces(const std::string& text) {
  const auto first = text.find_first_not_of(' ');
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(' ') - first + 1);
}

KernelEntry parse_word(const std::string& word, const std::string& text) {
  if (word == "ndrange") return KernelEntry::kNdRange;
  if (word == "single") return KernelEntry::kSingleWorkItem;
  throw UsageError("kernel entry '" + text + "': '" + word + "' is not a kernel entry (expected " + kWords + ")");
}
}  // namespace

KernelEntry preferred_entry(const DeviceInfo& info) {
  const bool fpga = info.intel_fpga || info.xilinx_fpga || info.kind == DeviceKind::kAccelerator;
  return fpga ? KernelEntry::kSingleWorkItem : KernelEntry::kNdRange;
}

const char* entry_name(KernelEntry entry) { return entry == KernelEntry::kSingleWorkItem ? "single" : "ndrange"; }

EntryChoice::EntryChoice(KernelEntry entry) : mode_(Mode::kForced), entries_{entry} {}

EntryChoice::EntryChoice(std::vector<KernelEntry> per_device)
    : mode_(Mode::kPerDevice), entries_(std::move(per_device)) {}

EntryChoice EntryChoice::parse(const std::string& text) {
  const std::string whole = without_surrounding_spaces(text);
  if (whole == "auto") return EntryChoice();
  if (whole.find(',') == std::string::npos) return EntryChoice(parse_word(whole, text));
  std::vector<KernelEntry> per_device;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = whole.find(',', begin);
    per_device.push_back(parse_word(without_surrounding_spaces(whole.substr(begin, comma - begin)), text));
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return EntryChoice(std::move(per_device));
}

void EntryChoice::check_device_count(std::size_t devices) const {
  if (mode_ != Mode::kPerDevice || entries_.size() == devices) return;
  throw UsageError("kernel entry list '" + text() + "' names " + std::to_string(entries_.size()) + " entries for " +
                   std::to_string(devices) + " selected device" + (devices == 1 ? "" : "s") +
                   ": give one entry per device, in the order `rfrecon devices` lists them, or auto, ndrange or "
                   "single for all");
}

KernelEntry EntryChoice::entry_for(std::size_t position, const DeviceInfo& info) const {
  switch (mode_) {
    case Mode::kAuto:
      return preferred_entry(info);
    case Mode::kForced:
      return entries_.front();
    case Mode::kPerDevice:
      break;
  }
  if (position >= entries_.size()) {
    throw std::out_of_range("kernel entry list '" + text() + "' has no entry for device " + std::to_string(position));
  }
  return entries_[position];
}

std::vector<KernelEntry> EntryChoice::resolve(const std::vector<DeviceContext>& devices) const {
  check_device_count(devices.size());
  std::vector<KernelEntry> entries;
  for (std::size_t i = 0; i < devices.size(); ++i) entries.push_back(entry_for(i, devices[i].info()));
  return entries;
}

std::string EntryChoice::text() const {
  if (mode_ == Mode::kAuto) return "auto";
  std::string text;
  for (const auto entry : entries_) text += (text.empty() ? "" : ",") + std::string(entry_name(entry));
  return text;
}

}  // namespace rfrecon::cl
