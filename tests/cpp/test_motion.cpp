#include <gtest/gtest.h>

#include <memory>

#include "plunge/depth.hpp"
#include "plunge/floor.hpp"
#include "plunge/gcode.hpp"
#include "plunge/heightfield.hpp"
#include "plunge/motion.hpp"
#include "plunge/plan.hpp"
#include "plunge/region.hpp"

#include "testutil.hpp"

using namespace plunge;

namespace {

PlanInput pocket() { return test::rectanglePocket(); }

}  // namespace

// Replayed on a fresh height field: no rapid down or across below the stock,
// approaches below the safe height where the stock allows, lead-outs clear of
// walls and islands, into cut stock or grazing it at the flanks.
TEST(Motion, HeightsAndLeadOutsKeepClearOfTheStock) {
  const PlanInput in = pocket();
  const Plan p = plan(in);
  const Region region(in.boundary, in.islands);
  HeightField f({-15, -15}, {135, 95}, 0.1, in.topZ);
  int low = 0, leads = 0;
  for (size_t i = 0; i < p.plunges.size(); ++i) {
    const Plunge& q = p.plunges[i];
    const double r = 0.5 * q.diameter;
    EXPECT_GE(q.approachZ, f.highest({q.x, q.y}, r - 0.05)) << i;
    low += q.approachZ < in.safeZ;
    const Cutter c{CutterShape::Flat, r, 0.0};
    f.cut({q.x, q.y}, c, q.z);
    if (q.leadOut) {
      ++leads;
      EXPECT_NEAR(dist(*q.leadOut, {q.x, q.y}), in.leadOut, 1e-9);
      EXPECT_GE(region.wallDistance(*q.leadOut, 100), r + in.radialAllowance - 1e-9);
      // Into cut stock, or grazing at its flanks: no material farther than half
      // the lead-out beyond the plunge's hole (two of this raster's cells apart).
      EXPECT_LE(f.bite({q.x, q.y}, *q.leadOut, c, q.z), 0.5 * in.leadOut + 0.2) << i;
      f.cut(*q.leadOut, c, q.z);
    }
    if (i + 1 < p.plunges.size()) {
      const Plunge& n = p.plunges[i + 1];
      const Vec2 from = q.leadOut ? *q.leadOut : Vec2{q.x, q.y};
      EXPECT_GE(q.retractZ, f.highestAlong(from, {n.x, n.y}, 0.5 * q.diameter - 0.05)) << i;
      EXPECT_GE(q.retractZ, n.approachZ);
    }
  }
  EXPECT_GT(low, static_cast<int>(p.plunges.size()) / 2);
  EXPECT_GT(leads, 0);
  EXPECT_DOUBLE_EQ(p.plunges.back().retractZ, in.safeZ);
  EXPECT_LT(p.stats.estimatedMinutes, p.stats.minutesAtSafeHeight);
}

TEST(Motion, WithoutStockAwareHeightsEverythingAtSafeZ) {
  PlanInput in = pocket();
  in.stockAwareHeights = false;
  in.leadOut = 0;
  const Plan p = plan(in);
  for (const Plunge& q : p.plunges) {
    EXPECT_DOUBLE_EQ(q.approachZ, in.safeZ);
    EXPECT_DOUBLE_EQ(q.retractZ, in.safeZ);
    EXPECT_FALSE(q.leadOut);
  }
  EXPECT_NEAR(p.stats.estimatedMinutes, p.stats.minutesAtSafeHeight, 1e-12);
}

// Flutes of 5 mm over 12.2 mm of material: three levels, none cutting deeper than 5.
TEST(Motion, ShortFlutesCutInLevels) {
  PlanInput in = pocket();
  for (Tool& t : in.tools) t.fluteLength = 5.0;
  const Plan p = plan(in);
  EXPECT_EQ(p.stats.levels, 3);
  HeightField f({-15, -15}, {135, 95}, 0.1, in.topZ);
  for (const Plunge& q : p.plunges) {
    const Cutter c{CutterShape::Flat, 0.5 * q.diameter, 0.0};
    EXPECT_LE(f.contact({q.x, q.y}, c, q.z).deepest, 5.0 + 1e-6) << q.x << " " << q.y << " " << q.z;
    f.cut({q.x, q.y}, c, q.z);
    if (q.leadOut) f.cut(*q.leadOut, c, q.z);
  }
  EXPECT_TRUE(p.warnings.empty() || p.warnings.front().find("flute") == std::string::npos);
}

// A 100 x 60 mm box, flat floor at -20, one 20 mm tool, a 1 mm lead-out:
// the machine's options alone, for plunges made by hand.
struct HandMadeBox {
  const Region region{{{0, 0}, {100, 0}, {100, 60}, {0, 60}}, {}};
  const std::unique_ptr<FloorSurface> floor = makeFlatFloor(-20);
  const DepthSolver depths{*floor, region.minCorner(), region.maxCorner(), 2.0};
  MotionOptions o = [] {
    MotionOptions m;
    m.tools = ToolTable({{20, 1, 150}});
    m.topZ = 0;
    m.safeZ = 10;
    m.leadOut = 1.0;
    return m;
  }();
};

// Motion on its own: two plunges of a row, made by hand, with nothing but the
// machine's options (no plan input). The second cuts a crescent beside the
// first: it rapids down to just above the stock, leads out back into the first
// hole, and the first retracts no higher than the move over the stock needs.
TEST(Motion, OnItsOwnOptions) {
  const HandMadeBox box;
  const Region& region = box.region;
  const DepthSolver& depths = box.depths;
  const MotionOptions& o = box.o;
  Plan plan;
  plan.plunges = {plungeOf(o.tools.byId(1), {30, 30}, -20), plungeOf(o.tools.byId(1), {38, 30}, -20)};
  planMotion(region, depths, plan, o);
  const Plunge &a = plan.plunges[0], &b = plan.plunges[1];
  EXPECT_DOUBLE_EQ(a.approachZ, o.topZ + o.rapidClearance);  // uncut stock under the first
  EXPECT_DOUBLE_EQ(a.retractZ, o.topZ + o.rapidClearance);   // the stock along the move is top_z
  EXPECT_DOUBLE_EQ(b.approachZ, o.topZ + o.rapidClearance);  // part of its disk is still uncut
  ASSERT_TRUE(b.leadOut.has_value());
  EXPECT_NEAR(dist(*b.leadOut, {38, 30}), 1.0, 1e-9);
  EXPECT_LT(b.leadOut->x, 38.0);  // toward the first hole, the only cut space
  EXPECT_DOUBLE_EQ(b.retractZ, o.safeZ);  // the last plunge of its tool
  EXPECT_NEAR(b.engagement, 8.0, 2 * stockOf(o.tools.all(), o.topZ, region).spacing());
  EXPECT_EQ(plan.stats.leadOuts + plan.stats.noLeadOutMaterial + plan.stats.noLeadOutWalls, 2);
  EXPECT_NEAR(plan.stats.travelLength, dist(a.leadOut ? *a.leadOut : Vec2{30, 30}, {38, 30}), 1e-9);
  EXPECT_EQ(plan.stats.estimatedMinutes, motionMinutes(plan, o, false));
}

// A plunge deeper than the six around it sits in a ring of their steps: its
// lead-out feeds up to the steps' height first, if they are no higher than the
// lead-out is long; the G-code and the time model follow.
TEST(Motion, ALeadOutRisesOutOfTheStepsAround) {
  const HandMadeBox box;
  const Region& region = box.region;
  const DepthSolver& depths = box.depths;
  const MotionOptions& o = box.o;
  for (double step : {0.8, 1.5}) {
    Plan plan;
    for (int k = 0; k < 6; ++k)
      plan.plunges.push_back(
          plungeOf(o.tools.byId(1), Vec2{50, 30} + Vec2{std::cos(k * kPi / 3), std::sin(k * kPi / 3)} * 9.0, -20 + step));
    plan.plunges.push_back(plungeOf(o.tools.byId(1), {50, 30}, -20));
    planMotion(region, depths, plan, o);
    const Plunge& deep = plan.plunges.back();
    if (step <= o.leadOut) {
      ASSERT_TRUE(deep.leadOut && deep.leadOutZ);
      EXPECT_NEAR(dist(*deep.leadOut, {50, 30}), o.leadOut, 1e-9);
      EXPECT_GE(*deep.leadOutZ, -20 + step - 1e-9);  // clear of the steps
      EXPECT_LE(*deep.leadOutZ, -20 + step + 0.01);  // and no higher than they need
      EXPECT_EQ(plan.stats.raisedLeadOuts, 1);
      PlanInput in;
      in.tools = o.tools.all();
      const std::string g = planToGcode(in, plan), feedDown = "G1 Z-20.0000 F150.0000\nG1 Z";
      const size_t at = g.rfind(feedDown);  // the deep plunge feeds up, then out
      ASSERT_NE(at, std::string::npos) << g;
      EXPECT_NEAR(std::stod(g.substr(at + feedDown.size())), *deep.leadOutZ, 1e-3);
      EXPECT_EQ(g.substr(g.find('\n', at + feedDown.size()) + 1, 4), "G1 X");
    } else {
      EXPECT_FALSE(deep.leadOut);  // the steps are higher than the lead-out is long
      EXPECT_EQ(plan.stats.raisedLeadOuts, 0);
      EXPECT_GE(plan.stats.noLeadOutMaterial, 1);
    }
    EXPECT_EQ(plan.stats.estimatedMinutes, motionMinutes(plan, o, false));
  }
}
