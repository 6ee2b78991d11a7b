// The wall encoding of contact tables (mechanics/model/PairIndex.h): j = -1 - wall, in every
// integer width the tables use, and the same numbers the result file stores.
#include <cstdint>

#include <gtest/gtest.h>

#include "mechanics/model/PairIndex.h"

using namespace tmdem::mechanics;

TEST(PairIndex, WallCodesAreMinusOneMinusTheWallIndex) {
  EXPECT_EQ(wall_code<std::int32_t>(0), -1);
  EXPECT_EQ(wall_code<std::int32_t>(5), -6);
  EXPECT_EQ(wall_code<std::int64_t>(0), -1);
  EXPECT_EQ(wall_code<std::int64_t>(7), -8);
  EXPECT_EQ(wall_code<int>(2), -3);
}

TEST(PairIndex, DecodesEveryWidthTheSameWay) {
  for (std::size_t w = 0; w < 4; ++w) {
    EXPECT_EQ(wall_index(wall_code<std::int32_t>(w)), w);
    EXPECT_EQ(wall_index(wall_code<std::int64_t>(w)), w);
    EXPECT_EQ(wall_index(wall_code<int>(w)), w);
    EXPECT_TRUE(is_wall(wall_code<std::int64_t>(w)));
  }
  EXPECT_FALSE(is_wall(std::int32_t{0}));  // particle 0 is not a wall
  EXPECT_FALSE(is_wall(std::int64_t{12}));
}
