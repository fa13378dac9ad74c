#include <gtest/gtest.h>

#include <random>
#include <tuple>

#include "plunge/error.hpp"
#include "packing.hpp"
#include "testutil.hpp"

using namespace plunge;

namespace {
double lineDistance(Vec2 p, Vec2 a, Vec2 b) { return std::fabs(cross(b - a, p - a)) / norm(b - a); }
}  // namespace

// --- corner placements (thesis 4.2.2.4), against hand-computed tangency -------

// Packing options by contact ratio and allowance.
static PackingOptions packing(double contactRatio, double allowance) {
  PackingOptions o;
  o.contactRatio = contactRatio;
  o.allowance = allowance;
  return o;
}

TEST(CornerPlacement, TwoWallsAtARightAngle) {
  // Bottom and right walls of a counter-clockwise square meet at (100, 0).
  const auto p = cornerPlacementsWallWall({{0, 0}, {100, 0}}, {{100, 0}, {100, 100}}, 5);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NEAR(p[0].x, 95, 1e-12);
  EXPECT_NEAR(p[0].y, 5, 1e-12);
}

TEST(CornerPlacement, TwoWallsMatchTheThesisOffsetPoint) {
  // Eqs. 4.18-4.26: the offset point lies on the bisector at r / sin(theta / 2),
  // theta being the corner's interior angle.
  for (double deg : {30.0, 60.0, 90.0, 120.0, 150.0}) {
    const double th = deg * kPi / 180;
    const Vec2 v{0, 0};
    const Segment in{{std::cos(th) * 50, std::sin(th) * 50}, v};  // arrives at v
    const Segment out{v, {50, 0}};
    // The material is on the left of both: the wedge of angle theta above the x axis.
    const auto p = cornerPlacementsWallWall(out, in, 4);
    ASSERT_EQ(p.size(), 1u) << deg;
    EXPECT_NEAR(dist(p[0], v), 4 / std::sin(th / 2), 1e-9) << deg;
    EXPECT_NEAR(std::atan2(p[0].y, p[0].x), th / 2, 1e-9) << "on the bisector";
    EXPECT_NEAR(lineDistance(p[0], in.a, in.b), 4, 1e-9);
    EXPECT_NEAR(lineDistance(p[0], out.a, out.b), 4, 1e-9);
  }
}

TEST(CornerPlacement, TwoWallsOutOfReachOrParallel) {
  EXPECT_TRUE(cornerPlacementsWallWall({{0, 0}, {10, 0}}, {{10, 20}, {0, 20}}, 5).empty());  // parallel channel
  // Offset lines cross beyond the segments: no tangency on both.
  EXPECT_TRUE(cornerPlacementsWallWall({{0, 0}, {10, 0}}, {{40, 0}, {40, 10}}, 5).empty());
}

TEST(CornerPlacement, WallAndCircle) {
  // Circle of radius 10 at (50, 10), new circle radius 5 keeping 5 from the wall y = 0:
  // centres on y = 5 at distance 15 from (50, 10): x = 50 -+ sqrt(200).
  const auto p = cornerPlacementsWallCircle({{0, 0}, {100, 0}}, 5, {{50, 10}, 15});
  ASSERT_EQ(p.size(), 2u);
  for (const Vec2& q : p) {
    EXPECT_NEAR(q.y, 5, 1e-12);
    EXPECT_NEAR(std::fabs(q.x - 50), std::sqrt(200.0), 1e-12);
    EXPECT_NEAR(dist(q, {50, 10}), 15, 1e-12);
  }
  // The tangent point must fall on the wall segment.
  EXPECT_TRUE(cornerPlacementsWallCircle({{0, 0}, {30, 0}}, 5, {{80, 10}, 15}).empty());
}

TEST(CornerPlacement, TwoCircles) {
  // Eqs. 4.39-4.54: circles of radius 10 touching at the origin, new radius 5.
  const auto p = cornerPlacementsCircleCircle({{-10, 0}, 15}, {{10, 0}, 15});
  ASSERT_EQ(p.size(), 2u);
  for (const Vec2& q : p) {
    EXPECT_NEAR(q.x, 0, 1e-12);
    EXPECT_NEAR(std::fabs(q.y), std::sqrt(125.0), 1e-12);
  }
}

TEST(CornerPlacement, ReflexVertexAndWall) {
  // A reflex vertex is a circle locus of radius = clearance around the vertex.
  const auto p = cornerPlacementsWallCircle({{0, 0}, {100, 0}}, 3, {{50, 5}, 3});
  ASSERT_EQ(p.size(), 2u);
  for (const Vec2& q : p) {
    EXPECT_NEAR(q.y, 3, 1e-12);
    EXPECT_NEAR(std::fabs(q.x - 50), std::sqrt(5.0), 1e-12);
  }
}

TEST(HoleDegree, Equation468) {
  EXPECT_DOUBLE_EQ(holeDegree(0, 5), 1);
  EXPECT_DOUBLE_EQ(holeDegree(2.5, 5), 0.5);
  EXPECT_DOUBLE_EQ(holeDegree(5, 5), 0);
  EXPECT_DOUBLE_EQ(holeDegree(-1, 5), 1);
  EXPECT_DOUBLE_EQ(holeDegree(50, 5), 0);
}

TEST(ContactDistance, SameToolAndSmallerTool) {
  const PackedDisk big{{0, 0}, 10, 8.6, 0}, big2{{0, 0}, 10, 8.6, 0}, small{{0, 0}, 3, 2.58, 1};
  EXPECT_DOUBLE_EQ(contactDistance(big, big2), 17.2);
  EXPECT_DOUBLE_EQ(contactDistance(big, small), 12.58);  // the smaller circle stays in uncut material
  EXPECT_DOUBLE_EQ(contactDistance(small, big), 12.58);
}

// --- packing properties on random pockets -------------------------------------

namespace {

struct Pocket {
  Loop outer;
  std::vector<Loop> islands;
  std::vector<Loop> all() const {
    std::vector<Loop> a{outer};
    a.insert(a.end(), islands.begin(), islands.end());
    return a;
  }
};

Pocket randomPocket(std::mt19937& rng) {
  Pocket p;
  p.outer = test::randomStar(rng, {0, 0}, 45, 90, 7 + rng() % 30);
  std::uniform_real_distribution<double> u(-20, 20);
  if (rng() % 2) p.islands.push_back(test::circleLoop({u(rng), u(rng)}, 8 + rng() % 6, 24));
  return p;
}

// Distinct points where the disk touches the walls.
int wallContacts(const std::vector<Loop>& loops, Vec2 c, double clearance) {
  std::vector<Vec2> pts;
  for (const Loop& L : loops)
    for (size_t i = 0; i < L.size(); ++i) {
      const Vec2 q = closestPointOnSegment({L[i], L[(i + 1) % L.size()]}, c);
      if (std::fabs(dist(q, c) - clearance) > 1e-6) continue;
      bool seen = false;
      for (const Vec2& s : pts) seen = seen || dist(s, q) < 1e-6;
      if (!seen) pts.push_back(q);
    }
  return static_cast<int>(pts.size());
}

}  // namespace

class PackingProperties : public ::testing::TestWithParam<std::tuple<double, PackingOrder>> {};

TEST_P(PackingProperties, RandomPockets) {
  const double ratio = std::get<0>(GetParam());
  std::mt19937 rng(2024);
  const std::vector<double> radii{9, 5, 2.5};
  for (int trial = 0; trial < 12; ++trial) {
    const Pocket pk = randomPocket(rng);
    const Region region(pk.outer, pk.islands);
    const double allowance = 0.4 * (trial % 3);
    PackingOptions opt;
    opt.contactRatio = ratio;
    opt.allowance = allowance;
    opt.order = std::get<1>(GetParam());
    const auto disks = packMaxHoleDegree(region, radii, opt);
    ASSERT_FALSE(disks.empty());
    const auto loops = pk.all();
    for (size_t i = 0; i < disks.size(); ++i) {
      const PackedDisk& d = disks[i];
      // Inside the pocket, clear of every wall by radius + allowance: no gouge.
      EXPECT_TRUE(test::bruteInside(loops, d.center));
      EXPECT_GE(test::bruteWallDistance(loops, d.center), d.radius + allowance - 1e-6);
      // Largest first.
      if (i > 0) {
        EXPECT_LE(d.radius, disks[i - 1].radius);
      }
      // A corner placement: touches at least two items (walls or circles).
      int items = wallContacts(loops, d.center, d.radius + allowance);
      for (size_t j = 0; j < i; ++j)
        if (std::fabs(dist(d.center, disks[j].center) - contactDistance(d, disks[j])) < 1e-6) ++items;
      if (i > 0) {
        EXPECT_GE(items, 2) << "disk " << i << " of trial " << trial;
      }
      // No overlap in the packing stage.
      for (size_t j = 0; j < i; ++j) {
        EXPECT_GE(dist(d.center, disks[j].center), contactDistance(d, disks[j]) - 1e-6);
        if (ratio == 1.0) {
          EXPECT_GE(dist(d.center, disks[j].center), d.radius + disks[j].radius - 1e-6);
        }
      }
    }
    // Maximal: no circle of any size fits anywhere any more (dense random probe).
    std::uniform_real_distribution<double> u(-95, 95);
    for (int k = 0; k < 20000; ++k) {
      const Vec2 p{u(rng), u(rng)};
      if (!test::bruteInside(loops, p)) continue;
      const double wd = test::bruteWallDistance(loops, p);
      for (size_t t = 0; t < radii.size(); ++t) {
        const PackedDisk probe{p, radii[t], ratio * radii[t], static_cast<int>(t)};
        if (wd < radii[t] + allowance + 1e-6) continue;
        bool clear = true;
        for (const PackedDisk& d : disks) clear = clear && dist(p, d.center) >= contactDistance(d, probe) + 1e-6;
        EXPECT_FALSE(clear) << "a circle of radius " << radii[t] << " still fits at " << p.x << "," << p.y;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(RatiosAndOrders, PackingProperties,
                         ::testing::Combine(::testing::Values(1.0, 0.86),
                                            ::testing::Values(PackingOrder::HoleDegree, PackingOrder::Lattice)));

// The lattice order keeps the interior one hexagonal lattice even around islands:
// almost every circle away from the walls touches six others.
TEST(Packing, LatticeOrderGivesAHexagonalInterior) {
  const Region region({{0, 0}, {300, 0}, {300, 200}, {0, 200}},
                      {test::circleLoop({90, 70}, 20, 60), test::circleLoop({210, 130}, 20, 60)});
  PackingOptions opt;
  opt.order = PackingOrder::Lattice;
  const auto d = packMaxHoleDegree(region, {10}, opt);
  int interior = 0, six = 0;
  for (const PackedDisk& a : d) {
    if (region.wallDistance(a.center, 40) < 40) continue;
    ++interior;
    int touching = 0;
    for (const PackedDisk& b : d) touching += &a != &b && std::fabs(dist(a.center, b.center) - 17.2) < 0.05;
    six += touching == 6;
  }
  EXPECT_GT(interior, 30);
  EXPECT_GE(six, 0.95 * interior);
}

TEST(Packing, Deterministic) {
  std::mt19937 rng(5);
  const Pocket pk = randomPocket(rng);
  const Region region(pk.outer, pk.islands);
  const auto a = packMaxHoleDegree(region, {6, 3});
  const auto b = packMaxHoleDegree(region, {3, 6});  // order of the radii does not matter
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].center, b[i].center);
    EXPECT_EQ(a[i].radius, b[i].radius);
  }
}

TEST(Packing, SquarePocketStartsInACorner) {
  const Region region({{0, 0}, {100, 0}, {100, 100}, {0, 100}}, {});
  const auto d = packMaxHoleDegree(region, {10}, packing(1.0, 0.0));
  ASSERT_FALSE(d.empty());
  EXPECT_NEAR(d[0].center.x, 10, 1e-9);  // gold corner first
  EXPECT_NEAR(d[0].center.y, 10, 1e-9);
  // 100 mm holds five disjoint 20 mm circles per row.
  int bottomRow = 0;
  for (const PackedDisk& x : d) bottomRow += std::fabs(x.center.y - 10) < 1e-9;
  EXPECT_EQ(bottomRow, 5);
}

TEST(Packing, RejectsBadOptions) {
  const Region region({{0, 0}, {10, 0}, {10, 10}}, {});
  EXPECT_THROW(packMaxHoleDegree(region, {0.0}), Error);
  EXPECT_THROW(packMaxHoleDegree(region, {NAN}), Error);
  EXPECT_THROW(packMaxHoleDegree(region, {1}, packing(0.0, 0.0)), Error);
  EXPECT_THROW(packMaxHoleDegree(region, {1}, packing(0.86, -1.0)), Error);
}
