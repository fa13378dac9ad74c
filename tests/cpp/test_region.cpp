#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "plunge/error.hpp"
#include "region.hpp"
#include "testutil.hpp"

using namespace plunge;
using ::testing::HasSubstr;

namespace {
const Loop kSquare{{0, 0}, {100, 0}, {100, 100}, {0, 100}};

std::string errorOf(const Loop& b, const std::vector<Loop>& islands = {}) {
  try {
    Region r(b, islands);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Region, OrientsLoopsWithMaterialOnTheLeft) {
  // Boundary given clockwise, island counter-clockwise: both get flipped.
  const Region r({{0, 0}, {0, 100}, {100, 100}, {100, 0}}, {{{40, 40}, {60, 40}, {60, 60}, {40, 60}}});
  EXPECT_GT(signedArea(r.loops()[0]), 0);
  EXPECT_LT(signedArea(r.loops()[1]), 0);
  EXPECT_DOUBLE_EQ(r.area(), 10000 - 400);
  for (const Segment& w : r.walls()) {
    const Vec2 mid = (w.a + w.b) * 0.5;
    const Vec2 probe = mid + leftNormal(w.b - w.a) * (1e-3 / norm(w.b - w.a));
    EXPECT_TRUE(r.contains(probe)) << "material must lie left of every wall";
  }
}

TEST(Region, ReflexVertices) {
  // L shape: one reflex corner of the boundary; a square island: four reflex corners.
  const Region r({{0, 0}, {100, 0}, {100, 50}, {50, 50}, {50, 100}, {0, 100}}, {{{10, 10}, {20, 10}, {20, 20}, {10, 20}}});
  int reflex = 0;
  for (const auto& v : r.vertices())
    if (v.reflex) {
      ++reflex;
      const bool expected = (v.p == Vec2{50, 50}) || (v.p.x >= 10 && v.p.x <= 20 && v.p.y >= 10 && v.p.y <= 20);
      EXPECT_TRUE(expected) << v.p.x << "," << v.p.y;
    }
  EXPECT_EQ(reflex, 5);
}

TEST(Region, QueriesMatchBruteForce) {
  std::mt19937 rng(11);
  const Loop outer = test::randomStar(rng, {0, 0}, 60, 100, 40);
  const std::vector<Loop> islands{test::circleLoop({10, 5}, 12, 30), test::randomStar(rng, {-25, -20}, 6, 10, 9)};
  const Region r(outer, islands);
  std::vector<Loop> all{outer};
  all.insert(all.end(), islands.begin(), islands.end());
  std::uniform_real_distribution<double> u(-110, 110);
  for (int i = 0; i < 3000; ++i) {
    const Vec2 p{u(rng), u(rng)};
    EXPECT_EQ(r.contains(p), test::bruteInside(all, p));
    const double d = test::bruteWallDistance(all, p);
    const double within = 15;
    const double got = r.wallDistance(p, within);
    if (d <= within)
      EXPECT_NEAR(got, d, 1e-12);
    else
      EXPECT_GT(got, within);
    EXPECT_EQ(r.diskFits(p, 5), test::bruteInside(all, p) && d >= 5 - 1e-9);
    // Far reach (a tool as large as the pocket): the nearest-box search.
    const double far = r.wallDistance(p, 500);
    EXPECT_NEAR(far, d, 1e-12);
    EXPECT_EQ(r.diskFits(p, 60), test::bruteInside(all, p) && d >= 60 - 1e-9);
    // The k nearest walls in reach: no wall left out is nearer than one kept.
    const std::vector<int> box = r.wallsNear(p, 30), near = r.nearestWallsNear(p, 30, 8);
    ASSERT_EQ(near.size(), std::min<size_t>(8, box.size()));
    double keptFarthest = 0.0, leftNearest = INFINITY;
    for (int w : box) {
      const double dw = distanceToSegment(r.walls()[w], p);
      if (std::find(near.begin(), near.end(), w) != near.end())
        keptFarthest = std::max(keptFarthest, dw);
      else
        leftNearest = std::min(leftNearest, dw);
    }
    EXPECT_LE(keptFarthest, leftNearest);
  }
}

TEST(Region, RejectsBadInput) {
  EXPECT_THAT(errorOf({{0, 0}, {1, 0}}), HasSubstr("at least 3 distinct points"));
  EXPECT_THAT(errorOf({{0, 0}, {1, 0}, {1, 0}, {0, 0}}), HasSubstr("at least 3 distinct points"));
  EXPECT_THAT(errorOf({{0, 0}, {1, 0}, {2, 0}}), HasSubstr("zero area"));
  EXPECT_THAT(errorOf({{0, 0}, {20, 0}, {20, 10}, {10, -5}, {0, 10}}), HasSubstr("self-intersecting"));
  EXPECT_THAT(errorOf({{0, 0}, {10, 10}, {10, 0}, {0, 10}}), HasSubstr("zero area"));  // bow tie
  EXPECT_THAT(errorOf({{0, 0}, {10, 0}, {10, 10}, {10, 5}, {0, 10}}), HasSubstr("self-intersecting"));
  EXPECT_THAT(errorOf({{0, 0}, {NAN, 0}, {1, 1}}), HasSubstr("finite"));
  EXPECT_THAT(errorOf({{0, 0}, {INFINITY, 0}, {1, 1}}), HasSubstr("finite"));
  EXPECT_THAT(errorOf(kSquare, {{{200, 200}, {210, 200}, {210, 210}}}), HasSubstr("island 1: lies outside the boundary"));
  EXPECT_THAT(errorOf(kSquare, {{{90, 50}, {110, 50}, {100, 60}}}), HasSubstr("island 1: crosses"));
  EXPECT_THAT(errorOf(kSquare, {{{10, 10}, {40, 10}, {40, 40}}, {{{30, 20}, {50, 20}, {50, 30}}}}), HasSubstr("overlap"));
  EXPECT_THAT(errorOf(kSquare, {{{10, 10}, {60, 10}, {60, 60}, {10, 60}}, {{{20, 20}, {30, 20}, {30, 30}}}}), HasSubstr("inside island"));
  EXPECT_THAT(errorOf(kSquare, {{{10, 10}, {20, 10}, {30, 10}}}), HasSubstr("island 1: has zero area"));
  EXPECT_EQ(errorOf(kSquare, {{{10, 10}, {20, 10}, {20, 20}}}), "");
}

TEST(Region, AcceptsClosingDuplicateAndRepeatedPoints) {
  const Region r({{0, 0}, {10, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}}, {});
  EXPECT_EQ(r.loops()[0].size(), 4u);
}
