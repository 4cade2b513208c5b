// --shard I/N (app/learning_options.cpp): the CLI's syntax for a share of the views or trainings,
// turned into core's {index from 0, count}; errors name the flag.
#include <gtest/gtest.h>

#include "learning_options.h"
#include "support/error_of.h"

using keyturn::app::parseShard;
using keyturn::test::errorOf;

TEST(ShardOption, IOfNCountsFromOne) {
  EXPECT_EQ(parseShard("1/1"), (std::pair<int, int>{0, 1}));
  EXPECT_EQ(parseShard("3/16"), (std::pair<int, int>{2, 16}));
  EXPECT_EQ(parseShard("16/16"), (std::pair<int, int>{15, 16}));
}

TEST(ShardOption, AnythingElseNamesTheFlag) {
  EXPECT_EQ(errorOf([] { parseShard("3"); }), "--shard 3: expected I/N, e.g. 3/16");
  EXPECT_EQ(errorOf([] { parseShard("3/16x"); }), "--shard 3/16x: expected I/N, e.g. 3/16");
  EXPECT_EQ(errorOf([] { parseShard("3/2"); }), "--shard 3/2: expected I/N with 1 <= I <= N");
  EXPECT_EQ(errorOf([] { parseShard("0/2"); }), "--shard 0/2: expected I/N with 1 <= I <= N");
  EXPECT_EQ(errorOf([] { parseShard("1/0"); }), "--shard 1/0: expected I/N with 1 <= I <= N");
}
