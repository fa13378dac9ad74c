#include <gtest/gtest.h>

#include <random>

#include "plunge/error.hpp"
#include "plunge/grid.hpp"
#include "plunge/polygon.hpp"
#include "testutil.hpp"

using namespace plunge;

TEST(Grid, DisksFitAndSpacingIsTheStep) {
  std::mt19937 rng(11);
  for (GridPattern pattern : {GridPattern::Square, GridPattern::Honeycomb}) {
    const Loop outer = test::randomStar(rng, {0, 0}, 40, 80, 24);
    const Region region(outer, {});
    GridOptions o;
    o.pattern = pattern;
    o.allowance = 0.4;
    const std::vector<double> radii{8, 3};
    const CoverResult res = gridPlacements(region, radii, o);
    ASSERT_FALSE(res.disks.empty());
    const double step = (pattern == GridPattern::Honeycomb ? std::sqrt(3.0) / 2 : std::sqrt(0.5)) * 16;
    for (const CoverDisk& d : res.disks) {
      EXPECT_GE(test::bruteWallDistance({outer}, d.center), d.radius + o.allowance - 1e-9);
      if (d.tool != 0) continue;
      double nearest = 1e9;
      for (const CoverDisk& e : res.disks)
        if (e.tool == 0 && &e != &d) nearest = std::min(nearest, dist(e.center, d.center));
      EXPECT_GT(nearest, step - 1e-9);  // never closer than the grid step
    }
    // The reported coverage is the measured one.
    std::vector<Circle> circles;
    for (const CoverDisk& d : res.disks) circles.push_back({d.center, d.radius});
    const Polygons acc = accessibleRegion(region, 3, o.allowance);
    const double left = poly::area(uncoveredRegion(acc, circles));
    EXPECT_NEAR(res.coveredArea, res.accessibleArea - left, 1e-6 * res.accessibleArea);
    EXPECT_GT(res.coveredArea / res.accessibleArea, 0.8);
  }
}

TEST(Grid, SmallerToolsOnlyWhereTheLargerLeftMaterial) {
  // A rectangle the large grid fills exactly: the small tool has nothing to add inside.
  const Region region({{0, 0}, {160, 0}, {160, 100}, {0, 100}}, {});
  GridOptions o;
  o.pattern = GridPattern::Square;
  o.step = 0.5;  // squares of half the diameter: the disks overlap everything but the wall cusps
  const CoverResult res = gridPlacements(region, {10, 2}, o);
  for (const CoverDisk& d : res.disks)
    if (d.tool == 1) {
      EXPECT_LT(test::bruteWallDistance({{{0, 0}, {160, 0}, {160, 100}, {0, 100}}}, d.center), 10.0);
    }
}

TEST(Grid, BadOptions) {
  const Region region({{0, 0}, {50, 0}, {50, 50}, {0, 50}}, {});
  GridOptions o;
  o.step = 1.5;
  EXPECT_THROW(gridPlacements(region, {5}, o), Error);
  o.step = -0.1;
  EXPECT_THROW(gridPlacements(region, {5}, o), Error);
  o.step = NAN;
  EXPECT_THROW(gridPlacements(region, {5}, o), Error);
}
