#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "plunge/progress.hpp"
#include "testutil.hpp"

using namespace plunge;

namespace {

PlanInput shape(const std::string& name) { return planInputFromJson(test::readData("shapes/" + name + ".json")); }

struct Seen {
  std::vector<double> fractions;
  std::vector<std::string> stages;
  std::thread::id thread;
  bool otherThread = false;
};

Progress recorder(Seen& seen, bool go = true) {
  seen.thread = std::this_thread::get_id();
  return Progress(
      [&seen, go](double f, const std::string& s) {
        seen.fractions.push_back(f);
        seen.stages.push_back(s);
        seen.otherThread = seen.otherThread || std::this_thread::get_id() != seen.thread;
        return go;
      },
      std::chrono::milliseconds(0));
}

}  // namespace

// Reported from the caller's thread only (both packing orders run in parallel),
// in order, through every stage; the plan is the one made without progress.
TEST(Progress, ReportsEveryStageInOrderOnTheCallersThread) {
  Seen seen;
  const Plan with = plan(shape("islands"), recorder(seen));
  const Plan without = plan(shape("islands"));
  ASSERT_GE(seen.fractions.size(), 4u);
  EXPECT_FALSE(seen.otherThread);
  for (size_t i = 1; i < seen.fractions.size(); ++i) EXPECT_GE(seen.fractions[i], seen.fractions[i - 1]);
  EXPECT_EQ(seen.fractions.front(), 0.0);
  EXPECT_GT(seen.fractions.back(), 0.8);
  EXPECT_LE(seen.fractions.back(), 1.0);
  for (const char* s : {"checking the pocket", "packing and covering", "plunge depths", "ordering the plunges"})
    EXPECT_NE(std::find(seen.stages.begin(), seen.stages.end(), s), seen.stages.end()) << s;
  test::expectSamePlunges(with, without);
}

// The callback saying no stops the plan with Cancelled, not a plunge::Error:
// the input is not at fault, and no stage that takes an Error for "no floor
// here" swallows it.
TEST(Progress, CallbackCancels) {
  static_assert(!std::is_base_of_v<Error, Cancelled>);
  Seen seen;
  EXPECT_THROW(plan(shape("islands"), recorder(seen, false)), Cancelled);
  EXPECT_EQ(seen.fractions.size(), 1u);  // nothing more was asked after "no"
  EXPECT_THAT([&] { plan(shape("convex"), recorder(seen, false)); },
              ::testing::ThrowsMessage<Cancelled>(::testing::StrEq("planning cancelled")));
}

// Cancelled from another thread (a GUI's cancel button) in the middle of packing.
TEST(Progress, CancelFromAnotherThread) {
  std::atomic<int> calls{0};
  Progress progress([&](double, const std::string&) { return ++calls < 1000000; }, std::chrono::milliseconds(0));
  std::thread canceller([&] {
    while (calls < 3) std::this_thread::yield();
    progress.cancel();
  });
  EXPECT_THROW(plan(shape("benchmark"), progress), Cancelled);
  canceller.join();
  EXPECT_TRUE(progress.cancelled());
}

// An exception from the callback (Python's KeyboardInterrupt) goes through as it is.
TEST(Progress, CallbackExceptionPropagates) {
  int calls = 0;
  Progress progress(
      [&](double, const std::string&) -> bool {
        if (++calls == 4) throw std::runtime_error("interrupted");  // while both packing orders run
        return true;
      },
      std::chrono::milliseconds(0));
  EXPECT_THROW(plan(shape("benchmark"), progress), std::runtime_error);
  EXPECT_EQ(calls, 4);
  EXPECT_TRUE(progress.cancelled());  // the other packing thread stopped too
}

// A plan through every stage (a sculptured floor with the floor-stock step,
// a section wider than the floor, flute levels, holders that stop plunges so
// that the tools they do not stop cover the rest and the plunges are posted
// twice).
static PlanInput throughEveryStage() {
  PlanInput in = test::rectanglePocket();
  in.floor.surface.kind = Floor::Kind::Expression;
  in.floor.surface.expression = "-12 + 2 * sin(x / 9) * cos(y / 7)";
  in.floor.sections = {{-6.0, {{-3, -3}, {123, -3}, {123, 83}, {-3, 83}}, {}}};
  for (Tool& t : in.tools) {
    t.fluteLength = 8.0;
    t.stickOut = 12.0;
    t.holderDiameter = 40.0;
  }
  in.tools.push_back({6, 3, 100});
  in.tools.back().stickOut = 40.0;
  in.tools.back().holderDiameter = 10.0;
  return in;
}

// Each stage is reported, and the fraction only rises.
TEST(Progress, RisesThroughEveryStage) {
  Seen seen;
  const Plan p = plan(throughEveryStage(), recorder(seen));
  ASSERT_FALSE(p.plunges.empty());
  for (size_t i = 1; i < seen.fractions.size(); ++i)
    EXPECT_GE(seen.fractions[i], seen.fractions[i - 1]) << seen.stages[i - 1] << " then " << seen.stages[i];
  for (const char* s : {"plunge depths", "plunges for the floor stock", "the wall band above the floor",
                        "ordering the plunges", "covering where holders stopped plunges", "heights and lead-outs",
                        "measuring the stock left"})
    EXPECT_NE(std::find(seen.stages.begin(), seen.stages.end(), s), seen.stages.end()) << s;
}

// The covering where holders stopped plunges ticks as it works (more reports
// than its stage's own), and a "no" at one of those ticks stops the plan.
TEST(Progress, TheReachStepTicksAndCancels) {
  const std::string reach = "covering where holders stopped plunges";
  Seen seen;
  plan(throughEveryStage(), recorder(seen));
  ASSERT_GE(std::count(seen.stages.begin(), seen.stages.end(), reach), 2);
  int inStage = 0;
  Progress progress([&](double, const std::string& s) { return s != reach || ++inStage < 2; },
                    std::chrono::milliseconds(0));
  EXPECT_THROW(plan(throughEveryStage(), progress), Cancelled);
  EXPECT_EQ(inStage, 2);
}

TEST(Progress, SubRangesMapFractions) {
  std::vector<double> got;
  Progress p([&](double f, const std::string&) { got.push_back(f); return true; }, std::chrono::milliseconds(0));
  const Progress half = p.sub(0.5, 1.0);
  half.stage(0.0, "a");
  half.stage(0.5, "b");
  half.sub(0.5, 1.0).stage(1.0, "c");
  EXPECT_EQ(got, (std::vector<double>{0.5, 0.75, 1.0}));
}

// Automatic tool choice plans several tool sets: one progress over all of them.
TEST(Progress, ToolSelectionStaysInRange) {
  PlanInput in = shape("neck");
  in.choice.automatic = true;
  in.choice.library = {{32, 1}, {20, 2}, {12, 3}, {6, 4}};
  in.tools.clear();
  Seen seen;
  plan(in, recorder(seen));
  ASSERT_FALSE(seen.fractions.empty());
  for (size_t i = 1; i < seen.fractions.size(); ++i) EXPECT_GE(seen.fractions[i], seen.fractions[i - 1] - 1e-12);
  EXPECT_LE(seen.fractions.back(), 1.0);
}

// Cancel anywhere: a plan cancelled at the first report inside each stage it
// goes through (a tick of its work, or the stage's own report where it has
// none) stops there with Cancelled, and reports nothing after the "no".
TEST(Progress, CancelsInEveryStage) {
  PlanInput in = shape("islands");
  in.floor.surface.kind = Floor::Kind::Expression;
  in.floor.surface.expression = "-20 + 2*sin(x/9)*cos(y/7)";
  for (Tool& t : in.tools) t.maxEngagement = 0.25 * t.diameter;
  Seen all;
  plan(in, recorder(all));
  std::vector<std::string> stages;
  for (const std::string& s : all.stages)
    if (std::find(stages.begin(), stages.end(), s) == stages.end()) stages.push_back(s);
  for (const char* s : {"analysing the floor", "packing and covering", "plunge depths", "ordering the plunges",
                        "growing the cut within the engagement limits", "heights and lead-outs",
                        "measuring the stock left"})
    EXPECT_NE(std::find(stages.begin(), stages.end(), s), stages.end()) << s;
  for (const std::string& stage : stages) {
    int seenInStage = 0, inStage = 0, after = 0;
    bool said = false;
    for (const std::string& s : all.stages) inStage += s == stage;
    Progress progress(
        [&](double, const std::string& s) {
          if (said) ++after;
          if (s != stage) return true;
          // The second report of the stage is a tick from its work, if it has one.
          said = ++seenInStage == std::min(inStage, 2);
          return !said;
        },
        std::chrono::milliseconds(0));
    EXPECT_THROW(plan(in, progress), Cancelled) << stage;
    EXPECT_TRUE(said) << stage;
    EXPECT_EQ(after, 0) << stage;
  }
}
