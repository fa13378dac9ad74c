#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "plunge/error.hpp"
#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "plunge/summary.hpp"
#include "testutil.hpp"

using namespace plunge;
using ::testing::HasSubstr;

namespace {

PlanInput neckInput() {
  PlanInput in = planInputFromJson(test::readData("shapes/neck.json"));
  in.choice.automatic = true;
  in.choice.library.clear();
  int id = 1;
  for (double d : {32.0, 25.0, 20.0, 12.0, 8.0, 6.0}) in.choice.library.push_back({d, id++, 100.0 + 10 * d});
  in.tools.clear();
  return in;
}

}  // namespace

TEST(Selection, TimeModelAddsUpThePlan) {
  PlanInput in = planInputFromJson(test::readData("shapes/convex.json"));
  in.motion.timeModel = {8000.0, 4000.0, 30.0};
  const Plan p = plan(in);
  std::map<int, double> feed;
  for (const Tool& t : in.tools) feed[t.id] = t.feed;
  // Each plunge: rapid down from the last retract height to its approach
  // height, feed to depth and along the lead-out, rapid up to its retract
  // height; rapids between plunges; a tool change per tool.
  auto minutes = [&](bool atSafe) {
    double m = 0.0, z = in.safeZ;
    for (size_t i = 0; i < p.plunges.size(); ++i) {
      const Plunge& q = p.plunges[i];
      const double approach = atSafe ? in.safeZ : q.approachZ, retract = atSafe ? in.safeZ : q.retractZ;
      m += (z - approach) / 4000.0 + (approach - q.z) / feed[q.toolId] + (retract - q.z) / 4000.0;
      if (q.leadOut) m += dist(*q.leadOut, {q.x, q.y}) / feed[q.toolId];
      if (i) {
        const Plunge& b = p.plunges[i - 1];
        Vec2 at = b.leadOut ? *b.leadOut : Vec2{b.x, b.y};
        for (Vec2 v : atSafe ? std::vector<Vec2>{} : b.via) {  // around the wall band
          m += dist(at, v) / 8000.0;
          at = v;
        }
        m += dist(at, {q.x, q.y}) / 8000.0;
      }
      z = retract;
    }
    return m + p.stats.perTool.size() * 0.5;
  };
  EXPECT_NEAR(p.stats.estimatedMinutes, minutes(false), 1e-9 * minutes(false));
  EXPECT_NEAR(p.stats.minutesAtSafeHeight, minutes(true), 1e-9 * minutes(true));
  // Feeding only through material saves time.
  EXPECT_LT(p.stats.estimatedMinutes, p.stats.minutesAtSafeHeight);
}

// Every set the choice looked at (the subsets of the candidates with the
// smallest, and the library as given) planned in full: its true minutes.
static std::map<std::vector<double>, double> plannedTruth(const PlanInput& in, const ToolSelection& sel) {
  std::map<std::vector<double>, double> truth;
  for (const ToolSetResult& r : sel.sets) {
    PlanInput sub = in;
    sub.choice.automatic = false;
    for (double d : r.diameters)
      for (const Tool& t : in.choice.library)
        if (t.diameter == d) sub.tools.push_back(t);
    truth[r.diameters] = plan(sub).stats.estimatedMinutes;
  }
  return truth;
}

// The choice against every set planned in full: it plans one set in full (the
// best estimate, or the library as given when no set beats it by more than the
// estimate can tell), comes within a few per cent of the true optimum, its
// estimates are within 5 % of the true times (5.3), and every bound is a true
// lower bound (5.4).
static void expectAGoodChoice(const PlanInput& in, bool estimatesHonest) {
  const Plan chosen = plan(in);
  ASSERT_TRUE(chosen.selection);
  const ToolSelection& sel = *chosen.selection;
  const std::map<std::vector<double>, double> truth = plannedTruth(in, sel);
  double best = 1e300;
  for (const auto& [set, minutes] : truth) best = std::min(best, minutes);
  EXPECT_LE(chosen.stats.estimatedMinutes, 1.03 * best);
  int planned = 0;
  for (const ToolSetResult& r : sel.sets) {
    planned += r.evaluated;
    const double real = truth.at(r.diameters);
    EXPECT_LE(r.bound, real + 1e-9) << r.diameters.size();  // a true lower bound
    if (r.evaluated) {
      EXPECT_NEAR(r.minutes, real, 1e-9 * real);
    }
    const double estimate = r.evaluated ? r.estimate : r.minutes;
    if (estimatesHonest && r.plunges > 0) {
      EXPECT_NEAR(estimate, real, 0.05 * real) << r.diameters.size();
    }
    // A pruned subtree's bound holds for every set with its tools and the same
    // largest one (those the subtree adds smaller candidates to among them).
    if (r.subtree && r.diameters.size() >= 2)
      for (const auto& [set, minutes] : truth)
        if (set.front() == r.diameters.front() &&
            std::includes(set.begin(), set.end(), r.diameters.begin(), r.diameters.end() - 1,
                          std::greater<double>())) {
          EXPECT_LE(r.bound, minutes);
        }
  }
  EXPECT_EQ(planned, 1);  // one plan in full: the choice costs one plan and the placements
  // The plan uses exactly the chosen tools.
  std::vector<double> used;
  for (const ToolCount& t : chosen.stats.perTool) used.push_back(t.diameter);
  EXPECT_EQ(used, sel.chosen);
}

TEST(Selection, ChoosesNearTheEnumeratedOptimum) {
  const PlanInput in = neckInput();
  const Plan chosen = plan(in);
  ASSERT_TRUE(chosen.selection);
  const ToolSelection& sel = *chosen.selection;
  // The neck of the dumbbell-like shape is found and gives a neck tool.
  ASSERT_FALSE(sel.necks.empty());
  EXPECT_GE(sel.parts.size(), 2u);
  ASSERT_FALSE(sel.chosen.empty());
  // Every set has the smallest candidate, the tool that reaches all the core
  // the library's smallest reaches (12 mm passes the 16 mm neck): the chosen
  // plan cuts as much of the core as the whole library's.
  EXPECT_EQ(sel.chosen.back(), sel.candidates.back());
  PlanInput all = in;
  all.choice.automatic = false;
  all.tools = in.choice.library;
  const Plan whole = plan(all);
  EXPECT_GE(chosen.stats.coreCoverage, whole.stats.coreCoverage - 1e-4);
  EXPECT_LE(chosen.stats.maxWallStockLeft, in.covering.maxWallStock + 0.01);
  // The library as given is among the sets.
  EXPECT_TRUE(std::any_of(sel.sets.begin(), sel.sets.end(),
                          [](const ToolSetResult& r) { return r.diameters.size() == 6; }));
  expectAGoodChoice(in, true);
}

// With engagement limits (more plunges, placed by the growth, which the
// estimate does not see) and stock-aware heights (shorter approaches, the
// default) the bound stays below every set's true time and the choice near the optimum.
TEST(Selection, LowerBoundHoldsWithLimitsAndStockAwareHeights) {
  PlanInput in = neckInput();
  ASSERT_TRUE(in.motion.stockAwareHeights);
  for (Tool& t : in.choice.library) t.maxEngagement = 0.5 * t.diameter;
  expectAGoodChoice(in, false);
}

// Tool changes that cost as much as the plunges of a tool that barely cuts:
// the choice leaves it out, and says what that saves.
TEST(Selection, LeavesOutAToolThatCostsMoreThanItSaves) {
  PlanInput in = planInputFromJson(test::readData("shapes/convex.json"));
  in.choice.library = in.tools;
  for (Tool& t : in.choice.library) t.feed = 1200.0;
  in.tools.clear();
  in.choice.automatic = true;
  const Plan p = plan(in);
  ASSERT_TRUE(p.selection);
  EXPECT_LT(p.selection->chosen.size(), in.choice.library.size());
  expectAGoodChoice(in, true);
  PlanInput all = planInputFromJson(test::readData("shapes/convex.json"));
  for (Tool& t : all.tools) t.feed = 1200.0;
  EXPECT_LT(p.stats.estimatedMinutes, plan(all).stats.estimatedMinutes);
  const std::string summary = planSummary(p);
  EXPECT_THAT(summary, HasSubstr("left out")) << summary;
  EXPECT_THAT(summary, HasSubstr("saves about")) << summary;
}

TEST(Selection, WeightOnToolCountPrefersFewerTools) {
  PlanInput in = neckInput();
  in.choice.weights.weightTime = 0.0;
  in.choice.weights.weightTools = 1.0;
  const Plan p = plan(in);
  EXPECT_EQ(p.selection->chosen.size(), 1u);  // the smallest alone reaches everything
}

TEST(Selection, Deterministic) {
  const PlanInput in = neckInput();
  test::expectSamePlunges(plan(in), plan(in));
}

TEST(Selection, SetsThatCannotBePlannedAreSkippedWithTheirReason) {
  // A plunge mill that does not cut its 8 mm core, and 10 and 6 mm end mills:
  // with the 6 mm alone it has no tool to drill its start holes (a pocket
  // whose corners need the 6 mm tool).
  PlanInput in = neckInput();
  const PlanInput concave = planInputFromJson(test::readData("shapes/concave.json"));
  in.boundary = concave.boundary;
  in.islands = concave.islands;
  in.choice.library.clear();
  Tool mill{20.0, 1, 300.0};
  mill.centerCutting = false;
  mill.coreDiameter = 8.0;
  in.choice.library = {mill, {10.0, 2, 200.0}, {6.0, 3, 160.0}};
  const Plan p = plan(in);
  ASSERT_TRUE(p.selection);
  const auto& chosen = p.selection->chosen;
  const bool withMill = std::find(chosen.begin(), chosen.end(), 20.0) != chosen.end();
  EXPECT_TRUE(!withMill || std::find(chosen.begin(), chosen.end(), 10.0) != chosen.end());
  int refused = 0;
  for (const ToolSetResult& r : p.selection->sets)
    if (!r.refused.empty()) {
      ++refused;
      EXPECT_FALSE(r.evaluated);
      EXPECT_THAT(r.refused, HasSubstr("does not cut at its centre")) << r.refused;
      EXPECT_NE(std::find(r.diameters.begin(), r.diameters.end(), 20.0), r.diameters.end());
      EXPECT_EQ(std::find(r.diameters.begin(), r.diameters.end(), 10.0), r.diameters.end());
    }
  EXPECT_EQ(refused, 1);  // {20, 6}: every other set plans
  // Only when no set can be planned is it an error, with the reason: two plunge
  // mills and nothing to drill their start holes (found before any set is tried).
  Tool small = mill;
  small.diameter = 12.0;
  small.id = 2;
  small.coreDiameter = 6.0;
  in.choice.library = {mill, small};
  try {
    plan(in);
    FAIL() << "planned without a centre-cutting tool";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_THAT(what, HasSubstr("does not cut at its centre")) << what;
  }
}

TEST(Selection, BadLibrary) {
  PlanInput in = neckInput();
  in.choice.library.clear();
  EXPECT_THROW(plan(in), Error);
  in = neckInput();
  in.choice.library[1].diameter = -3;
  try {
    plan(in);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("tool_library[1]")) << e.what();
  }
}
