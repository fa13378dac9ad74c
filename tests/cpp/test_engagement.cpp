#include <gtest/gtest.h>

#include "plunge/engagement.hpp"
#include "plunge/error.hpp"
#include "plunge/heightfield.hpp"
#include "plunge/polygon.hpp"
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

// The contour and rows a limited tool grows along cut everything its centres
// reach: disks on every position cover the centre region grown by the radius
// (scallops aside), with rows no closer than the row bound's 0.87 D.
TEST(Engagement, GrowthPathsCoverWhatTheToolReaches) {
  const double r = 10, step = 5;
  const Polygons centres = poly::offset({{{0, 0}, {200, 0}, {200, 90}, {120, 90}, {120, 50}, {80, 50}, {80, 90},
                                         {0, 90}}},
                                        -r);
  const std::vector<GrowthPath> paths = growthPaths(centres, step, step, rowSpacing(r, step));
  std::vector<Circle> disks;
  size_t rows = 0;
  for (const GrowthPath& p : paths) {
    rows += !p.closed;
    for (size_t i = 0; i + 1 < p.at.size(); ++i) EXPECT_LE(dist(p.at[i], p.at[i + 1]), step + 1e-6);
    for (Vec2 c : p.at) disks.push_back({c, r});
  }
  EXPECT_GT(rows, 0u);
  EXPECT_GE(rowSpacing(r, step), 0.87 * 2 * r);
  const Polygons reach = poly::offset(centres, r);
  const double left = poly::area(poly::subtract(reach, poly::unionOfDisks(disks, 0.01)));
  EXPECT_LT(left, 0.01 * poly::area(reach)) << left;
  // Nothing far from the walls is left: only scallops within 1 mm of the reach's edge.
  EXPECT_LT(poly::area(poly::subtract(poly::offset(reach, -1.0), poly::unionOfDisks(disks, 0.01))), 1.0);
}
