#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "cuts.hpp"
#include "engagement.hpp"
#include "plunge/error.hpp"
#include "heightfield.hpp"
#include "plunge/json.hpp"
#include "polygon.hpp"
#include "plunge/plan.hpp"
#include "testutil.hpp"

using namespace plunge;

namespace {

PlanInput pocket(double maxEngagement, bool centerCutting) {
  PlanInput in = test::rectanglePocket(140, 90);
  if (maxEngagement > 0) in.tools[0].maxEngagement = maxEngagement;  // 0: none
  if (!centerCutting) {
    in.tools[0].centerCutting = false;
    in.tools[0].coreDiameter = 6;
  }
  in.tools[1].diameter = 8;
  return in;
}

// The plan replayed on a fresh, finer height field and on circles: every
// plunge that is not a start meets at most the limit, and a non-centre-cutting
// core only cut stock.
void expectLimitsKept(const PlanInput& in, const Plan& p) {
  HeightField f({-15, -15}, {155, 105}, 0.2, 0.0);
  Cuts cuts(kEngagementSkin);
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
    } else if (t->maxEngagement) {
      EXPECT_LE(cuts.engagement({q.x, q.y}, c, q.z), *t->maxEngagement + 0.01) << q.x << " " << q.y;
    }
    if (!t->centerCutting) {
      EXPECT_TRUE(k.coreClear) << q.x << " " << q.y;
    }
    f.cut({q.x, q.y}, c, q.z);
    cuts.add({q.x, q.y}, c, q.z);
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
// (scallops aside), with rows no closer than the row bound's 0.87 D. So do
// offsets of a ring's contour; in a pocket with sharp corners and arms of
// unequal width, offsets leave gaps on the corners' diagonals and in the
// middle of the narrower arm, which the rings fill ("auto" keeps rows where
// that costs more). Every path, either way, can be entered from cut material:
// a chain of paths, each with a position within a step of the last, leads to
// it from the contour (a row ends at the contour, a loop has its bridge).
class GrowthPaths : public ::testing::TestWithParam<std::tuple<int, GrowthPattern>> {};

TEST_P(GrowthPaths, CoverWhatTheToolReachesAndAreEnteredFromTheContour) {
  const double r = 10, step = 5;
  const auto [shape, pattern] = GetParam();
  Polygons pocket = {{{0, 0}, {200, 0}, {200, 90}, {120, 90}, {120, 50}, {80, 50}, {80, 90}, {0, 90}}};
  if (shape == 1) {  // a ring around a round island
    pocket = {poly::disk({{0, 0}, 80}, 0.01), poly::disk({{0, 0}, 25}, 0.01)};
    std::reverse(pocket[1].begin(), pocket[1].end());
  }
  const Polygons centres = poly::offset(pocket, -r);
  const double spacing = pattern == GrowthPattern::Offsets ? loopSpacing(r, step) : rowSpacing(r, step);
  const std::vector<GrowthPath> paths = growthPaths(centres, step, step, spacing, pattern);
  std::vector<Circle> disks;
  size_t inner = 0;
  for (const GrowthPath& p : paths) {
    inner += !p.contour;
    EXPECT_TRUE(p.closed || !p.contour);
    for (size_t i = 0; i + 1 < p.at.size(); ++i) EXPECT_LE(dist(p.at[i], p.at[i + 1]), step + 1e-6);
    if (p.closed && !p.contour) {
      EXPECT_LE(dist(p.at.back(), p.at.front()), step + 1e-6);
    }
    for (Vec2 c : p.at) disks.push_back({c, r});
  }
  EXPECT_GT(inner, 0u);
  EXPECT_GE(spacing, 0.87 * 2 * r);
  const Polygons reach = poly::offset(centres, r);
  const double left = poly::area(poly::subtract(reach, poly::unionOfDisks(disks, 0.01)));
  const double inside = poly::area(poly::subtract(poly::offset(reach, -1.0), poly::unionOfDisks(disks, 0.01)));
  if (pattern == GrowthPattern::Rows || shape == 1) {
    EXPECT_LT(left, 0.01 * poly::area(reach)) << left;
    // Nothing far from the walls is left: only scallops within 1 mm of the reach's edge.
    EXPECT_LT(inside, 1.0);
  } else {
    EXPECT_GT(inside, 1.0);  // the gaps the comment above names, which the rings fill
    EXPECT_LT(left, 0.1 * poly::area(reach)) << left;
  }
  // Entered from the contour: a search over paths that meet within a step.
  auto meet = [&](const GrowthPath& a, const GrowthPath& b) {
    for (Vec2 p : a.at)
      for (Vec2 q : b.at)
        if (dist(p, q) <= step + 1e-6) return true;
    return false;
  };
  std::vector<bool> reached(paths.size(), false);
  std::vector<size_t> todo;
  for (size_t k = 0; k < paths.size(); ++k)
    if (paths[k].contour) {
      reached[k] = true;
      todo.push_back(k);
    }
  while (!todo.empty()) {
    const size_t k = todo.back();
    todo.pop_back();
    for (size_t q = 0; q < paths.size(); ++q)
      if (!reached[q] && meet(paths[k], paths[q])) {
        reached[q] = true;
        todo.push_back(q);
      }
  }
  for (size_t k = 0; k < paths.size(); ++k) EXPECT_TRUE(reached[k]) << "path " << k;
}

INSTANTIATE_TEST_SUITE_P(Engagement, GrowthPaths,
                         ::testing::Combine(::testing::Values(0, 1),
                                            ::testing::Values(GrowthPattern::Rows, GrowthPattern::Offsets)),
                         [](const auto& info) {
                           return std::string(std::get<0>(info.param) == 0 ? "UShape" : "Ring") +
                                  (std::get<1>(info.param) == GrowthPattern::Rows ? "Rows" : "Offsets");
                         });

// "auto" grows each limited tool along rows and along offsets and keeps the
// one with fewer plunges, a start counted twice. On the neck shape at 0.25 D
// the largest tool grows first, from the same stock either way: in "auto" its
// plunges are those of the cheaper pattern's plan, one for one. Each pattern
// keeps the limits.
TEST(Engagement, AutoKeepsTheCheaperPatternPerTool) {
  PlanInput in = planInputFromJson(test::readData("shapes/neck.json"));
  for (Tool& t : in.tools) t.maxEngagement = 0.25 * t.diameter;
  const int largest = in.tools.front().id;
  auto mine = [&](const Plan& p) {
    std::vector<Plunge> out;
    for (const Plunge& q : p.plunges)
      if (q.toolId == largest) out.push_back(q);
    return out;
  };
  auto cost = [](const std::vector<Plunge>& ps) {
    int n = 0;
    for (const Plunge& q : ps) n += 1 + q.start;
    return n;
  };
  std::map<GrowthPattern, std::vector<Plunge>> plunges;
  for (GrowthPattern g : {GrowthPattern::Rows, GrowthPattern::Offsets, GrowthPattern::Auto}) {
    in.engagement.pattern = g;
    const Plan p = plan(in);
    EXPECT_EQ(p.stats.overEngaged, 0);
    EXPECT_GT(p.stats.coreCoverage, 0.9999);
    plunges[g] = mine(p);
  }
  const int rows = cost(plunges[GrowthPattern::Rows]), offsets = cost(plunges[GrowthPattern::Offsets]);
  const std::vector<Plunge>& kept = plunges[offsets < rows ? GrowthPattern::Offsets : GrowthPattern::Rows];
  const std::vector<Plunge>& chosen = plunges[GrowthPattern::Auto];
  EXPECT_EQ(cost(chosen), std::min(rows, offsets));
  ASSERT_EQ(chosen.size(), kept.size());
  for (size_t i = 0; i < kept.size(); ++i) {
    EXPECT_EQ(chosen[i].x, kept[i].x);
    EXPECT_EQ(chosen[i].y, kept[i].y);
    EXPECT_EQ(chosen[i].z, kept[i].z);
  }
}
