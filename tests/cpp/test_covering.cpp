#include <gtest/gtest.h>

#include <random>

#include "covering.hpp"
#include "polygon.hpp"
#include "testutil.hpp"

using namespace plunge;

// Covering options by allowance and target coverage.
static CoveringOptions covering(double allowance, double minCoverage) {
  CoveringOptions o;
  o.allowance = allowance;
  o.minCoverage = minCoverage;
  return o;
}

TEST(Covering, AccessibleRegionOfARectangle) {
  const Region r({{0, 0}, {200, 0}, {200, 100}, {0, 100}}, {});
  // Shrunk by 0.5, opened by radius 3: the corners lose (4 - pi) r^2.
  const double expected = 199 * 99 - (4 - kPi) * 9;
  EXPECT_NEAR(poly::area(accessibleRegion(r, 3, 0.5)), expected, 0.05);
  EXPECT_NEAR(poly::area(allowedRegion(r, 0.5)), 199 * 99, 1e-6);
  EXPECT_TRUE(accessibleRegion(r, 60, 0.0).empty());  // a 120 mm tool fits nowhere
}

TEST(Covering, DelaunayClosedAndOpenTriangles) {
  // Three mutually touching circles: one closed triangle.
  const double h = std::sqrt(3.0) * 10;
  std::vector<PackedDisk> tri{{{0, 0}, 10, 10, 0}, {{20, 0}, 10, 10, 0}, {{10, h}, 10, 10, 0}};
  DelaunayGaps g = delaunayGaps(tri);
  ASSERT_EQ(g.triangles.size(), 1u);
  EXPECT_TRUE(g.triangles[0].closed);
  // Four circles on a square: the diagonal is open, both triangles merge into one gap.
  std::vector<PackedDisk> sq{{{0, 0}, 10, 10, 0}, {{20, 0}, 10, 10, 0}, {{20, 20}, 10, 10, 0}, {{0, 20.5}, 10, 10, 0}};
  g = delaunayGaps(sq);
  ASSERT_EQ(g.triangles.size(), 2u);
  EXPECT_FALSE(g.triangles[0].closed);
  EXPECT_FALSE(g.triangles[1].closed);
  ASSERT_EQ(g.groups.size(), 1u);
  EXPECT_EQ(g.groups[0].size(), 2u);
}

TEST(Covering, GapBetweenThreeTouchingCirclesGetsTheNextLargerTool) {
  // Thesis 4.2.3.2: the gap between three touching 20 mm circles is enclosed by a
  // circle of radius 20 / (2 sqrt 3) = 5.77, readjusted to the 6 mm radius tool.
  const Region region({{-100, -100}, {120, -100}, {120, 120}, {-100, 120}}, {});
  const double h = std::sqrt(3.0) * 10;
  std::vector<PackedDisk> tri{{{0, 0}, 10, 10, 0}, {{20, 0}, 10, 10, 0}, {{10, h}, 10, 10, 0}};
  const CoverResult res = coverRegion(region, {10, 6, 3}, tri, covering(0.0, 0.2));
  bool found = false;
  for (const CoverDisk& d : res.disks)
    if (d.stage == Stage::Gap && dist(d.center, {10, h / 3}) < 0.05) {
      found = true;
      EXPECT_EQ(d.radius, 6);
    }
  EXPECT_TRUE(found);
}

TEST(Covering, TiledSubtractionMatchesOneBoolean) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0, 300), r(2, 9);
  const Polygons area{{{0, 0}, {300, 0}, {300, 200}, {0, 200}}};
  std::vector<Circle> disks;
  for (int i = 0; i < 400; ++i) disks.push_back({{u(rng), u(rng) * 2 / 3}, r(rng)});
  const double tiled = poly::area(uncoveredRegion(area, disks));
  const double direct = poly::area(poly::subtract(area, poly::unionOfDisks(disks, 0.005)));
  EXPECT_NEAR(tiled, direct, 1e-6 * 300 * 200);
}

namespace {

// Coverage measured independently: finer disks, finer accessible region.
double measuredCoverage(const Region& region, double rMin, double allowance, const std::vector<CoverDisk>& disks) {
  const Polygons acc = poly::offset(poly::offset(region.polygons(), -(rMin + allowance), 0.0005), rMin, 0.0005);
  std::vector<Circle> cs;
  for (const CoverDisk& d : disks) cs.push_back({d.center, d.radius});
  const double a = poly::area(acc);
  return (a - poly::area(poly::subtract(acc, poly::unionOfDisks(cs, 0.0005)))) / a;
}

}  // namespace

TEST(Covering, RandomPocketsAreCoveredWithoutGouging) {
  std::mt19937 rng(77);
  const std::vector<double> radii{8, 5, 2};
  for (int trial = 0; trial < 10; ++trial) {
    const Loop outer = test::randomStar(rng, {0, 0}, 40, 85, 6 + rng() % 40);
    std::vector<Loop> islands;
    if (trial % 2) islands.push_back(test::randomStar(rng, {5, -3}, 8, 14, 7));
    const Region region(outer, islands);
    const double allowance = 0.25 * (trial % 3);
    PackingOptions po;
    po.allowance = allowance;
    const auto packed = packMaxHoleDegree(region, radii, po);
    const CoverResult res = coverRegion(region, radii, packed, covering(allowance, 0.996));
    std::vector<Loop> loops{outer};
    loops.insert(loops.end(), islands.begin(), islands.end());
    for (const CoverDisk& d : res.disks) {
      EXPECT_TRUE(test::bruteInside(loops, d.center));
      EXPECT_GE(test::bruteWallDistance(loops, d.center), d.radius + allowance - 1e-6) << "gouge in trial " << trial;
    }
    EXPECT_GE(res.coveredArea / res.accessibleArea, 0.996);
    EXPECT_GE(measuredCoverage(region, 2, allowance, res.disks), 0.995) << "trial " << trial;
    // No free-standing core of material: every uncovered piece worth a plunge
    // touches the edge of the accessible region.
    const Polygons acc = accessibleRegion(region, 2, allowance);
    const Polygons accEdge = poly::subtract(acc, poly::offset(acc, -0.01));
    for (const Polygons& piece : poly::components(res.uncovered)) {
      if (poly::area(piece) > 0.05 * 4) {
        EXPECT_GT(poly::area(poly::intersect(piece, accEdge)), 0.0) << "standing pin in trial " << trial;
      }
    }
  }
}

TEST(Covering, ThesisContactRatioAlsoReachesTheTarget) {
  const Region region({{0, 0}, {150, 0}, {150, 90}, {0, 90}}, {{{{60, 30}, {90, 30}, {75, 60}}}});
  const std::vector<double> radii{10, 6, 3};
  PackingOptions po;
  po.contactRatio = 1.0;  // disjoint disks, as in the thesis
  const auto packed = packMaxHoleDegree(region, radii, po);
  const CoverResult res = coverRegion(region, radii, packed, covering(0.0, 0.996));
  EXPECT_GE(measuredCoverage(region, 3, 0.0, res.disks), 0.995);
}

// Small pockets, a few tool diameters across: the covering once re-placed a disk
// forever when its ranked gain was a polygon artefact (60 x 40, radii 8 and 3).
// Every size must finish, reach the target, and need no more plunges than
// covering everything with the smallest tool would (interior plus one wall row).
TEST(Covering, SmallRectanglesFinishWithBoundedPlunges) {
  const std::vector<double> radii{8, 3};
  for (double w = 30; w <= 80; w += 10)
    for (double h = 20; h <= 50; h += 10) {
      const Region region({{0, 0}, {w, 0}, {w, h}, {0, h}}, {});
      const auto packed = packMaxHoleDegree(region, radii, {});
      const CoverResult res = coverRegion(region, radii, packed, covering(0.0, 0.996));
      EXPECT_GE(measuredCoverage(region, 3, 0.0, res.disks), 0.995) << w << " x " << h;
      const double bound = res.accessibleArea / (2.598 * 9) + 2 * (w + h) / 3;
      EXPECT_LE(static_cast<double>(res.disks.size()), bound) << w << " x " << h;
    }
}
