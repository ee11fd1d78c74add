// The entry rule per device (FPGA boards single work-item, CPUs and GPUs NDRange) and the `--entry` text: auto, one
// entry forced, one per device, and the errors for a bad word or a list whose length is not the device count.
#include "host/cl/entry_choice.h"

#include <gtest/gtest.h>

#include "host/core/errors.h"

namespace rfrecon::cl {
namespace {

DeviceInfo device(DeviceKind kind, bool intel_fpga = false, bool xilinx_fpga = false) {
  DeviceInfo info;
  info.kind = kind;
  info.intel_fpga = intel_fpga;
  info.xilinx_fpga = xilinx_fpga;
  return info;
}

const DeviceInfo kCpu = device(DeviceKind::kCpu);
const DeviceInfo kGpu = device(DeviceKind::kGpu);
const DeviceInfo kIntelBoard = device(DeviceKind::kAccelerator, true);  // aoc BSPs report an accelerator
const DeviceInfo kXilinxBoard = device(DeviceKind::kAccelerator, false, true);

std::string usage_error(const std::string& text, std::size_t devices) {
  try {
    EntryChoice::parse(text).check_device_count(devices);
  } catch (const UsageError& error) {
    return error.what();
  }
  return "(no UsageError)";
}

TEST(EntryChoiceTest, FpgaBoardsRunSingleWorkItemCpusAndGpusNdRange) {
  EXPECT_EQ(preferred_entry(kCpu), KernelEntry::kNdRange);
  EXPECT_EQ(preferred_entry(kGpu), KernelEntry::kNdRange);
  EXPECT_EQ(preferred_entry(device(DeviceKind::kOther)), KernelEntry::kNdRange);
  EXPECT_EQ(preferred_entry(kIntelBoard), KernelEntry::kSingleWorkItem);
  EXPECT_EQ(preferred_entry(kXilinxBoard), KernelEntry::kSingleWorkItem);
  // Each sign alone is enough: an FPGA platform whatever type its device reports, or an accelerator on any platform.
  EXPECT_EQ(preferred_entry(device(DeviceKind::kOther, true)), KernelEntry::kSingleWorkItem);
  EXPECT_EQ(preferred_entry(device(DeviceKind::kOther, false, true)), KernelEntry::kSingleWorkItem);
  EXPECT_EQ(preferred_entry(device(DeviceKind::kAccelerator)), KernelEntry::kSingleWorkItem);
}

TEST(EntryChoiceTest, AutoFollowsTheRuleOnEachDevice) {
  const EntryChoice choice;  // the default, and what "auto" parses to
  for (const auto& parsed : {choice, EntryChoice::parse("auto"), EntryChoice::parse(" auto ")}) {
    EXPECT_EQ(parsed.entry_for(0, kCpu), KernelEntry::kNdRange);
    EXPECT_EQ(parsed.entry_for(1, kIntelBoard), KernelEntry::kSingleWorkItem);
    EXPECT_EQ(parsed.entry_for(2, kGpu), KernelEntry::kNdRange);
    EXPECT_NO_THROW(parsed.check_device_count(3));
    EXPECT_EQ(parsed.text(), "auto");
  }
}

TEST(EntryChoiceTest, OneWordForcesEveryDevice) {
  for (const auto& [text, entry] :
       {std::pair{"ndrange", KernelEntry::kNdRange}, std::pair{"single", KernelEntry::kSingleWorkItem}}) {
    const auto choice = EntryChoice::parse(text);
    for (const auto& info : {kCpu, kGpu, kIntelBoard, kXilinxBoard}) EXPECT_EQ(choice.entry_for(5, info), entry);
    EXPECT_NO_THROW(choice.check_device_count(1));
    EXPECT_NO_THROW(choice.check_device_count(4));
    EXPECT_EQ(choice.text(), text);
    // A KernelEntry converts to the choice that forces it.
    const EntryChoice forced = entry;
    EXPECT_EQ(forced.entry_for(0, kIntelBoard), entry);
  }
}

TEST(EntryChoiceTest, ListGivesOneEntryPerDeviceInOrderWhateverTheDevice) {
  const auto choice = EntryChoice::parse("single, ndrange,single");
  EXPECT_EQ(choice.entry_for(0, kCpu), KernelEntry::kSingleWorkItem);  // the list overrides the rule
  EXPECT_EQ(choice.entry_for(1, kIntelBoard), KernelEntry::kNdRange);
  EXPECT_EQ(choice.entry_for(2, kGpu), KernelEntry::kSingleWorkItem);
  EXPECT_NO_THROW(choice.check_device_count(3));
  EXPECT_EQ(choice.text(), "single,ndrange,single");
  const EntryChoice built({KernelEntry::kSingleWorkItem, KernelEntry::kNdRange});
  EXPECT_EQ(built.text(), "single,ndrange");
  EXPECT_EQ(built.entry_for(1, kXilinxBoard), KernelEntry::kNdRange);
  EXPECT_THROW(built.entry_for(2, kCpu), std::out_of_range);
}

TEST(EntryChoiceTest, ListOfAnotherLengthThanTheDevicesIsAUsageErrorNamingBothCounts) {
  EXPECT_EQ(usage_error("single,ndrange", 2), "(no UsageError)");
  const std::string three = usage_error("single,ndrange", 3);
  EXPECT_NE(three.find("'single,ndrange' names 2 entries for 3 selected devices"), std::string::npos) << three;
  const std::string one = usage_error("single,ndrange,ndrange", 1);
  EXPECT_NE(one.find("3 entries for 1 selected device:"), std::string::npos) << one;
}

TEST(EntryChoiceTest, WordsThatAreNoEntryAreUsageErrorsQuotingThem) {
  for (const auto& [text, word] :
       {std::pair{"fast", "'fast'"}, std::pair{"", "''"}, std::pair{"NDRange", "'NDRange'"},
        std::pair{"single,,ndrange", "''"}, std::pair{"single,auto", "'auto'"}, std::pair{"ndrange,", "''"}}) {
    std::string message = "(no UsageError)";
    try {
      EntryChoice::parse(text);
    } catch (const UsageError& error) {
      message = error.what();
    }
    EXPECT_NE(message.find(std::string(word) + " is not a kernel entry"), std::string::npos) << text << ": " << message;
  }
}

}  // namespace
}  // namespace rfrecon::cl
