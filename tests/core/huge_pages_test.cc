// Arrays filled on huge pages, or refilled on every core, hold exactly the count and value asked for, whatever they
// held before.
#include "host/core/huge_pages.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

namespace rfrecon {
namespace {

TEST(HugePagesTest, AssignedArraysHoldOnlyTheValueWhateverTheyHeldBefore) {
  for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{1000}, std::size_t{3} << 20}) {
    std::vector<std::int32_t> values(count / 2 + 7, 5);
    assign_on_huge_pages(values, count, -1);
    ASSERT_EQ(values.size(), count);
    EXPECT_TRUE(std::all_of(values.begin(), values.end(), [](std::int32_t v) { return v == -1; })) << count;
  }
}

TEST(HugePagesTest, ArraysOfTheSizeAskedForAreRefilledEntirely) {
  // Sizes below, at and past the 1 MiB blocks filled on every core, the last not a multiple of them.
  for (const std::size_t count : {std::size_t{1}, std::size_t{1} << 18, (std::size_t{3} << 20) + 5}) {
    std::vector<std::int32_t> values(count);
    for (std::size_t i = 0; i < count; ++i) values[i] = static_cast<std::int32_t>(i % 1000);
    assign_on_huge_pages(values, count, -1);
    ASSERT_EQ(values.size(), count);
    EXPECT_TRUE(std::all_of(values.begin(), values.end(), [](std::int32_t v) { return v == -1; })) << count;
  }
}

}  // namespace
}  // namespace rfrecon
