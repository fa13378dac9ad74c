// Rest plunging (rest.hpp, material.hpp): the sweep of earlier moves against
// brute force, and plans that start from the material the operations before
// left.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "depth.hpp"
#include "material.hpp"
#include "plunge/plan.hpp"
#include "plunge/rest.hpp"
#include "testutil.hpp"

using namespace plunge;

namespace {

// Brute force: the highest point of the cutter's surface over a cell's square
// (sampled 7 x 7) at its lowest along the move (sampled every 0.02 mm), or
// +inf where the cutter does not cover the whole square.
double bruteCellCut(const MaterialGrid& g, size_t i, size_t j, const Cutter& c, const Move& m) {
  double worst = -INFINITY;
  const int n = 7, steps = 2000;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const Vec2 p{g.origin.x + (i + a / (n - 1.0)) * g.spacing, g.origin.y + (j + b / (n - 1.0)) * g.spacing};
      double best = INFINITY;
      for (int k = 0; k <= steps; ++k) {
        const double t = static_cast<double>(k) / steps;
        const Vec2 axis{m.x0 + t * (m.x1 - m.x0), m.y0 + t * (m.y1 - m.y0)};
        const double rho = dist(axis, p);
        if (rho <= c.radius) best = std::min(best, m.z0 + t * (m.z1 - m.z0) + cutterProfile(c, rho));
      }
      worst = std::max(worst, best);
    }
  return worst;
}

class Sweep : public testing::TestWithParam<Cutter> {};

}  // namespace

// Every cell stays at or above the cutter's surface over all of its square
// (an upper bound of the material), and within the surface's rise across one
// cell of it: the sweep removes what the cutter removes, to the raster.
TEST_P(Sweep, LowersEachCellToTheCutterSurfaceOverIt) {
  const Cutter c = GetParam();
  const Move m{2.0, 3.0, -1.0, 14.0, 9.0, -4.0};  // a ramp
  MaterialGrid g = materialGrid({-5, -5}, 0.5, 50, 40, 0.0);
  sweep(g, c, {m});
  int lowered = 0;
  double removed = 0.0, bruteRemoved = 0.0;
  for (size_t j = 0; j < g.ny; ++j)
    for (size_t i = 0; i < g.nx; ++i) {
      const double top = g.top[j * g.nx + i];
      const double brute = std::min(0.0, bruteCellCut(g, i, j, c, m));
      // Never below what the tool reached over all of the square (the brute
      // force's own sampling along the move errs by up to 0.002 mm).
      EXPECT_GE(top, brute - 3e-3) << i << " " << j;
      // Lowered wherever the tool cut it deeply, but for the rim's cells (the
      // sweep bounds a square's farthest point by its centre's distance plus
      // half its diagonal).
      const Vec2 centre{g.origin.x + (i + 0.5) * g.spacing, g.origin.y + (j + 0.5) * g.spacing};
      const double toAxis = distanceToSegment({{m.x0, m.y0}, {m.x1, m.y1}}, centre);
      if (brute < -0.5 && toAxis + 1.5 * g.spacing < c.radius) {
        EXPECT_LT(top, 0.0) << i << " " << j;
      }
      lowered += top < 0.0;
      removed -= top;
      bruteRemoved -= brute;
    }
  // The raster keeps most of what the tool cut (only the rise of its surface
  // across one cell is kept back).
  EXPECT_GT(removed, 0.8 * bruteRemoved);
  EXPECT_LE(removed, bruteRemoved + 1e-6 * g.nx * g.ny);
  EXPECT_GT(lowered, 100);
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
  EXPECT_NE(test::planError(in).find("material"), std::string::npos);
}
