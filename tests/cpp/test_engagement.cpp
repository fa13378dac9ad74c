#include <gtest/gtest.h>

#include "plunge/engagement.hpp"
#include "plunge/error.hpp"
#include "plunge/heightfield.hpp"
#include "plunge/plan.hpp"
#include "testutil.hpp"

using namespace plunge;

namespace {

PlanInput pocket(double maxEngagement, bool centerCutting) {
  PlanInput in = test::rectanglePocket(140, 90);
  in.tools[0].maxEngagement = maxEngagement;
  if (!centerCutting) {
    in.tools[0].centerCutting = false;
    in.tools[0].coreDiameter = 6;
  }
  in.tools[1].diameter = 8;
  return in;
}

// The plan replayed on a fresh, finer height field: every plunge that is not a
// start meets at most the limit, and a non-centre-cutting core only cut stock.
void expectLimitsKept(const PlanInput& in, const Plan& p) {
  HeightField f({-15, -15}, {155, 105}, 0.2, 0.0);
  int starts = 0;
  for (const Plunge& q : p.plunges) {
    const Tool* t = nullptr;
    for (const Tool& u : in.tools)
      if (u.id == q.toolId) t = &u;
    ASSERT_NE(t, nullptr);
    const Cutter c = cutterOf(*t);
    const HeightField::Contact k = f.contact({q.x, q.y}, c, q.z, t->centerCutting ? 0.0 : 0.5 * t->coreDiameter);
    if (q.start) {
      ++starts;
    } else if (t->maxEngagement > 0) {
      EXPECT_LE(k.engagement, t->maxEngagement + 0.5) << q.x << " " << q.y;
    }
    if (!t->centerCutting) {
      EXPECT_TRUE(k.coreClear) << q.x << " " << q.y;
    }
    f.cut({q.x, q.y}, c, q.z);
  }
  EXPECT_GE(starts, 1);
  EXPECT_EQ(p.stats.overEngaged, 0);
}

}  // namespace

TEST(Engagement, LimitedPlungesGrowFromAStartWithinTheirBand) {
  const PlanInput in = pocket(5.0, true);
  const Plan p = plan(in);
  expectLimitsKept(in, p);
  // More plunges than the unlimited plan, the core still cut.
  EXPECT_GT(p.stats.plungeCount, plan(pocket(0.0, true)).stats.plungeCount);
  EXPECT_GT(p.stats.coreCoverage, 0.9999);
}

TEST(Engagement, NonCentreCuttingToolsStartOnDrilledHoles) {
  const PlanInput in = pocket(8.0, false);
  const Plan p = plan(in);
  expectLimitsKept(in, p);
  ASSERT_GE(p.stats.startHoles, 1);
  // The holes come first, by the centre-cutting tool, at a start of the cutter.
  for (int i = 0; i < p.stats.startHoles; ++i) {
    EXPECT_TRUE(p.plunges[i].startHole);
    EXPECT_EQ(p.plunges[i].toolId, 2);
    bool started = false;
    for (const Plunge& q : p.plunges)
      started |= q.toolId == 1 && q.start && q.x == p.plunges[i].x && q.y == p.plunges[i].y;
    EXPECT_TRUE(started);
  }
}

TEST(Engagement, LimitFromTheCore) {
  Tool t{25, 1, 100};
  EXPECT_TRUE(std::isinf(engagementLimit(t)));
  t.centerCutting = false;
  t.coreDiameter = 9;
  EXPECT_DOUBLE_EQ(engagementLimit(t), 8.0);
  t.maxEngagement = 5;
  EXPECT_DOUBLE_EQ(engagementLimit(t), 5.0);
}

TEST(Engagement, StartHolesNeedACentreCuttingToolAsWideAsTheCore) {
  Tool cutter{25, 1, 100};
  cutter.centerCutting = false;
  cutter.coreDiameter = 10;
  EXPECT_THROW(startHoleTool({cutter, {8, 2, 100}}, cutter), Error);
  EXPECT_EQ(startHoleTool({cutter, {16, 3, 100}, {12, 2, 100}, {8, 4, 100}}, cutter).id, 2);
}
