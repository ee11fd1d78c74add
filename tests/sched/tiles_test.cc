// split_rows: every row in exactly one block, blocks contiguous and balanced.
#include <gtest/gtest.h>

#include "host/sched/scheduler.h"

namespace rfrecon::sched {
namespace {

TEST(SplitRowsTest, CoversEveryRowOnceWithBalancedBlocks) {
  for (const std::size_t rows : {0u, 1u, 7u, 100u, 1024u}) {
    for (const std::size_t tiles : {1u, 3u, 8u, 200u}) {
      SCOPED_TRACE(std::to_string(rows) + " rows, " + std::to_string(tiles) + " tiles");
      const auto blocks = split_rows(rows, tiles);
      std::size_t next = 0;
      std::size_t smallest = rows;
      std::size_t largest = 0;
      for (const auto& block : blocks) {
        EXPECT_EQ(block.begin, next);  // contiguous, in order: each row once
        EXPECT_GT(block.size(), 0u);
        smallest = std::min(smallest, block.size());
        largest = std::max(largest, block.size());
        next = block.end;
      }
      EXPECT_EQ(next, rows);
      EXPECT_EQ(blocks.size(), std::min(rows, tiles));
      if (!blocks.empty()) {
        EXPECT_LE(largest - smallest, 1u);
      }
    }
  }
}

}  // namespace
}  // namespace rfrecon::sched
