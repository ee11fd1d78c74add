// ScopedProgressObserver: every step of a Progress made on the observing thread, counts never going back, from any
// thread that advances it; the previous observer restored after.
#include <algorithm>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "host/core/progress.h"

namespace rfrecon {
namespace {

TEST(ProgressObserverTest, EveryStepFromEveryThreadInNonDecreasingOrder) {
  std::vector<ProgressStep> steps;  // the observer is called one at a time per Progress
  const ScopedProgressObserver observer([&](const ProgressStep& step) { steps.push_back(step); });
  constexpr std::size_t kThreads = 4, kEach = 250;
  Progress progress("work", kThreads * kEach, "items");
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < kThreads; ++t) {
    threads.emplace_back([&] {
      for (std::size_t i = 0; i < kEach; ++i) progress.advance();
    });
  }
  for (auto& thread : threads) thread.join();
  ASSERT_EQ(steps.size(), kThreads * kEach);
  EXPECT_TRUE(std::is_sorted(steps.begin(), steps.end(),
                             [](const ProgressStep& a, const ProgressStep& b) { return a.done < b.done; }));
  EXPECT_EQ(steps.back().done, kThreads * kEach);
  EXPECT_EQ(steps.back().total, kThreads * kEach);
  EXPECT_EQ(steps.back().label, "work");
  EXPECT_EQ(steps.back().unit, "items");
}

TEST(ProgressObserverTest, OnlyProgressMadeWhileTheObserverLivesOnItsThread) {
  int outer_calls = 0, inner_calls = 0;
  const ScopedProgressObserver outer([&](const ProgressStep&) { ++outer_calls; });
  {
    const ScopedProgressObserver inner([&](const ProgressStep&) { ++inner_calls; });
    Progress progress("inner", 2, "items");
    progress.advance(2);
    std::thread([] { Progress("another thread", 1, "items").advance(); }).join();  // no observer there
  }
  Progress progress("outer", 1, "items");
  progress.advance();
  EXPECT_EQ(inner_calls, 1);
  EXPECT_EQ(outer_calls, 1);
}

}  // namespace
}  // namespace rfrecon
