// The fuzz target's judge (tests/fuzz/oracle.hpp), which shares no code with
// the planner: it passes the planner's plans and catches each kind of gouge.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "../fuzz/oracle.hpp"
#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "testutil.hpp"

using namespace plunge;
using ::testing::HasSubstr;

TEST(Oracle, PassesThePlannersPlansAndCatchesEachGouge) {
  const std::string text = test::smallJobJson();  // 100 x 60 box, island (40,20) (60,20) (50,40)
  const plunge_oracle::Pocket pocket(text);
  const Plan p = plan(planInputFromJson(text));
  ASSERT_FALSE(p.plunges.empty());
  for (const Plunge& q : p.plunges) EXPECT_EQ(pocket.gouge({q.x, q.y}, q.diameter, q.z), "") << q.x << " " << q.y;
  // 12 mm at 6.1 from the left wall: 0.1 mm short of radius + 0.2 allowance.
  EXPECT_THAT(pocket.gouge({6.1, 30}, 12, -9.9), HasSubstr("from a wall"));
  EXPECT_EQ(pocket.gouge({6.25, 30}, 12, -9.9), "");
  // Beside the island's slanted edge, and inside it.
  EXPECT_THAT(pocket.gouge({50, 45}, 12, -9.9), HasSubstr("from a wall"));
  EXPECT_THAT(pocket.gouge({50, 25}, 6, -9.9), HasSubstr("outside the pocket"));
  EXPECT_THAT(pocket.gouge({120, 30}, 6, -9.9), HasSubstr("outside the pocket"));
  // The floor at -10 with 0.1 mm of allowance.
  EXPECT_THAT(pocket.gouge({20, 30}, 12, -9.95), HasSubstr("below the floor"));
  EXPECT_EQ(pocket.gouge({20, 30}, 12, -9.9), "");
}
