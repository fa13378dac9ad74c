#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "plunge/error.hpp"
#include "plunge/json.hpp"
#include "limits.hpp"
#include "plunge/plan.hpp"
#include "testutil.hpp"

using namespace plunge;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

PlanInput square() {
  PlanInput in = test::rectanglePocket();
  std::swap(in.tools[0], in.tools[1]);  // any order: the plan takes the largest first
  return in;
}

using test::planError;

}  // namespace

TEST(Plan, OrderDepthAndStats) {
  const Plan p = plan(square());
  ASSERT_FALSE(p.plunges.empty());
  // Tools largest first, all plunges of one tool together.
  EXPECT_EQ(p.plunges.front().toolId, 1);
  int changes = 0;
  for (size_t i = 1; i < p.plunges.size(); ++i) {
    EXPECT_GE(p.plunges[i - 1].diameter, p.plunges[i].diameter);
    changes += p.plunges[i].toolId != p.plunges[i - 1].toolId;
  }
  EXPECT_LE(changes, 1);
  int counted = 0;
  for (const ToolCount& t : p.stats.perTool) counted += t.count;
  EXPECT_EQ(counted, p.stats.plungeCount);
  EXPECT_EQ(p.stats.plungeCount, static_cast<int>(p.plunges.size()));
  for (const Plunge& q : p.plunges) EXPECT_DOUBLE_EQ(q.z, -11.8);
  // The default wall band: all of the core cut, nothing thicker than the band left.
  EXPECT_LT(p.stats.coreArea * (1 - p.stats.coreCoverage), 0.01);
  EXPECT_LE(p.stats.maxWallStockLeft, 1.0 + 1e-9);
  EXPECT_NEAR(p.stats.coverage, p.stats.coveredArea / p.stats.accessibleArea, 1e-12);
  EXPECT_LT(p.stats.accessibleArea, p.stats.regionArea);
  // Travel: from each plunge's lead-out end (or its centre) to the next plunge.
  double travel = 0;
  for (size_t i = 1; i < p.plunges.size(); ++i) {
    const Plunge& q = p.plunges[i - 1];
    travel += dist(q.leadOut ? *q.leadOut : Vec2{q.x, q.y}, {p.plunges[i].x, p.plunges[i].y});
  }
  EXPECT_NEAR(p.stats.travelLength, travel, 1e-9);
}

TEST(Plan, SameInputSamePlan) {
  test::expectSamePlunges(plan(square()), plan(square()));
}

TEST(Plan, RejectsBadNumbers) {
  PlanInput in = square();
  in.tools[0].diameter = -3;
  EXPECT_THAT(planError(in), HasSubstr("diameter must be > 0"));
  in = square();
  in.tools[0].diameter = NAN;
  EXPECT_THAT(planError(in), HasSubstr("not a finite number"));
  in = square();
  in.tools.clear();
  EXPECT_THAT(planError(in), HasSubstr("at least one tool"));
  in = square();
  in.tools[0].id = 1;
  EXPECT_THAT(planError(in), HasSubstr("used twice"));
  in = square();
  in.safeZ = -1;
  EXPECT_THAT(planError(in), HasSubstr("safe_z"));
  in = square();
  in.floor.surface.z = 3;
  EXPECT_THAT(planError(in), HasSubstr("below top_z"));
  in = square();
  in.radialAllowance = -0.1;
  EXPECT_THAT(planError(in), HasSubstr("allowance.radial"));
  in = square();
  in.floorAllowance = INFINITY;
  EXPECT_THAT(planError(in), HasSubstr("allowance.floor"));
  in = square();
  in.packing.gridStep = 1.5;
  EXPECT_THAT(planError(in), HasSubstr("grid.step must be 0"));
  in = square();
  in.tools[0].id = kMaxToolId + 1;  // io refuses it too; validate() for callers of the library
  EXPECT_THAT(planError(in), HasSubstr("tools[0].id must be a positive integer"));
  in = square();
  in.covering.minCoverage = 1.5;
  EXPECT_THAT(planError(in), HasSubstr("min_coverage"));
}

TEST(Plan, NoToolFits) {
  PlanInput in = square();
  in.tools = {{100, 1, 100}, {90, 2, 100}};
  EXPECT_THAT(planError(in), HasSubstr("no tool fits"));
  in = square();
  in.radialAllowance = 39;  // 80 mm wide pocket, 10 mm tool, 2 x 39 mm allowance
  EXPECT_THAT(planError(in), HasSubstr("no tool fits"));
}

TEST(Plan, ToolThatFitsNowhereGetsNoPlunge) {
  PlanInput in = square();
  in.tools.push_back({95, 7, 100});
  const Plan p = plan(in);
  for (const Plunge& q : p.plunges) EXPECT_NE(q.toolId, 7);
  EXPECT_LT(p.stats.coreArea * (1 - p.stats.coreCoverage), 0.01);
}

// Every test shape of the suite: no gouge; with the default 1 mm wall band, the
// core cut whole and no thicker wall stock; without a band, coverage at least 99.5 %.
class Shapes : public ::testing::TestWithParam<const char*> {};

static void expectNoGouge(const PlanInput& in, const Plan& p) {
  std::vector<Loop> loops{in.boundary};
  loops.insert(loops.end(), in.islands.begin(), in.islands.end());
  for (const Plunge& q : p.plunges) {
    EXPECT_TRUE(test::bruteInside(loops, {q.x, q.y}));
    EXPECT_GE(test::bruteWallDistance(loops, {q.x, q.y}), q.diameter / 2 + in.radialAllowance - 1e-6);
  }
}

TEST_P(Shapes, InvariantsHold) {
  PlanInput in = planInputFromJson(test::readData(std::string("shapes/") + GetParam() + ".json"));
  const Plan p = plan(in);
  expectNoGouge(in, p);
  EXPECT_LT(p.stats.coreArea * (1 - p.stats.coreCoverage), 0.01);
  EXPECT_LE(p.stats.maxWallStockLeft, in.covering.maxWallStock + 1e-9);
  EXPECT_TRUE(p.warnings.empty());
  // The band's point: fewer plunges than the honeycomb grid of the same tools.
  PlanInput grid = in;
  grid.packing.strategy = Strategy::Grid;
  EXPECT_LT(p.stats.plungeCount, plan(grid).stats.plungeCount);
  // No band: today's covering down to min_coverage.
  in.covering.maxWallStock = 0.0;
  const Plan today = plan(in);
  expectNoGouge(in, today);
  EXPECT_GE(today.stats.coverage, 0.995);
  EXPECT_DOUBLE_EQ(today.stats.coreCoverage, today.stats.coverage);
  EXPECT_TRUE(today.warnings.empty());
}

// Bands reaching deep into the plunger's disk (here up to beyond its radius):
// still one wall row and one packing inside it, never two packings on top of
// each other, and never more plunges than covering without a band.
TEST(Plan, DeepBandsPackOnce) {
  PlanInput in = square();
  in.tools = {{10, 1, 100}};
  in.covering.maxWallStock = 0;
  const int today = plan(in).stats.plungeCount;
  for (double band : {3.0, 4.0, 6.0}) {
    in.covering.maxWallStock = band;
    const Plan p = plan(in);
    EXPECT_LT(p.stats.plungeCount, today) << band;
    EXPECT_LT(p.stats.coreArea * (1 - p.stats.coreCoverage), 0.01) << band;
    for (size_t i = 0; i < p.plunges.size(); ++i)
      for (size_t j = i + 1; j < p.plunges.size(); ++j)
        EXPECT_GT(dist({p.plunges[i].x, p.plunges[i].y}, {p.plunges[j].x, p.plunges[j].y}), 1.0) << band;
  }
}

// A much smaller second plunger cleans only what the largest cannot reach: it
// used to take the whole pocket over (an 80 x 60 mm pocket, 10 mm and 1 mm
// tools: 7342 plunges of the 1 mm one, none of the 10 mm one).
TEST(Plan, ASmallSecondToolDoesNotTakeOver) {
  PlanInput in = test::rectanglePocket(80, 60);
  in.tools = {{10, 1, 100}, {6, 2, 100}};
  const Plan usual = plan(in);
  const int largest = usual.stats.perTool.at(0).count;
  for (double small : {2.0, 1.0, 0.5}) {
    in.tools[1].diameter = small;
    const Plan p = plan(in);
    ASSERT_EQ(p.stats.perTool.at(0).toolId, 1) << small;
    EXPECT_GE(p.stats.perTool[0].count, 0.8 * largest) << small;
    EXPECT_LT(p.stats.plungeCount, 2 * usual.stats.plungeCount) << small;
    EXPECT_GT(p.stats.coreCoverage, 0.999) << small;
    expectNoGouge(in, p);
  }
}

// A band as wide as the pocket leaves nothing to cut: a clear error, not an empty plan.
TEST(Plan, BandWiderThanThePocketIsAnError) {
  PlanInput in = square();
  in.covering.maxWallStock = 45;  // the square is 80 mm wide
  EXPECT_THAT(planError(in), HasSubstr("max_wall_stock"));
  in.covering.maxWallStock = 1e5;  // wider than the pocket, within the limits
  EXPECT_THAT(planError(in), HasSubstr("is the whole pocket"));
  in.covering.maxWallStock = 1e308;  // beyond any polygon offset: a length no machine has (limits.hpp)
  EXPECT_THAT(planError(in), HasSubstr("max_wall_stock 1.000e+308 mm is beyond"));
  in.covering.maxWallStock = -1;
  EXPECT_THAT(planError(in), HasSubstr("max_wall_stock must be >= 0"));
  in.covering.maxWallStock = 1;
  in.floor.maxFloorStock = NAN;
  EXPECT_THAT(planError(in), HasSubstr("max_floor_stock"));
}

INSTANTIATE_TEST_SUITE_P(TestShapes, Shapes, ::testing::Values("convex", "concave", "islands", "freeform", "neck"));

// A plan short of min_coverage says so (never a silent shortfall); one that meets it says nothing.
TEST(Plan, CoverageShortfallIsAWarning) {
  PlanInput in;
  in.boundary = {{0, 0}, {60, 0}, {60, 40}, {0, 40}};
  in.tools = {{16, 1}, {6, 2}};
  in.topZ = 0;
  in.safeZ = 5;
  in.floor.surface.z = -10;
  in.covering.maxWallStock = 0;  // cover down to min_coverage
  const Plan ok = plan(in);
  EXPECT_GE(ok.stats.coverage, in.covering.minCoverage);
  EXPECT_TRUE(ok.warnings.empty());
  in.covering.minCoverage = 1.0;  // wall cusps always remain
  const Plan short_ = plan(in);
  ASSERT_EQ(short_.warnings.size(), 1u);
  EXPECT_THAT(short_.warnings[0], HasSubstr("less than the 100.00 % asked for"));
  EXPECT_THAT(short_.warnings[0], Not(HasSubstr("min_coverage")));  // no internal key names
  EXPECT_THAT(planToJson(short_), HasSubstr("\"warnings\""));
  // The grid baseline short of the target warns the same way.
  in.covering.minCoverage = 0.996;
  in.packing.strategy = Strategy::Grid;
  const Plan grid = plan(in);
  ASSERT_LT(grid.stats.coverage, in.covering.minCoverage);
  ASSERT_EQ(grid.warnings.size(), 1u);
  EXPECT_THAT(grid.warnings[0], HasSubstr("grid"));
}

TEST(Plan, NoPlungeStopsBelowTheFinalDepth) {
  // A floor sloping from -12 to -4 across the pocket, roughed down to -8 only.
  PlanInput in = square();
  in.floor.surface.kind = Floor::Kind::Expression;
  in.floor.surface.expression = "-12 + x / 15";
  in.floor.finalDepth = -8.0;
  const Plan p = plan(in);
  ASSERT_FALSE(p.plunges.empty());
  int held = 0;
  for (const Plunge& q : p.plunges) {
    EXPECT_GE(q.z, -8.0 + in.floorAllowance - 1e-12);
    EXPECT_GE(q.approachZ, q.z);
    EXPECT_GE(q.retractZ, q.z);
    held += q.z == -8.0 + in.floorAllowance;
  }
  EXPECT_GT(held, 0);  // the deep half stops at the final depth
  // The stock left below the final depth is said to be the final depth's.
  const auto why = std::find_if(p.warnings.begin(), p.warnings.end(),
                                [](const std::string& w) { return w.find("stay above the floor") != std::string::npos; });
  ASSERT_NE(why, p.warnings.end());
  EXPECT_THAT(*why, HasSubstr("the final depth stops plunges"));
  // Plunges over the floor above it keep their own stop heights.
  in.floor.finalDepth.reset();
  const Plan free = plan(in);
  ASSERT_EQ(free.plunges.size(), p.plunges.size());
  for (size_t i = 0; i < p.plunges.size(); ++i)
    EXPECT_EQ(p.plunges[i].z, std::max(free.plunges[i].z, -8.0 + in.floorAllowance));
  in.floor.finalDepth = 1.0;
  EXPECT_THAT(planError(in), HasSubstr("final_depth"));
}
