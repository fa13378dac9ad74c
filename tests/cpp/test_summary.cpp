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
