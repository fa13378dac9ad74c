// The plan's pictures (svg.hpp): one view per question.
#include <algorithm>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "plunge/svg.hpp"
#include "testutil.hpp"

using namespace plunge;
using ::testing::HasSubstr;
using ::testing::Not;

namespace {

// The <circle .../> elements of a picture, each as its text.
std::vector<std::string> circles(const std::string& svg) {
  std::vector<std::string> out;
  for (size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1))
    out.push_back(svg.substr(at, svg.find("/>", at) - at));
  return out;
}

// The circle element drawn for a plunge's disk (its centre, y drawn downwards, and radius).
std::string diskOf(const Plunge& p) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "cx=\"%.3f\" cy=\"%.3f\" r=\"%.3f\"", p.x, -p.y, p.diameter / 2);
  return buf;
}

size_t count(const std::vector<std::string>& elements, const std::string& what) {
  size_t n = 0;
  for (const std::string& e : elements) n += e.find(what) != std::string::npos;
  return n;
}

// Each <text> element's text, its x and its font size.
struct Text {
  std::string what;
  double x = 0.0, size = 0.0;
};
std::vector<Text> texts(const std::string& svg) {
  std::vector<Text> out;
  for (size_t at = svg.find("<text"); at != std::string::npos; at = svg.find("<text", at + 1)) {
    Text t;
    t.x = std::stod(svg.substr(svg.find("x=\"", at) + 3));
    t.size = std::stod(svg.substr(svg.find("font-size=\"", at) + 11));
    const size_t from = svg.find('>', at) + 1;
    t.what = svg.substr(from, svg.find("</text>", from) - from);
    out.push_back(t);
  }
  return out;
}

}  // namespace

// The legend names what the depths were found on, and each of its lines fits
// the picture: at 0.45 em a character (less than a sans-serif font's mean
// width) none runs past the view box's right edge.
TEST(Svg, PlanLegendSaysTheFloorKindAndFitsThePicture) {
  PlanInput in = planInputFromJson(test::smallJobJson());
  in.floor.surface.kind = Floor::Kind::Expression;
  in.floor.surface.expression = "-10 + sin(x / 9)";
  const Plan p = plan(in);
  const std::string svg = planToSvg(in, p, SvgView::Plan);
  const size_t box = svg.find("viewBox=\"") + 9;
  std::istringstream view(svg.substr(box, svg.find('"', box) - box));
  double vx = 0, vy = 0, vw = 0, vh = 0;
  view >> vx >> vy >> vw >> vh;
  const std::vector<Text> lines = texts(svg);
  EXPECT_EQ(std::count_if(lines.begin(), lines.end(), [](const Text& t) { return t.what == "depths on the floor's expression"; }), 1);
  for (const Text& t : lines) EXPECT_LE(t.x + 0.45 * t.size * t.what.size(), vx + vw) << t.what;
}

TEST(Svg, PlanViewDrawsEveryPlungeItsToursAndALegend) {
  PlanInput in = planInputFromJson(test::smallJobJson());
  const Plan p = plan(in);
  const std::string svg = planToSvg(in, p, SvgView::Plan);
  const std::vector<std::string> cs = circles(svg);
  for (const Plunge& q : p.plunges) EXPECT_GE(count(cs, diskOf(q)), 1u) << diskOf(q);
  // The disks, a legend swatch and a first-plunge ring per tool.
  EXPECT_EQ(cs.size(), p.plunges.size() + 2 * p.stats.perTool.size());
  size_t tours = 0;
  for (size_t at = svg.find("<polyline"); at != std::string::npos; at = svg.find("<polyline", at + 1)) ++tours;
  EXPECT_GE(tours, p.stats.perTool.size());
  EXPECT_THAT(svg, HasSubstr("T4"));
  EXPECT_THAT(svg, Not(HasSubstr("stop height")));  // not this view's question
  EXPECT_EQ(svg.rfind("</svg>"), svg.size() - 7);
}

TEST(Svg, StockViewShowsWhatIsLeftAndEveryBrokenLimit) {
  PlanInput in = planInputFromJson(test::smallJobJson());
  in.covering.minCoverage = 0.9999;  // more than the wall band lets the disks cover: said, and marked
  in.covering.maxWallStock = 0.0;
  const Plan p = plan(in);
  const std::string svg = planToSvg(in, p, SvgView::Stock);
  ASSERT_FALSE(p.uncovered.empty());
  EXPECT_THAT(svg, HasSubstr("fill=\"#e00000\""));  // what the disks leave, in red
  EXPECT_THAT(svg, Not(HasSubstr("<polyline")));        // no tour here
  const std::vector<std::string> cs = circles(svg);
  for (const Plunge& q : p.plunges) EXPECT_EQ(count(cs, diskOf(q)), 1u) << diskOf(q);  // faint outlines
  for (size_t k = 0; k < p.broken.size() && k < 6; ++k) {
    EXPECT_THAT(svg, HasSubstr(std::to_string(k + 1) + ": " + p.broken[k].limit + " broken"));
  }
  if (p.broken.empty()) {
    EXPECT_THAT(svg, HasSubstr("every limit kept"));
  }
}

TEST(Svg, HeightsOnlyOverASculpturedFloorDeepestOnTop) {
  PlanInput in = planInputFromJson(test::smallJobJson());
  EXPECT_EQ(svgViews(in, plan(in)), (std::vector<SvgView>{SvgView::Plan, SvgView::Stock}));
  in.floor.surface.kind = Floor::Kind::Expression;
  in.floor.surface.expression = "-20 + 0.05 * x";
  const Plan p = plan(in);
  ASSERT_EQ(svgViews(in, p).size(), 3u);
  const std::string svg = planToSvg(in, p, SvgView::Heights);
  const std::vector<std::string> cs = circles(svg);
  ASSERT_EQ(cs.size(), p.plunges.size());
  // Drawn from the highest stop to the deepest, so the deepest stays in sight.
  std::vector<double> drawn;
  for (const std::string& c : cs)
    for (const Plunge& q : p.plunges)
      if (c.find(diskOf(q)) != std::string::npos) {
        drawn.push_back(q.z);
        break;
      }
  ASSERT_EQ(drawn.size(), cs.size());
  for (size_t k = 1; k < drawn.size(); ++k) EXPECT_LE(drawn[k], drawn[k - 1]);
  EXPECT_LT(drawn.back(), drawn.front());  // the floor slopes: heights differ
}

// Rest plunging: the plan view draws the material the plan started from
// behind the disks, inside the pocket only, dark where the stock is whole.
TEST(Svg, PlanViewShowsTheMaterialBeforeAsItsBackground) {
  PlanInput in = test::rectanglePocket();
  in.material = MaterialGrid{{-20, -20}, 1.0, 160, 120, std::vector<double>(160 * 120, -5.0)};
  for (size_t j = 0; j < 120; ++j)
    for (size_t i = 0; i < 20; ++i) in.material->top[j * 160 + i] = in.topZ;  // x < 0: the wall's side, whole
  for (size_t j = 0; j < 120; ++j)
    for (size_t i = 20; i < 60; ++i) in.material->top[j * 160 + i] = in.topZ;  // 0 < x < 40: untouched
  const Plan p = plan(in);
  const std::string svg = planToSvg(in, p, SvgView::Plan);
  EXPECT_THAT(svg, HasSubstr("material before it"));
  const std::string dark = "fill=\"rgb(160,145,120)\"";
  EXPECT_THAT(svg, HasSubstr(dark));  // the untouched third
  // Nothing drawn outside the pocket: no block starts left of its wall.
  for (size_t at = svg.find(dark); at != std::string::npos; at = svg.find(dark, at + 1)) {
    const size_t x = svg.rfind("<rect x=\"", at);
    EXPECT_GE(std::stod(svg.substr(x + 9)), -1e-9);
  }
  in.material.reset();
  EXPECT_THAT(planToSvg(in, plan(in), SvgView::Plan), Not(HasSubstr("material before it")));
}

// A holder that stops plunges: the stop heights are drawn over a flat floor
// too, a red ring on each plunge it stopped, counted in the legend. A holder
// out of reach draws none.
TEST(Svg, HeightsMarkThePlungesAHolderStopped) {
  PlanInput in = planInputFromJson(test::smallJobJson());
  in.floor.surface.z = -60.0;
  EXPECT_EQ(svgViews(in, plan(in)).size(), 2u);
  for (Tool& t : in.tools) {
    t.stickOut = 200.0;
    t.holderDiameter = 2.5 * t.diameter;
  }
  EXPECT_EQ(svgViews(in, plan(in)).size(), 2u);
  for (Tool& t : in.tools) t.stickOut = 40.0;
  const Plan p = plan(in);
  ASSERT_EQ(svgViews(in, p).size(), 3u);
  const long held = std::count_if(p.plunges.begin(), p.plunges.end(), [](const Plunge& q) { return q.holderLimited; });
  ASSERT_GT(held, 0);
  const std::string svg = planToSvg(in, p, SvgView::Heights);
  long rings = 0;
  for (size_t at = svg.find("stroke=\"#e00000\""); at != std::string::npos; at = svg.find("stroke=\"#e00000\"", at + 1))
    ++rings;
  EXPECT_EQ(rings, held);
  EXPECT_THAT(svg, HasSubstr(std::to_string(held) + " plunges stopped above their depth by the holder")) << svg;
}
