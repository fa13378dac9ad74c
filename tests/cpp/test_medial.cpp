#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "medial.hpp"
#include "polygon.hpp"
#include "testutil.hpp"

using namespace plunge;

namespace {

// Two squares joined by a corridor: the neck a machinist would name.
Region dumbbell(double corridor) {
  const double h = corridor / 2;
  return Region({{0, 0}, {60, 0}, {60, 30 - h}, {100, 30 - h}, {100, 0}, {160, 0}, {160, 60}, {100, 60},
                 {100, 30 + h}, {60, 30 + h}, {60, 60}, {0, 60}},
                {});
}

}  // namespace

TEST(Medial, AxisNodesAreInsideWithTheirTrueClearance) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 8; ++trial) {
    const Loop outer = test::randomStar(rng, {0, 0}, 30, 70, 8 + rng() % 30);
    std::vector<Loop> islands;
    if (trial % 2) islands.push_back(test::randomStar(rng, {4, -2}, 6, 10, 7));
    const Region region(outer, islands);
    std::vector<Loop> loops{outer};
    loops.insert(loops.end(), islands.begin(), islands.end());
    const MedialAxis axis = medialAxis(region);
    ASSERT_GT(axis.edges.size(), 3u);
    for (size_t i = 0; i < axis.nodes.size(); ++i) {
      if (axis.radius[i] > 1e-3) {
        EXPECT_TRUE(test::bruteInside(loops, axis.nodes[i])) << axis.radius[i] << " at " << axis.nodes[i].x << " " << axis.nodes[i].y;
      }
      EXPECT_NEAR(axis.radius[i], test::bruteWallDistance(loops, axis.nodes[i]), 1e-6);  // corners: on the wall
    }
    // The largest inscribed circle against a dense grid search (brute force).
    const Circle lic = largestInscribedCircle(axis);
    double brute = 0.0;
    for (double x = -70; x <= 70; x += 0.5)
      for (double y = -70; y <= 70; y += 0.5)
        if (test::bruteInside(loops, {x, y})) brute = std::max(brute, test::bruteWallDistance(loops, {x, y}));
    EXPECT_GE(lic.r, brute - 1e-6) << "trial " << trial;
    EXPECT_LE(lic.r, brute + 0.36) << "trial " << trial;  // grid step 0.5: within half a diagonal
  }
}

TEST(Medial, DumbbellHasOneNeckAndTwoRooms) {
  const Region region = dumbbell(16);
  const MedialAxis axis = medialAxis(region);
  EXPECT_NEAR(largestInscribedCircle(axis).r, 30.0, 1e-6);
  const std::vector<Neck> necks = findNecks(region, axis);
  ASSERT_GE(necks.size(), 1u);
  for (const Neck& n : necks) {
    EXPECT_NEAR(n.width, 16.0, 1e-6);
    EXPECT_GT(n.center.x, 60.0 - 1e-6);
    EXPECT_LT(n.center.x, 100.0 + 1e-6);
    EXPECT_FALSE(n.island);
  }
  const std::vector<SubRegion> parts = subdivide(region, axis, necks);
  ASSERT_GE(parts.size(), 2u);
  // The two rooms are the two largest parts, each with its own 60 mm circle.
  EXPECT_NEAR(parts[0].inscribed.r, 30.0, 1e-6);
  EXPECT_NEAR(parts[1].inscribed.r, 30.0, 1e-6);
  EXPECT_GT(std::abs(parts[0].inscribed.c.x - parts[1].inscribed.c.x), 90.0);
  double total = 0.0;
  for (const SubRegion& p : parts) total += p.area;
  EXPECT_NEAR(total, region.area() - 0.01 * 16 * necks.size(), 1e-3);  // minus the saw cuts (0.01 mm)
  // Sub-region order: a permutation starting with the room nearest the start.
  const std::vector<int> order = subRegionOrder(parts, {150, 30});
  ASSERT_EQ(order.size(), parts.size());
  EXPECT_GT(parts[order[0]].inscribed.c.x, 100.0);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < sorted.size(); ++i) EXPECT_EQ(sorted[i], static_cast<int>(i));
}

TEST(Medial, NoNeckInAConvexPocketOrAWideCorridor) {
  const Region square({{0, 0}, {80, 0}, {80, 50}, {0, 50}}, {});
  EXPECT_TRUE(findNecks(square, medialAxis(square)).empty());
  const Region wide = dumbbell(56);  // the corridor is nearly as wide as the rooms
  EXPECT_TRUE(findNecks(wide, medialAxis(wide)).empty());
}

TEST(Medial, IslandNecks) {
  // An island near the left wall: a narrow gap there, wide room elsewhere.
  const Region region({{0, 0}, {120, 0}, {120, 80}, {0, 80}}, {{{10, 25}, {40, 25}, {40, 55}, {10, 55}}});
  const MedialAxis axis = medialAxis(region);
  const std::vector<Neck> necks = findNecks(region, axis);
  ASSERT_FALSE(necks.empty());
  bool gap = false;
  for (const Neck& n : necks) {
    EXPECT_TRUE(n.island);
    if (std::abs(n.width - 10.0) < 1e-6 && n.center.x < 10) gap = true;
  }
  EXPECT_TRUE(gap);  // the 10 mm gap between the island and the left wall
}
