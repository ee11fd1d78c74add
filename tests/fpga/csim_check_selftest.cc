// The access and dependence check finds what it is for (csim_check_probes.cc): a false dependence directive, a RAM
// read three times and a bundle read twice per iteration; a true directive, a struct array's fields and a wide word
// read in pieces (one beat), pass.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/fpga/csim_check.h"
#include "tests/fpga/csim_check_probes.h"

namespace rf_csim {
namespace {

// The one loop that ran, and its use of `memory`.
std::pair<LoopUse, MemoryUse> only_loop(const std::string& memory) {
  const auto loops = loop_uses();
  EXPECT_EQ(loops.size(), 1u);
  if (loops.empty()) return {};
  for (const auto& m : loops.front().memories) {
    if (m.memory == memory) return {loops.front(), m};
  }
  ADD_FAILURE() << "no memory " << memory << " in\n" << table(loops);
  return {loops.front(), {}};
}

const std::vector<float> kInput(80, 1.5f);

class CsimCheck : public testing::Test {
 protected:
  void SetUp() override { reset(); }
};

TEST_F(CsimCheck, TrueDependenceDistancePasses) {
  std::vector<float> out(8);
  probes::accumulate(kInput.data(), out.data(), 64, 8);
  const auto [loop, acc] = only_loop("acc");
  EXPECT_TRUE(loop.violations.empty()) << loop.violations.front();
  EXPECT_EQ(acc.shortest_distance, 8);
  EXPECT_EQ(acc.claimed_distance, 8);
  EXPECT_EQ(acc.reads, 1);
  EXPECT_EQ(acc.writes, 1);
  EXPECT_EQ(loop.initiation_interval(), 1);
  EXPECT_EQ(loop.iterations, 64);
  EXPECT_EQ(out[0], 8 * 1.5f);
}

TEST_F(CsimCheck, FalseDependenceDirectiveIsFound) {
  std::vector<float> out(8);
  probes::accumulate(kInput.data(), out.data(), 64, 16);
  const auto [loop, acc] = only_loop("acc");
  ASSERT_FALSE(loop.violations.empty());
  EXPECT_NE(loop.violations.front().find("8 apart where the loop claims 16"), std::string::npos)
      << loop.violations.front();
}

TEST_F(CsimCheck, FalseSafelenIsFoundOnEveryMemory) {
  std::vector<float> out(64);
  probes::prefix_sum(kInput.data(), out.data(), 64);
  const auto [loop, a] = only_loop("a");
  ASSERT_FALSE(loop.violations.empty());
  EXPECT_EQ(a.shortest_distance, 1);
  EXPECT_EQ(a.claimed_distance, 4);
}

TEST_F(CsimCheck, ThreeReadsOfOneRamNeedTwoClocks) {
  std::vector<float> out(64);
  probes::three_taps(kInput.data(), out.data(), 64);
  const auto [loop, r] = only_loop("r");
  EXPECT_EQ(r.reads, 3);
  EXPECT_EQ(r.initiation_interval(), 2);
  EXPECT_EQ(loop.initiation_interval(), 2);
}

TEST_F(CsimCheck, TwoReadsOfOneBundleNeedTwoClocks) {
  std::vector<float> out(40);
  probes::two_reads_one_bundle(kInput.data(), out.data(), 40);
  const auto [loop, x] = only_loop("gmem0");
  EXPECT_EQ(x.reads, 2);
  EXPECT_EQ(loop.initiation_interval(), 2);
}

TEST_F(CsimCheck, WideWordIsOneBeatAndItsFloatsAreSixteen) {
  const std::vector<probes::WideWord> words(8, probes::WideWord{{1.0f, 2.0f, 3.0f, 4.0f}});
  std::vector<float> out(8);
  probes::wide_word_sum(words.data(), out.data(), 8);
  const auto [loop, x] = only_loop("gmem0");
  EXPECT_EQ(x.reads, 1);
  EXPECT_EQ(loop.initiation_interval(), 1);
  EXPECT_EQ(out[0], 10.0f);
  // The same 16 floats read from a float argument are 16 beats.
  reset();
  std::vector<float> sums(4);
  probes::two_reads_one_bundle(reinterpret_cast<const float*>(words.data()), sums.data(), 4);
  EXPECT_EQ(only_loop("gmem0").second.reads, 2);
}

TEST_F(CsimCheck, StructArrayIsOneRamPerField) {
  std::vector<float> out(4);
  probes::struct_fields(kInput.data(), out.data(), 64);
  const auto [loop, sum] = only_loop("pairs+0");
  const auto [same_loop, product] = only_loop("pairs+4");
  EXPECT_TRUE(loop.violations.empty());
  EXPECT_EQ(sum.accesses, 2);
  EXPECT_EQ(product.accesses, 2);
  EXPECT_EQ(loop.initiation_interval(), 1);
}

}  // namespace
}  // namespace rf_csim
