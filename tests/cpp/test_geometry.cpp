#include <gtest/gtest.h>

#include <random>

#include "plunge/geometry.hpp"

using namespace plunge;

TEST(Geometry, ClosestPointOnSegment) {
  const Segment s{{0, 0}, {10, 0}};
  double t;
  Vec2 q = closestPointOnSegment(s, {3, 4}, &t);
  EXPECT_DOUBLE_EQ(q.x, 3);
  EXPECT_DOUBLE_EQ(q.y, 0);
  EXPECT_DOUBLE_EQ(t, 0.3);
  q = closestPointOnSegment(s, {-5, 1}, &t);
  EXPECT_DOUBLE_EQ(q.x, 0);
  EXPECT_DOUBLE_EQ(t, 0);
  EXPECT_DOUBLE_EQ(distanceToSegment(s, {13, 4}), 5);
}

TEST(Geometry, SegmentsIntersect) {
  EXPECT_TRUE(segmentsIntersect({{0, 0}, {2, 2}}, {{0, 2}, {2, 0}}));
  EXPECT_FALSE(segmentsIntersect({{0, 0}, {1, 1}}, {{2, 0}, {3, 1}}));
  EXPECT_TRUE(segmentsIntersect({{0, 0}, {2, 0}}, {{1, 0}, {3, 0}}));  // collinear overlap
  EXPECT_TRUE(segmentsIntersect({{0, 0}, {2, 0}}, {{2, 0}, {3, 1}}));  // shared end
  EXPECT_FALSE(segmentsIntersect({{0, 0}, {2, 0}}, {{0, 1}, {2, 1}}));
}

TEST(Geometry, CircleIntersectionsAreOnBothCircles) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-10, 10), r(0.5, 8);
  int found = 0;
  for (int i = 0; i < 500; ++i) {
    const Circle a{{u(rng), u(rng)}, r(rng)}, b{{u(rng), u(rng)}, r(rng)};
    for (const Vec2& p : intersectCircles(a, b)) {
      EXPECT_NEAR(dist(p, a.c), a.r, 1e-9);
      EXPECT_NEAR(dist(p, b.c), b.r, 1e-9);
      ++found;
    }
  }
  EXPECT_GT(found, 100);
  EXPECT_TRUE(intersectCircles({{0, 0}, 1}, {{5, 0}, 1}).empty());
  EXPECT_TRUE(intersectCircles({{0, 0}, 5}, {{1, 0}, 1}).empty());  // nested
  EXPECT_EQ(intersectCircles({{0, 0}, 1}, {{2, 0}, 1}).size(), 1u);   // tangent
}

TEST(Geometry, LineCircle) {
  const auto ts = intersectLineCircle({-10, 3}, {1, 0}, {{0, 0}, 5});
  ASSERT_EQ(ts.size(), 2u);
  for (double t : ts) EXPECT_NEAR(dist(Vec2{-10 + t, 3}, {0, 0}), 5, 1e-12);
  EXPECT_TRUE(intersectLineCircle({-10, 6}, {1, 0}, {{0, 0}, 5}).empty());
}

TEST(Geometry, Lines) {
  const auto x = intersectLines({0, 0}, {1, 1}, {0, 2}, {1, -1});
  ASSERT_TRUE(x);
  EXPECT_NEAR(x->x, 1, 1e-12);
  EXPECT_NEAR(x->y, 1, 1e-12);
  EXPECT_FALSE(intersectLines({0, 0}, {1, 1}, {0, 1}, {2, 2}));
}

TEST(Geometry, SignedArea) {
  EXPECT_DOUBLE_EQ(signedArea({{0, 0}, {2, 0}, {2, 1}, {0, 1}}), 2);
  EXPECT_DOUBLE_EQ(signedArea({{0, 0}, {0, 1}, {2, 1}, {2, 0}}), -2);
}

// The smallest enclosing circle contains every point and is no larger than the
// best circle through two or three of them (brute force).
TEST(Geometry, MinEnclosingCircleAgainstBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5, 5);
  for (int trial = 0; trial < 40; ++trial) {
    std::vector<Vec2> pts(3 + trial % 9);
    for (Vec2& p : pts) p = {u(rng), u(rng)};
    const Circle c = minEnclosingCircle(pts);
    for (const Vec2& p : pts) EXPECT_LE(dist(p, c.c), c.r + 1e-9);
    double best = INFINITY;
    auto consider = [&](Circle k) {
      for (const Vec2& p : pts)
        if (dist(p, k.c) > k.r + 1e-9) return;
      best = std::min(best, k.r);
    };
    for (size_t i = 0; i < pts.size(); ++i)
      for (size_t j = i + 1; j < pts.size(); ++j) {
        consider({(pts[i] + pts[j]) * 0.5, dist(pts[i], pts[j]) * 0.5});
        for (size_t k = j + 1; k < pts.size(); ++k) {
          const Vec2 a = pts[i], b = pts[j], cc = pts[k];
          const double d = 2 * (a.x * (b.y - cc.y) + b.x * (cc.y - a.y) + cc.x * (a.y - b.y));
          if (std::fabs(d) < 1e-12) continue;
          const double ux = (dot(a, a) * (b.y - cc.y) + dot(b, b) * (cc.y - a.y) + dot(cc, cc) * (a.y - b.y)) / d;
          const double uy = (dot(a, a) * (cc.x - b.x) + dot(b, b) * (a.x - cc.x) + dot(cc, cc) * (b.x - a.x)) / d;
          consider({{ux, uy}, dist({ux, uy}, a)});
        }
      }
    EXPECT_NEAR(c.r, best, 1e-7);
  }
}
