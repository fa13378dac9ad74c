// The plan's picture (svg.hpp).
#include <gtest/gtest.h>
#include <string>
#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "plunge/svg.hpp"
#include "testutil.hpp"

using namespace plunge;

TEST(Svg, SvgDrawsEveryPlungeAndALegend) {
  PlanInput in = planInputFromJson(test::smallJobJson());
  const Plan p = plan(in);
  const std::string svg = planToSvg(in, p);
  size_t circles = 0;
  for (size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) ++circles;
  EXPECT_EQ(circles, p.plunges.size() + p.stats.perTool.size());  // plunges + legend swatches
  EXPECT_NE(svg.find("% covered"), std::string::npos);
  EXPECT_NE(svg.find("T4"), std::string::npos);
  EXPECT_EQ(svg.rfind("</svg>"), svg.size() - 7);
}
