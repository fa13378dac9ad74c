// Rest plunging (rest.hpp, material.hpp): the sweep of earlier moves against
// brute force, and plans that start from the material the operations before
// left.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "depth.hpp"
#include "material.hpp"
#include "plunge/plan.hpp"
#include "plunge/rest.hpp"
#include "testutil.hpp"

using namespace plunge;
using ::testing::HasSubstr;

namespace {

// Brute force: the cutter's surface over a cell's centre at its lowest along
// the move (sampled every 0.003 mm of it), or +inf where it passes beside it.
double bruteCentreCut(const MaterialGrid& g, size_t i, size_t j, const Cutter& c, const Move& m) {
  const Vec2 p{g.origin.x + (i + 0.5) * g.spacing, g.origin.y + (j + 0.5) * g.spacing};
  const int steps = 5000;
  double best = INFINITY;
  for (int k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    const Vec2 axis{m.x0 + t * (m.x1 - m.x0), m.y0 + t * (m.y1 - m.y0)};
    const double rho = dist(axis, p);
    if (rho <= c.radius + kRimTolerance)
      best = std::min(best, m.z0 + t * (m.z1 - m.z0) + cutterProfile(c, std::min(rho, c.radius)));
  }
  return best;
}

class Sweep : public testing::TestWithParam<Cutter> {};

}  // namespace

// Every cell is lowered to the cutter's surface over its centre at its
// lowest along the move, as brute force finds it.
TEST_P(Sweep, LowersEachCellToTheCutterSurfaceOverItsCentre) {
  const Cutter c = GetParam();
  const Move m{2.0, 3.0, -1.0, 14.0, 9.0, -4.0};  // a ramp
  MaterialGrid g = materialGrid({-5, -5}, 0.5, 50, 40, 0.0);
  sweep(g, c, {m});
  int lowered = 0;
  for (size_t j = 0; j < g.ny; ++j)
    for (size_t i = 0; i < g.nx; ++i) {
      const double top = g.top[j * g.nx + i];
      const double brute = std::min(0.0, bruteCentreCut(g, i, j, c, m));
      // The brute force errs by its step's rise (0.001 mm), the sweep's
      // sampling of a round nose by a quarter cell's.
      EXPECT_NEAR(top, brute, c.shape == CutterShape::Flat ? 2e-3 : 2e-2) << i << " " << j;
      lowered += top < 0.0;
    }
  EXPECT_GT(lowered, 200);
}

// Moves in order: a later move higher than an earlier one leaves its cut.
TEST(Sweep, KeepsTheDeepestOfSeveralMoves) {
  MaterialGrid g = materialGrid({0, 0}, 0.25, 80, 80, 0.0);
  const Cutter c{CutterShape::Flat, 3.0, 0.0};
  sweep(g, c, {{10, 10, 5, 10, 10, -6}, {10, 10, -6, 10, 10, 5}, {10, 10, -2, 15, 10, -2}});
  auto at = [&](double x, double y) {
    return g.top[static_cast<size_t>(y / 0.25) * g.nx + static_cast<size_t>(x / 0.25)];
  };
  EXPECT_DOUBLE_EQ(at(10.1, 10.1), -6.0);
  EXPECT_DOUBLE_EQ(at(14.1, 10.1), -2.0);
  EXPECT_DOUBLE_EQ(at(18.6, 10.1), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Shapes, Sweep,
                         testing::Values(Cutter{CutterShape::Flat, 5.0, 0.0}, Cutter{CutterShape::Ball, 5.0, 5.0},
                                         Cutter{CutterShape::Bull, 5.0, 2.0}));

TEST(Sweep, RefusesMovesThatAreNotNumbers) {
  MaterialGrid g = materialGrid({0, 0}, 1.0, 4, 4, 0.0);
  EXPECT_THROW(sweep(g, {CutterShape::Flat, 2.0, 0.0}, {{0, 0, NAN, 1, 1, -1}}), Error);
  EXPECT_THROW(sweep(g, {CutterShape::Flat, 0.0, 0.0}, {{0, 0, 0, 1, 1, -1}}), Error);
}

namespace {

// The 120 x 80 pocket (floor -12, flutes 5 mm) with the material an earlier
// operation left: the top `cleared` mm gone over [x0, x1] x the pocket.
PlanInput pocketAfter(double cleared, double x0 = -20, double x1 = 140) {
  PlanInput in = test::rectanglePocket();
  for (Tool& t : in.tools) t.fluteLength = 5.0;
  MaterialGrid g = materialGrid({-20, -20}, 0.5, 320, 240, in.topZ);
  const Cutter c{CutterShape::Flat, 10.0, 0.0};
  std::vector<Move> rows;
  for (double y = -10; y <= 90; y += 5) rows.push_back({x0, y, in.topZ - cleared, x1, y, in.topZ - cleared});
  sweep(g, c, rows);
  in.material = std::move(g);
  return in;
}

}  // namespace

// Without material the plan is the full-stock plan: the grid at top_z
// everywhere changes nothing.
TEST(RestPlan, MaterialAtTheTopIsTheFullStock) {
  PlanInput in = pocketAfter(0.0);
  const Plan rest = plan(in);
  in.material.reset();
  const Plan full = plan(in);
  ASSERT_EQ(rest.plunges.size(), full.plunges.size());
  for (size_t i = 0; i < rest.plunges.size(); ++i) {
    EXPECT_EQ(rest.plunges[i].approachZ, full.plunges[i].approachZ);
    EXPECT_EQ(rest.plunges[i].level, full.plunges[i].level);
  }
  EXPECT_EQ(rest.stats.airPlunges, 0);
  EXPECT_NEAR(rest.stats.volumeBefore, full.stats.volumeBefore, 1e-6);
}

// The top 7 mm of the 12 mm pocket gone: the same positions, fed from just
// above the material left, in one level of the 5 mm flutes instead of three,
// in less time; the volume before is what is left.
TEST(RestPlan, FeedsFromTheMaterialLeftAndCountsLevelsFromIt) {
  PlanInput in = pocketAfter(7.0);
  const Material material(in.material, in.topZ);
  const Plan rest = plan(in);
  in.material.reset();
  const Plan full = plan(in);
  EXPECT_EQ(full.stats.levels, 3);
  EXPECT_EQ(rest.stats.levels, 1);
  EXPECT_LT(rest.stats.estimatedMinutes, 0.8 * full.stats.estimatedMinutes);
  EXPECT_EQ(rest.stats.airPlunges, 0);
  EXPECT_LT(rest.stats.volumeBefore, 0.5 * full.stats.volumeRemoved);
  EXPECT_GE(rest.stats.coreCoverage, full.stats.coreCoverage - 1e-9);
  for (const Plunge& p : rest.plunges) {
    // The approach stays above the material under the tool, and below the
    // uncut top wherever the pocket was cleared under it.
    const double under = material.highest({p.x, p.y}, 0.5 * p.diameter);
    EXPECT_GE(p.approachZ, under) << p.x << " " << p.y;
    if (under < in.topZ - 6.0) {
      EXPECT_LT(p.approachZ, in.topZ - 4.0) << p.x << " " << p.y;
    }
  }
}

// The left half cleared to the floor: no plunge there (each would cut
// nothing), they count as covered, and every plunge made cuts material.
TEST(RestPlan, PlansNoPlungeInAir) {
  PlanInput in = pocketAfter(12.5, -20, 50);
  const Material material(in.material, in.topZ);
  const Plan rest = plan(in);
  in.material.reset();
  const Plan full = plan(in);
  EXPECT_GT(rest.stats.airPlunges, 5);
  EXPECT_LT(rest.plunges.size(), full.plunges.size());
  EXPECT_GE(rest.stats.coreCoverage, full.stats.coreCoverage - 1e-9);
  for (const Plunge& p : rest.plunges) {
    if (p.startHole) continue;
    EXPECT_TRUE(material.cutsAny({p.x, p.y}, {CutterShape::Flat, 0.5 * p.diameter, 0.0}, p.z)) << p.x << " " << p.y;
  }
}

TEST(RestPlan, RefusesABadGrid) {
  PlanInput in = pocketAfter(1.0);
  in.material->top.pop_back();
  EXPECT_NE(test::planError(in), "");
  in = pocketAfter(1.0);
  in.material->top[5] = NAN;
  EXPECT_THAT(test::planError(in), HasSubstr("material"));
}

// A plunge mill with an engagement limit after the left half of the pocket
// was cleared to the floor: the engagement counts only the material left, so
// the growth starts beside the cleared half (no start into solid needed
// there) and plans fewer plunges, each within its limit.
TEST(RestPlan, EngagementCountsOnlyTheMaterialLeft) {
  PlanInput in = pocketAfter(12.5, -20, 50);
  for (Tool& t : in.tools) t.maxEngagement = 0.3 * t.diameter;
  const Plan rest = plan(in);
  in.material.reset();
  const Plan full = plan(in);
  EXPECT_LT(rest.plunges.size(), full.plunges.size());
  EXPECT_EQ(rest.stats.overEngaged, 0);
  int starts = 0;
  for (const Plunge& p : rest.plunges) {
    starts += p.start;
    if (!p.start) {
      EXPECT_LE(p.engagement, 0.3 * p.diameter + 0.02) << p.x << " " << p.y;
    }
  }
  int fullStarts = 0;
  for (const Plunge& p : full.plunges) fullStarts += p.start;
  EXPECT_LE(starts, fullStarts);
}

// The automatic tool choice after the pocket was cleared to the floor but
// for a strip along its left wall: each set's estimate counts only the
// plunges that cut the strip, and the plan chosen is as fast as the best of
// its sets planned in full (within the estimate's 5 %). Every set keeps the
// library's smallest (the island's corners need it, selection.hpp).
TEST(RestPlan, ToolChoiceWeighsOnlyTheRest) {
  PlanInput in = pocketAfter(12.5, 20, 140);  // the strip 0 < x < 20 - 10 (the clearing tool's radius) left
  in.choice.automatic = true;
  in.choice.library = {{20, 1, 100}, {12, 2, 100}, {6, 3, 100}};
  for (Tool& t : in.choice.library) t.fluteLength = 5.0;
  in.tools.clear();
  const Plan chosen = plan(in);
  ASSERT_TRUE(chosen.selection);
  EXPECT_GT(chosen.stats.airPlunges, 0);
  double best = 1e300;
  for (const std::vector<double>& set : {std::vector<double>{20, 6}, {20, 12, 6}, {12, 6}, {6}}) {
    PlanInput one = in;
    one.choice.automatic = false;
    one.tools.clear();
    int id = 1;
    for (double d : set) {
      one.tools.push_back({d, id++, 100});
      one.tools.back().fluteLength = 5.0;
    }
    try {
      best = std::min(best, plan(one).stats.estimatedMinutes);
    } catch (const Error&) {  // a set that cannot plan the pocket
    }
  }
  EXPECT_LE(chosen.stats.estimatedMinutes, 1.05 * best);
}
