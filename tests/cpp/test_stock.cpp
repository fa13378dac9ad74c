// The floor-stock step (stock.hpp): what it adds brings the stock under the
// limit where a plunger can, and its work stays within its budget on a floor
// no plunger follows.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "depth.hpp"
#include "floor.hpp"
#include "region.hpp"
#include "stock.hpp"

using namespace plunge;

namespace {

// A w x h mm pocket over an expression floor, a first covering of 10 mm
// ball plungers every 6 mm (no gaps) at their exact stop heights, and the grid they cut.
struct Wavy {
  Wavy(const char* expression, double w, double h)
      : floor(makeExpressionFloor(expression)),
        region(Loop{{0, 0}, {w, 0}, {w, h}, {0, h}}, {}),
        depths(*floor, region.minCorner(), region.maxCorner(), 0.5),
        tools(std::vector<Tool>{ball(1, 10.0), ball(2, 4.0)}),
        grid(region, *floor, {0.0, 0.0, 0.0, 0.5}) {
    for (double x = 5; x < region.maxCorner().x - 4; x += 6)
      for (double y = 5; y < region.maxCorner().y - 4; y += 6) {
        const Cutter c = cutterOf(tools.all().front());
        const CutDisk d{{x, y}, 1, depths.plungeHeight({x, y}, c, 0.0, 0.0)};
        grid.cut(d, c);
      }
  }
  static Tool ball(int id, double diameter) {
    Tool t;
    t.id = id;
    t.diameter = diameter;
    t.shape = CutterShape::Ball;
    return t;
  }
  FloorStockResult step(int budget) {
    FloorStockOptions o;
    o.maxFloorStock = 0.5;
    o.topZ = 0.0;
    o.maxSearches = budget;
    return plungeFloorStock(region, depths, tools, grid, o);
  }
  // The highest stock left where the smaller plunger reaches (2 mm and more
  // from the walls; nearer, only a ball's rim passes).
  double maxStock() const {
    double m = 0.0;
    for (size_t k = 0; k < grid.size(); ++k)
      if (region.wallDistance(grid.at(k), 10.0) >= 4.0 && !std::isnan(grid.stock(k))) m = std::max(m, grid.stock(k));
    return m;
  }
  std::unique_ptr<FloorSurface> floor;
  Region region;
  DepthSolver depths;
  ToolTable tools;
  StockGrid grid;
};

}  // namespace

TEST(FloorStock, BringsAFollowableFloorUnderTheLimit) {
  Wavy job("-10 + 1.5*sin(x/4)*cos(y/5)", 42, 30);
  const double before = job.maxStock();
  ASSERT_GT(before, 0.5);
  const FloorStockResult r = job.step(kFloorStockSearches);
  EXPECT_FALSE(r.outOfBudget);
  EXPECT_GT(r.added.size(), 0u);
  EXPECT_LT(r.searches, kFloorStockSearches);
  // The margin between samples is the step's own: the samples are under the limit.
  EXPECT_LE(job.maxStock(), 0.5 + 1e-9);
  for (const CutDisk& d : r.added) EXPECT_TRUE(d.forFloorStock);
}

TEST(FloorStock, StopsAtItsBudgetOnAFloorNoPlungerFollows) {
  // 0.6 mm waves 2 mm deep (sin(x*10)): every sample stays over the limit, and
  // without the budget the step searched for minutes.
  Wavy job("-10 + sin(x*10)", 24, 16);  // small: every depth search on it is slow
  const FloorStockResult r = job.step(40);
  EXPECT_TRUE(r.outOfBudget);
  // It stops before the next sample once the budget is spent: at most one
  // sample's candidates (two tools, 25 centres each) beyond it.
  EXPECT_GE(r.searches, 40);
  EXPECT_LE(r.searches, 40 + 2 * 25);
  EXPECT_GT(job.maxStock(), 0.5);
  // The same input, the same step.
  Wavy again("-10 + sin(x*10)", 24, 16);
  const FloorStockResult s = again.step(40);
  EXPECT_EQ(s.searches, r.searches);
  ASSERT_EQ(s.added.size(), r.added.size());
  for (size_t i = 0; i < r.added.size(); ++i) EXPECT_EQ(s.added[i].center, r.added[i].center);
}
