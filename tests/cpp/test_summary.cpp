// The plan in one line (summary.hpp): its figures are the plan's own.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <string>
#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "plunge/summary.hpp"
#include "testutil.hpp"

using namespace plunge;
using ::testing::HasSubstr;
using ::testing::Not;

TEST(Summary, SaysThePlansOwnFigures) {
  const PlanInput in = planInputFromJson(test::smallJobJson());
  Plan p = plan(in);
  const std::string s = planSummary(p);
  EXPECT_EQ(s.rfind(std::to_string(p.stats.plungeCount) + " plunges (", 0), 0u) << s;
  for (const ToolCount& t : p.stats.perTool)
    EXPECT_THAT(s, HasSubstr("T" + std::to_string(t.toolId) + " ")) << s;
  EXPECT_THAT(s, HasSubstr("coverage ")) << s;
  EXPECT_THAT(s, HasSubstr("lead-outs on " + std::to_string(p.stats.leadOuts) + " plunges")) << s;
  EXPECT_THAT(s, Not(HasSubstr("raised"))) << s;  // a flat floor: none
  // Raised lead-outs and start holes are said only when there are some.
  p.stats.raisedLeadOuts = 3;
  p.stats.startHoles = 2;
  const std::string t = planSummary(p);
  EXPECT_THAT(t, HasSubstr(", 3 of them raised")) << t;
  EXPECT_THAT(t, HasSubstr("2 start holes")) << t;
}

// The tool choice's outcome says what leaving plungers out does by the
// estimate, as it is: a saving, no difference, or more time, never "-0.0 min".
TEST(Summary, TheChoiceSaysWhatLeavingOutDoes) {
  auto selection = [](double libraryMinutes, double chosenEstimate) {
    ToolSelection sel;
    ToolSetResult library, chosen;
    library.diameters = {12, 8, 5};
    library.evaluated = true;
    library.plunges = 100;
    library.minutes = libraryMinutes;
    chosen.diameters = {5};
    chosen.evaluated = true;
    chosen.plunges = 300;
    chosen.estimate = chosenEstimate;
    chosen.minutes = chosenEstimate;
    sel.sets = {library, chosen};
    sel.chosen = {5};
    return choiceSummary(sel);
  };
  EXPECT_THAT(selection(10.0, 8.0), ::testing::HasSubstr("left out 12/8, which saves about 2.0 min by the estimate"));
  const std::string same = selection(10.0, 10.02);
  EXPECT_THAT(same, ::testing::HasSubstr("which takes as long by the estimate"));
  EXPECT_THAT(same, ::testing::Not(::testing::HasSubstr("-0.0")));
  EXPECT_THAT(selection(10.0, 10.4), ::testing::HasSubstr("whose estimate is about 0.4 min above"));
}
