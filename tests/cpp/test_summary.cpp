// The plan in one line (summary.hpp): its figures are the plan's own.
#include <gtest/gtest.h>
#include <string>
#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "plunge/summary.hpp"
#include "testutil.hpp"

using namespace plunge;

TEST(Summary, SaysThePlansOwnFigures) {
  const PlanInput in = planInputFromJson(test::smallJobJson());
  Plan p = plan(in);
  const std::string s = planSummary(p);
  EXPECT_EQ(s.rfind(std::to_string(p.stats.plungeCount) + " plunges (", 0), 0u) << s;
  for (const ToolCount& t : p.stats.perTool)
    EXPECT_NE(s.find("T" + std::to_string(t.toolId) + " "), std::string::npos) << s;
  EXPECT_NE(s.find("coverage "), std::string::npos) << s;
  EXPECT_NE(s.find("lead-outs on " + std::to_string(p.stats.leadOuts) + " plunges"), std::string::npos) << s;
  EXPECT_EQ(s.find("raised"), std::string::npos) << s;  // a flat floor: none
  // Raised lead-outs and start holes are said only when there are some.
  p.stats.raisedLeadOuts = 3;
  p.stats.startHoles = 2;
  const std::string t = planSummary(p);
  EXPECT_NE(t.find(", 3 of them raised"), std::string::npos) << t;
  EXPECT_NE(t.find("2 start holes"), std::string::npos) << t;
}
