// limits.hpp: what is refused before planning, simplified big boundaries,
// tools too large for the pocket. Each refusal is checked to happen (and to say
// why); each accepted input to plan without gouging the given walls.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "plunge/error.hpp"
#include "plunge/json.hpp"
#include "limits.hpp"
#include "plunge/plan.hpp"
#include "validate.hpp"
#include "testutil.hpp"

using namespace plunge;
using ::testing::Contains;
using ::testing::HasSubstr;

namespace {

PlanInput benchmark() { return planInputFromJson(test::readData("shapes/benchmark.json")); }

using test::planError;


// A smooth closed curve of about 600 x 400 mm with n vertices (a fine
// chordal tolerance on a B-spline face).
Loop freeForm(int n) {
  Loop out;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPi * i / n;
    const double r = (1 + 0.15 * std::sin(3 * t) + 0.08 * std::cos(5 * t)) / 1.23;
    out.push_back({300 + 290 * r * std::cos(t), 200 + 190 * r * std::sin(t)});
  }
  return out;
}

void expectNoGouge(const std::vector<Loop>& loops, double allowance, const Plan& p) {
  for (const Plunge& q : p.plunges) {
    ASSERT_TRUE(test::bruteInside(loops, {q.x, q.y}));
    ASSERT_GE(test::bruteWallDistance(loops, {q.x, q.y}), q.diameter / 2 + allowance - 1e-6);
  }
}

}  // namespace

// The hostile inputs that ran for minutes (a fuzzing run): each is refused at once, naming the cause.
TEST(Limits, UnitSlipsAreRefused) {
  for (double d : {1e-300, 1e-3, 0.01}) {
    PlanInput in = benchmark();
    in.tools.push_back({d, 9, 100});
    const std::string e = planError(in);
    EXPECT_THAT(e, HasSubstr("plunges, more than max_plunges (200000)"));
    EXPECT_THAT(e, HasSubstr("is the diameter in mm?"));
    EXPECT_THAT(e, HasSubstr("tool 9"));
  }
  PlanInput in = benchmark();
  in.tools.push_back({1e9, 9, 100});
  EXPECT_THAT(planError(in), HasSubstr("larger than any milling tool"));
  in = benchmark();
  in.boundary[1].x = 1e9;
  EXPECT_THAT(planError(in), HasSubstr("boundary: coordinate 1.000e+09 mm is beyond"));
  in = benchmark();
  in.radialAllowance = 1e308;
  EXPECT_THAT(planError(in), HasSubstr("allowance.radial"));
  in = benchmark();
  in.islands[0][3].y = -2e5;
  EXPECT_THAT(planError(in), HasSubstr("island 1: coordinate"));
}

TEST(Limits, EstimateAgainstMaxPlunges) {
  PlanInput in = benchmark();  // 600 x 400 mm less four 60 mm islands, smallest tool 5 mm
  const double area = 600.0 * 400 - 4 * kPi * 30 * 30;
  EXPECT_NEAR(estimatedPlunges(in), area / (kPi * 2.5 * 2.5), 0.01 * area / (kPi * 2.5 * 2.5));
  in.maxPlunges = 0.9 * estimatedPlunges(in);
  EXPECT_THAT(planError(in), HasSubstr("more than max_plunges"));
  in.maxPlunges = 0.5;
  EXPECT_THAT(planError(in), HasSubstr("max_plunges must be at least 1"));
  // A 2 mm plunger fits the default (76000 plunges estimated).
  in = benchmark();
  in.tools.push_back({2, 9, 100});
  EXPECT_NO_THROW(validate(in));
}

// Growing within an engagement limit costs about kGrowthCost packed plunges
// each, counted from the row bound: a quarter of the diameter on the benchmark
// plans (not run here: 15 s), about 5 % of it is refused (a limit of microns is refused
// by validation).
TEST(Limits, EngagementLimitsCountTheirGrowth) {
  PlanInput in = benchmark();
  for (Tool& t : in.tools) t.maxEngagement = 0.25 * t.diameter;
  EXPECT_GT(estimatedPlunges(in), kGrowthCost * 228000 / (0.87 * 12 * 3));  // tools already largest first
  EXPECT_LT(estimatedPlunges(in), in.maxPlunges);
  in.tools[0].maxEngagement = 0.62;  // just over 5 % of the diameter: allowed, but not in a pocket this big
  const std::string e = planError(in);
  EXPECT_THAT(e, HasSubstr("tool 1 (diameter 12 mm, engagement limit 0.62 mm)"));
  EXPECT_THAT(e, HasSubstr("is the limit in mm, or too small for this pocket?"));
}

TEST(Limits, TooManyVerticesAreRefused) {
  PlanInput in = benchmark();
  in.islands.clear();
  in.boundary = freeForm(static_cast<int>(kMaxVertices) + 1);
  EXPECT_THAT(planError(in), HasSubstr("export the face with a coarser tolerance"));
}

TEST(Limits, ToolsTooLargeAreLeftOutWithAWarning) {
  PlanInput in = benchmark();
  in.tools.push_back({700, 9, 100});
  const Plan p = plan(in);
  EXPECT_THAT(p.warnings, Contains(HasSubstr("T9 (700 mm)")));
  for (const Plunge& q : p.plunges) EXPECT_NE(q.toolId, 9);
  EXPECT_GT(p.plunges.size(), 2000u);
}

// A boundary of 100k vertices: planned on simplified walls, never nearer the
// given walls than the allowance.
TEST(Limits, BigBoundariesPlanOnSimplifiedWalls) {
  PlanInput in;
  in.boundary = freeForm(100000);
  in.tools = {{12, 1, 100}, {6, 2, 100}};
  in.floor.surface.z = -20;
  in.radialAllowance = 0.5;
  const Plan p = plan(in);
  EXPECT_GT(p.stats.boundaryTolerance, 0.0);
  EXPECT_LE(p.stats.boundaryTolerance, kMaxBoundaryTolerance);
  EXPECT_GT(p.plunges.size(), 1000u);
  expectNoGouge({in.boundary}, in.radialAllowance, p);
  EXPECT_GE(p.stats.coreCoverage, 0.999);
}

TEST(Limits, SimplifiedRegionStaysWithinItsTolerance) {
  std::mt19937 rng(3);
  const Loop outer = freeForm(20000);
  const Loop island = test::circleLoop({300, 200}, 40, 9000);
  const Region full(outer, {island});
  double tol = 0.0;
  const std::optional<Region> coarse = simplifiedRegion(full, kPlanningVertices, kMaxBoundaryTolerance, tol);
  ASSERT_TRUE(coarse);
  EXPECT_LE(coarse->vertices().size(), kPlanningVertices);
  EXPECT_GT(tol, 0.0);
  // Both ways: every given vertex near the simplified walls, every simplified
  // wall (sampled) near the given ones.
  for (const Region::Vertex& v : full.vertices()) ASSERT_LE(coarse->wallDistance(v.p, 1.0), tol + 1e-9);
  for (const Segment& s : coarse->walls())
    for (double f : {0.25, 0.5, 0.75}) ASSERT_LE(full.wallDistance(s.a + (s.b - s.a) * f, 1.0), tol + 1e-9);
  // Small regions are left as they are.
  EXPECT_FALSE(simplifiedRegion(Region(freeForm(500), {}), kPlanningVertices, kMaxBoundaryTolerance, tol));
  EXPECT_EQ(tol, 0.0);
}
