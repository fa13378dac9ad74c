#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "plunge/error.hpp"
#include "grid.hpp"
#include "polygon.hpp"
#include "testutil.hpp"

using namespace plunge;

namespace {

std::vector<Circle> circlesOf(const CoverResult& res, int tool = -1) {
  std::vector<Circle> out;
  for (const CoverDisk& d : res.disks)
    if (tool < 0 || d.tool == tool) out.push_back({d.center, d.radius});
  return out;
}

}  // namespace

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
      // Inside the pocket, and the whole disk with its allowance clear of the walls.
      EXPECT_TRUE(test::bruteInside({outer}, d.center));
      EXPECT_GE(test::bruteWallDistance({outer}, d.center), d.radius + o.allowance - 1e-9);
      if (d.tool != 0) continue;
      double nearest = 1e9;
      for (const CoverDisk& e : res.disks)
        if (e.tool == 0 && &e != &d) nearest = std::min(nearest, dist(e.center, d.center));
      EXPECT_GT(nearest, step - 1e-9);  // never closer than the grid step
    }
    // The reported coverage is the measured one: with polygons, and on a raster
    // of the accessible region (brute force: a sample is cut when some disk holds it).
    const Polygons acc = accessibleRegion(region, 3, o.allowance);
    const Polygons left = uncoveredRegion(acc, circlesOf(res));
    EXPECT_NEAR(res.coveredArea, res.accessibleArea - poly::area(left), 1e-6 * res.accessibleArea);
    int inside = 0, cut = 0;
    for (double x = -80; x <= 80; x += 0.5)
      for (double y = -80; y <= 80; y += 0.5) {
        if (!test::bruteInside(acc, {x, y})) continue;
        ++inside;
        cut += std::any_of(res.disks.begin(), res.disks.end(),
                           [&](const CoverDisk& d) { return dist(d.center, {x, y}) <= d.radius; });
      }
    EXPECT_NEAR(static_cast<double>(cut) / inside, res.coveredArea / res.accessibleArea, 0.005);
    // What a grid reaches: its lattice covers the plane, so material stays only
    // where lattice points were dropped, within a large disk's reach of the walls
    // (and polygon slivers at the lattice's triple points, far below 0.01 mm^2).
    for (const Polygons& piece : poly::components(left)) {
      if (poly::area(piece) < 0.01) continue;
      for (const Vec2& p : piece.front())
        EXPECT_LE(test::bruteWallDistance({outer}, p), 2 * radii[0] + o.allowance + 1e-6);
    }
  }
}

TEST(Grid, SmallerToolsOnlyWhereTheLargerLeftMaterial) {
  // A rectangle the large grid fills but for the wall cusps and the corners:
  // the small tool plunges there, and only where it cuts what the large left.
  const Loop rect{{0, 0}, {160, 0}, {160, 100}, {0, 100}};
  const Region region(rect, {});
  GridOptions o;
  o.pattern = GridPattern::Square;
  o.step = 0.5;  // squares of half the diameter: the disks overlap everything but the wall cusps
  const CoverResult res = gridPlacements(region, {10, 2}, o);
  const std::vector<Circle> large = circlesOf(res, 0);
  ASSERT_FALSE(large.empty());
  int small = 0;
  for (const CoverDisk& d : res.disks) {
    if (d.tool != 1) continue;
    ++small;
    EXPECT_LT(test::bruteWallDistance({rect}, d.center), 10.0);
    const Polygons disk{test::circleLoop(d.center, d.radius, 64)};
    EXPECT_GE(poly::area(uncoveredRegion(disk, large)), o.minGain * kPi * d.radius * d.radius * 0.9);
  }
  EXPECT_GE(small, 4);  // at least the four corners the 20 mm plunger cannot reach
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
