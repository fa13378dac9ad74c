#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "plunge/error.hpp"
#include "plunge/tools.hpp"

using namespace plunge;
using ::testing::HasSubstr;

TEST(Tools, EngagementLimitFromTheCore) {
  Tool t{25, 1, 100};
  EXPECT_TRUE(std::isinf(engagementLimit(t)));
  t.centerCutting = false;
  t.coreDiameter = 9;
  EXPECT_DOUBLE_EQ(engagementLimit(t), 8.0);
  t.maxEngagement = 5;
  EXPECT_DOUBLE_EQ(engagementLimit(t), 5.0);
}

TEST(Tools, StartHolesNeedACentreCuttingToolAsWideAsTheCore) {
  Tool cutter{25, 1, 100};
  cutter.centerCutting = false;
  cutter.coreDiameter = 10;
  EXPECT_THROW(startHoleTool({cutter, {8, 2, 100}}, cutter), Error);
  EXPECT_EQ(startHoleTool({cutter, {16, 3, 100}, {12, 2, 100}, {8, 4, 100}}, cutter).id, 2);
}

TEST(Tools, CutterAndCore) {
  Tool ball{12, 1, 100};
  ball.shape = CutterShape::Ball;
  EXPECT_DOUBLE_EQ(cutterOf(ball).radius, 6.0);
  EXPECT_DOUBLE_EQ(cutterOf(ball).cornerRadius, 6.0);
  Tool mill{20, 2, 100};
  EXPECT_DOUBLE_EQ(coreRadius(mill), 0.0);
  mill.centerCutting = false;
  mill.coreDiameter = 8;
  EXPECT_DOUBLE_EQ(coreRadius(mill), 4.0);
  const Plunge p = plungeOf(mill, {3, 4}, -7);
  EXPECT_EQ(p.toolId, 2);
  EXPECT_DOUBLE_EQ(p.diameter, 20.0);
  EXPECT_DOUBLE_EQ(p.z, -7.0);
}

// An id no tool has is the planner's fault, never bad input: one kind of
// error (the CLI exits 3, Python raises RuntimeError), whoever looks it up.
TEST(Tools, AnUnknownIdIsAnInternalError) {
  const ToolTable table({{20, 7, 100}, {10, 3, 100}});
  EXPECT_EQ(table.byId(3).diameter, 10.0);
  EXPECT_EQ(table.indexOf(7), 0u);
  EXPECT_THROW(table.byId(5), InternalError);
  EXPECT_THROW(table.indexOf(5), InternalError);
  try {
    table.byId(5);
  } catch (const Error&) {
    FAIL() << "an internal fault reported as bad input";
  } catch (const InternalError& e) {
    EXPECT_THAT(e.what(), HasSubstr("tool 5")) << e.what();
  }
}
