#include <gtest/gtest.h>

#include "polygon.hpp"

using namespace plunge;

TEST(Polygon, AreaOffsetBooleans) {
  const Polygons sq{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}};
  EXPECT_NEAR(poly::area(sq), 100, 1e-9);
  EXPECT_NEAR(poly::area(poly::offset(sq, -1)), 64, 1e-6);
  // Round outward offset: 100 + 4*10*1 + pi*1^2, chords slightly inside the arcs.
  const double grown = poly::area(poly::offset(sq, 1));
  EXPECT_LT(grown, 140 + kPi);
  EXPECT_GT(grown, 140 + kPi - 0.01);
  const Polygons other{{{5, 5}, {15, 5}, {15, 15}, {5, 15}}};
  EXPECT_NEAR(poly::area(poly::unite(sq, other)), 175, 1e-6);
  EXPECT_NEAR(poly::area(poly::intersect(sq, other)), 25, 1e-6);
  EXPECT_NEAR(poly::area(poly::subtract(sq, other)), 75, 1e-6);
}

TEST(Polygon, DiskIsInscribedWithinChordError) {
  const Circle c{{3, 4}, 7};
  const Loop d = poly::disk(c, 0.002);
  double minR = INFINITY;
  for (const Vec2& p : d) {
    EXPECT_LE(dist(p, c.c), c.r + 1e-5);
    minR = std::min(minR, dist(p, c.c));
  }
  EXPECT_GT(minR, c.r - 1e-5);
  EXPECT_LT(poly::area({d}), kPi * 49);
  EXPECT_GT(poly::area({d}), kPi * 49 - 2 * kPi * 7 * 0.002);
}

TEST(Polygon, ComponentsKeepTheirHoles) {
  const Polygons p{{{0, 0}, {10, 0}, {10, 10}, {0, 10}},
                   {{2, 2}, {2, 8}, {8, 8}, {8, 2}},  // hole
                   {{4, 4}, {6, 4}, {6, 6}, {4, 6}},  // island inside the hole
                   {{20, 0}, {30, 0}, {30, 10}, {20, 10}}};
  const auto comps = poly::components(p);
  ASSERT_EQ(comps.size(), 3u);
  double total = 0;
  for (const Polygons& c : comps) total += poly::area(c);
  EXPECT_NEAR(total, 100 - 36 + 4 + 100, 1e-6);
}
