// The part around the pocket (part.hpp): plunges know every face above them.
// Each plan is checked against the part's own solids by this file's
// geometry (a box, a sphere on a cylinder), none of the planner's: the tool,
// a cylinder from its stop up, enters none of them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "part.hpp"
#include "plunge/plan.hpp"

using namespace plunge;
using ::testing::HasSubstr;

namespace {


struct Box3 {
  double x0, y0, z0, x1, y1, z1;
};

void addQuad(TriangleMesh& m, std::array<double, 3> a, std::array<double, 3> b, std::array<double, 3> c,
             std::array<double, 3> d) {
  const auto n = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.insert(m.vertices.end(), {a, b, c, d});
  m.triangles.push_back({n, n + 1, n + 2});
  m.triangles.push_back({n, n + 2, n + 3});
}

void addBox(TriangleMesh& m, const Box3& b) {
  addQuad(m, {b.x0, b.y0, b.z0}, {b.x1, b.y0, b.z0}, {b.x1, b.y1, b.z0}, {b.x0, b.y1, b.z0});
  addQuad(m, {b.x0, b.y0, b.z1}, {b.x1, b.y0, b.z1}, {b.x1, b.y1, b.z1}, {b.x0, b.y1, b.z1});
  addQuad(m, {b.x0, b.y0, b.z0}, {b.x1, b.y0, b.z0}, {b.x1, b.y0, b.z1}, {b.x0, b.y0, b.z1});
  addQuad(m, {b.x0, b.y1, b.z0}, {b.x1, b.y1, b.z0}, {b.x1, b.y1, b.z1}, {b.x0, b.y1, b.z1});
  addQuad(m, {b.x0, b.y0, b.z0}, {b.x0, b.y1, b.z0}, {b.x0, b.y1, b.z1}, {b.x0, b.y0, b.z1});
  addQuad(m, {b.x1, b.y0, b.z0}, {b.x1, b.y1, b.z0}, {b.x1, b.y1, b.z1}, {b.x1, b.y0, b.z1});
}

// A block of W x D x H with a W - 2t x D - 2t pocket down to its floor at
// z = -depth (top at 0): the walls, the top around the pocket and the floor,
// as FreeCAD's tessellation of such a part gives them.
TriangleMesh pocketBlock(double w, double d, double depth, double t) {
  TriangleMesh m;
  const double x0 = t, y0 = t, x1 = w - t, y1 = d - t;
  // The top: four strips around the opening.
  addQuad(m, {0, 0, 0}, {w, 0, 0}, {w, y0, 0}, {0, y0, 0});
  addQuad(m, {0, y1, 0}, {w, y1, 0}, {w, d, 0}, {0, d, 0});
  addQuad(m, {0, y0, 0}, {x0, y0, 0}, {x0, y1, 0}, {0, y1, 0});
  addQuad(m, {x1, y0, 0}, {w, y0, 0}, {w, y1, 0}, {x1, y1, 0});
  // The pocket's walls and floor.
  addQuad(m, {x0, y0, -depth}, {x1, y0, -depth}, {x1, y0, 0}, {x0, y0, 0});
  addQuad(m, {x0, y1, -depth}, {x1, y1, -depth}, {x1, y1, 0}, {x0, y1, 0});
  addQuad(m, {x0, y0, -depth}, {x0, y1, -depth}, {x0, y1, 0}, {x0, y0, 0});
  addQuad(m, {x1, y0, -depth}, {x1, y1, -depth}, {x1, y1, 0}, {x1, y0, 0});
  addQuad(m, {x0, y0, -depth}, {x1, y0, -depth}, {x1, y1, -depth}, {x0, y1, -depth});
  return m;
}

// A sphere of n x n facets: every vertex on it, the facets inside it by at
// most their sagitta (returned as the deviation).
double addSphere(TriangleMesh& m, std::array<double, 3> c, double r, int n) {
  const auto first = static_cast<std::uint32_t>(m.vertices.size());
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double th = kPi * i / n, ph = kPi * j / n;
      m.vertices.push_back({c[0] + r * std::sin(th) * std::cos(ph), c[1] + r * std::sin(th) * std::sin(ph),
                            c[2] + r * std::cos(th)});
    }
  auto at = [&](int i, int j) { return first + static_cast<std::uint32_t>(i * 2 * n + (j % (2 * n))); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return r * (1 - std::cos(kPi / n));  // a facet's farthest point from the sphere, about
}

PlanInput pocket60x40() {
  PlanInput in;
  in.boundary = {{10, 10}, {70, 10}, {70, 50}, {10, 50}};
  in.tools = {{12, 1, 300}, {8, 2, 300}, {5, 3, 300}};
  in.topZ = 0.0;
  in.safeZ = 5.0;
  in.floor.surface.z = -20.0;
  in.radialAllowance = 0.3;
  in.floorAllowance = 0.2;
  return in;
}

double diameterOf(const PlanInput& in, int id) {
  for (const Tool& t : in.tools)
    if (t.id == id) return t.diameter;
  return 0.0;
}

// The tool (a flat cylinder from its tip at z up) enters the box.
bool entersBox(Vec2 c, double r, double z, const Box3& b) {
  const double dx = std::max({b.x0 - c.x, 0.0, c.x - b.x1}), dy = std::max({b.y0 - c.y, 0.0, c.y - b.y1});
  return std::hypot(dx, dy) < r && z < b.z1;
}

// ... enters the ball of radius R around s.
bool entersBall(Vec2 c, double r, double z, std::array<double, 3> s, double R) {
  const double gap = std::max(0.0, std::hypot(c.x - s[0], c.y - s[1]) - r);
  return gap < R && z < s[2] + std::sqrt(R * R - gap * gap);
}

// Every stop and lead-out of the plan, each tool at its stop height.
template <class F>
void eachStop(const Plan& plan, const PlanInput& in, F check) {
  for (const Plunge& p : plan.plunges) {
    const double r = 0.5 * diameterOf(in, p.toolId);
    check(Vec2{p.x, p.y}, r, p.z, "plunge");
    if (p.leadOut)
      for (int k = 1; k <= 20; ++k) {
        const Vec2 q = Vec2{p.x, p.y} + (*p.leadOut - Vec2{p.x, p.y}) * (k / 20.0);
        check(q, r, p.leadOutZ.value_or(p.z), "lead-out");
      }
  }
}

}  // namespace

TEST(Part, WallsAndFloorChangeNothing) {
  // The part's faces that the outline already says (the walls, the top around
  // them, the floor): the plan is the plan without the part.
  PlanInput bare = pocket60x40();
  PlanInput with = bare;
  with.part = pocketBlock(80, 60, 20, 10);
  const Plan a = plan(bare), b = plan(with);
  ASSERT_EQ(a.plunges.size(), b.plunges.size());
  for (size_t i = 0; i < a.plunges.size(); ++i) {
    EXPECT_DOUBLE_EQ(a.plunges[i].x, b.plunges[i].x);
    EXPECT_DOUBLE_EQ(a.plunges[i].y, b.plunges[i].y);
    EXPECT_DOUBLE_EQ(a.plunges[i].z, b.plunges[i].z);
  }
  EXPECT_EQ(a.warnings, b.warnings);
}

TEST(Part, NoPlungeGoesUnderATab) {
  // A tab 20 x 16 mm out of the left wall, 10 to 15 mm below the top: the
  // floor's outline does not show it.
  PlanInput in = pocket60x40();
  TriangleMesh part = pocketBlock(80, 60, 20, 10);
  const Box3 tab{10, 22, -15, 30, 38, -10};
  addBox(part, tab);
  in.part = part;
  const Plan p = plan(in);
  ASSERT_GT(p.plunges.size(), 10u);
  int beside = 0;
  eachStop(p, in, [&](Vec2 c, double r, double z, const char* what) {
    EXPECT_FALSE(entersBox(c, r, z, tab)) << what << " at (" << c.x << ", " << c.y << ") z " << z;
    if (std::hypot(std::max({tab.x0 - c.x, 0.0, c.x - tab.x1}), std::max({tab.y0 - c.y, 0.0, c.y - tab.y1})) < r + 2)
      ++beside;
  });
  EXPECT_GT(beside, 0) << "the plunges reach up to the tab";
  EXPECT_THAT(p.warnings, testing::Contains(HasSubstr("overhangs the pocket")));
  // The floor under the tab (20 x 16 mm, with the allowance) is said and not cut.
  EXPECT_LT(p.stats.regionArea, 60 * 40 - 20 * 16 + 10);
}

TEST(Part, ADomeWiderThanItsStemIsAsWideAsTheDome) {
  // A stem of R 11.5 (the island the floor's outline shows) under a dome of R 15.9.
  PlanInput in = pocket60x40();
  in.boundary = {{0, 0}, {90, 0}, {90, 70}, {0, 70}};
  Loop stem;
  for (int k = 0; k < 64; ++k) stem.push_back({45 + 11.5 * std::cos(2 * kPi * k / 64), 35 + 11.5 * std::sin(2 * kPi * k / 64)});
  in.islands = {stem};
  in.topZ = 5.0;
  in.safeZ = 10.0;
  TriangleMesh part;
  const std::array<double, 3> centre{45, 35, -12};
  const double R = 15.9;
  part.deviation = {addSphere(part, centre, R, 48)};
  in.part = part;
  const Plan p = plan(in);
  ASSERT_GT(p.plunges.size(), 10u);
  double nearest = 1e9;
  eachStop(p, in, [&](Vec2 c, double r, double z, const char* what) {
    EXPECT_FALSE(entersBall(c, r, z, centre, R)) << what << " at (" << c.x << ", " << c.y << ") z " << z;
    nearest = std::min(nearest, std::hypot(c.x - centre[0], c.y - centre[1]) - r);
  });
  // The plunges come up to the dome's shadow, not to the stem's.
  EXPECT_GT(nearest, R);
  EXPECT_LT(nearest, R + 1.5);
}

TEST(Part, APartFaceOverTheFloorHoldsTheStopAbove) {
  // A sloped floor (-19 to -13 mm) and a block on it up to -15 mm that the
  // floor's outline does not show: lower than the floor's top, so no overhang
  // to take out; the stops over it stay above it.
  PlanInput in = pocket60x40();
  in.floor.surface.kind = Floor::Kind::Expression;
  in.floor.surface.expression = "-20 + 0.1 * x";
  TriangleMesh part;
  const Box3 block{20, 25, -20, 26, 35, -15};
  addBox(part, block);
  in.part = part;
  const Plan p = plan(in);
  ASSERT_GT(p.plunges.size(), 10u);
  int held = 0;
  eachStop(p, in, [&](Vec2 c, double r, double z, const char* what) {
    EXPECT_FALSE(entersBox(c, r, z, block)) << what << " at (" << c.x << ", " << c.y << ") z " << z;
    if (std::string(what) == "plunge" && z >= -15.0) ++held;
  });
  EXPECT_GT(held, 0) << "the plunges over the block stop on it";
}

TEST(Part, OverhangsOverIgnoresWallsAndTheMaterialBelow) {
  const TriangleMesh block = pocketBlock(80, 60, 20, 10);
  const Polygons region{{{10, 10}, {70, 10}, {70, 50}, {10, 50}}};
  EXPECT_TRUE(overhangsOver(block, -20 + 0.01, region, 0.005).empty());
  TriangleMesh withTab = block;
  addBox(withTab, {10, 22, -15, 30, 38, -10});
  const Polygons over = overhangsOver(withTab, -20 + 0.01, region, 0.005);
  ASSERT_FALSE(over.empty());
  double lo = 1e9, hi = -1e9;
  for (const Loop& L : over)
    for (const Vec2& v : L) lo = std::min(lo, v.y), hi = std::max(hi, v.y);
  EXPECT_NEAR(lo, 22, 0.01);
  EXPECT_NEAR(hi, 38, 0.01);
  // Below the tab's underside nothing hangs over; from it up the tab does.
  EXPECT_FALSE(overhangsOver(withTab, -14.0, region, 0.005).empty());
  EXPECT_TRUE(overhangsOver(withTab, -9.0, region, 0.005).empty());
}

TEST(Part, InReachKeepsWhatReachesIntoThePocket) {
  TriangleMesh block = pocketBlock(80, 60, 20, 10);
  const size_t walls = block.triangles.size();
  addBox(block, {10, 22, -15, 30, 38, -10});
  const TriangleMesh near = partInReach(block, {{{10, 10}, {70, 10}, {70, 50}, {10, 50}}}, 0.005);
  // The floor's two triangles and the tab's that are not flush with the wall.
  EXPECT_LT(near.triangles.size(), block.triangles.size() - walls + 2 + 1);
  EXPECT_GE(near.triangles.size(), 2u + 10u);
  EXPECT_EQ(near.deviation.size(), near.triangles.size());
}

TEST(Part, TheStockAroundAnIslandThatNarrowsUpwardIsMeasuredAndSaid) {
  // A boss R 15.9 at the floor tapering to R 12.1 at 2 mm below the top: the
  // outline's island is its foot, so the plunges leave a ring above the floor,
  // out to the foot, its allowance (0.3) and the band (1): at the boss's top
  // about 17.2 - 12.1 - 0.3 = 4.8 mm beyond the radial allowance.
  PlanInput in = pocket60x40();
  in.boundary = {{0, 0}, {90, 0}, {90, 70}, {0, 70}};
  const int n = 96;
  Loop foot;
  TriangleMesh part = pocketBlock(90, 70, 20, 0);  // the walls and the top around: flush with the outline
  const auto base = static_cast<std::uint32_t>(part.vertices.size());
  for (int k = 0; k < n; ++k) {
    const double a = 2 * kPi * k / n;
    foot.push_back({45 + 15.9 * std::cos(a), 35 + 15.9 * std::sin(a)});
    part.vertices.push_back({45 + 15.9 * std::cos(a), 35 + 15.9 * std::sin(a), -20});
    part.vertices.push_back({45 + 12.1 * std::cos(a), 35 + 12.1 * std::sin(a), -2});
  }
  part.vertices.push_back({45, 35, -2});
  for (int k = 0; k < n; ++k) {
    const std::uint32_t b0 = base + 2 * k, t0 = b0 + 1, b1 = base + 2 * ((k + 1) % n), t1 = b1 + 1;
    part.triangles.push_back({b0, b1, t1});
    part.triangles.push_back({b0, t1, t0});
    part.triangles.push_back({t0, t1, base + 2 * n});
  }
  in.islands = {foot};
  const Plan without = plan(in);
  in.part = part;
  const Plan p = plan(in);
  // Without the part nothing tells the ring apart; with it, the band is said at its size.
  EXPECT_LT(without.stats.maxWallStockLeft, 1.2);
  EXPECT_THAT(p.warnings, testing::Contains(HasSubstr("measured against the whole part")));
  const auto band = std::find_if(p.broken.begin(), p.broken.end(), [](const BrokenLimit& b) {
    return b.limit == "max_wall_stock" && b.worst > 2.0;
  });
  ASSERT_NE(band, p.broken.end());
  EXPECT_NEAR(band->worst, 4.8, 0.4);
  EXPECT_NEAR(std::hypot(band->at.x - 45, band->at.y - 35), 17.2, 1.0) << "the ring's outer edge (a raster step or two)";
  EXPECT_NEAR(p.stats.maxWallStockLeft, band->worst, 1e-9);
}
