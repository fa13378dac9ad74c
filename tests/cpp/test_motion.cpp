#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <string>

#include "depth.hpp"
#include "floor.hpp"
#include "plunge/gcode.hpp"
#include "heightfield.hpp"
#include "motion.hpp"
#include "plunge/plan.hpp"
#include "region.hpp"

#include "testutil.hpp"

using namespace plunge;
using ::testing::HasSubstr;

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
      EXPECT_NEAR(dist(*q.leadOut, {q.x, q.y}), in.motion.leadOut, 1e-9);
      EXPECT_GE(region.wallDistance(*q.leadOut, 100), r + in.radialAllowance - 1e-9);
      // Into cut stock, or grazing at its flanks: no material farther than half
      // the lead-out beyond the plunge's hole (two of this raster's cells apart).
      EXPECT_LE(f.bite({q.x, q.y}, *q.leadOut, c, q.z), 0.5 * in.motion.leadOut + 0.2) << i;
      f.cut(*q.leadOut, c, q.z);
    }
    if (i + 1 < p.plunges.size()) {
      const Plunge& n = p.plunges[i + 1];
      Vec2 from = q.leadOut ? *q.leadOut : Vec2{q.x, q.y};
      for (Vec2 v : q.via) {  // the way around
        EXPECT_GE(q.retractZ, f.highestAlong(from, v, 0.5 * q.diameter - 0.05)) << i;
        from = v;
      }
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
  in.motion.stockAwareHeights = false;
  in.motion.leadOut = 0;
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
namespace {
struct HandMadeBox {
  const Region region{{{0, 0}, {100, 0}, {100, 60}, {0, 60}}, {}};
  const std::unique_ptr<FloorSurface> floor = makeFlatFloor(-20);
  const DepthSolver depths{*floor, region.minCorner(), region.maxCorner(), 2.0};
  MotionOptions o = [] {
    MotionOptions m;
    m.tools = ToolTable({{20, 1, 150}});
    m.material = Material(std::nullopt, 0);
    m.safeZ = 10;
    m.settings.leadOut = 1.0;
    return m;
  }();
};
}  // namespace

// Levels: every other one runs the path backwards, so it starts where the one
// above ended; a tool with an engagement limit keeps its order (it keeps each
// plunge within the limit).
TEST(Motion, EveryOtherLevelStartsWhereTheOneAboveEnded) {
  for (const bool limited : {false, true}) {
    HandMadeBox box;
    Tool t{20, 1, 150};
    t.fluteLength = 12.0;
    if (limited) t.maxEngagement = 15.0;
    box.o.tools = ToolTable({t});
    std::vector<Plunge> row;
    for (double x : {15.0, 35.0, 55.0, 75.0}) row.push_back(plungeOf(box.o.tools.all().front(), {x, 30.0}, -20.0));
    const Levels split = splitIntoLevels(row, box.o);
    const std::vector<Plunge>& levels = split.plunges;
    ASSERT_EQ(split.levels, 2);
    ASSERT_EQ(levels.size(), 8u);
    for (size_t k = 0; k < 4; ++k) {
      EXPECT_EQ(levels[k].level, 0);
      EXPECT_EQ(levels[4 + k].level, 1);
      EXPECT_DOUBLE_EQ(levels[k].x, row[k].x);
      EXPECT_DOUBLE_EQ(levels[4 + k].x, row[limited ? k : 3 - k].x) << "limited " << limited;
    }
  }
}

// Motion on its own: two plunges of a row, made by hand, with nothing but the
// machine's options (no plan input). The second cuts a crescent beside the
// first: it rapids down to just above the stock, leads out back into the first
// hole, and the first retracts no higher than the move over the stock needs.
TEST(Motion, OnItsOwnOptions) {
  const HandMadeBox box;
  const Region& region = box.region;
  const DepthSolver& depths = box.depths;
  const MotionOptions& o = box.o;
  const Motion plan =
      planMotion(region, depths, {plungeOf(o.tools.byId(1), {30, 30}, -20), plungeOf(o.tools.byId(1), {38, 30}, -20)}, o);
  const Plunge &a = plan.plunges[0], &b = plan.plunges[1];
  EXPECT_DOUBLE_EQ(a.approachZ, o.material.topZ() + o.settings.rapidClearance);  // uncut stock under the first
  EXPECT_DOUBLE_EQ(a.retractZ, o.material.topZ() + o.settings.rapidClearance);   // the stock along the move is top_z
  EXPECT_DOUBLE_EQ(b.approachZ, o.material.topZ() + o.settings.rapidClearance);  // part of its disk is still uncut
  ASSERT_TRUE(b.leadOut.has_value());
  EXPECT_NEAR(dist(*b.leadOut, {38, 30}), 1.0, 1e-9);
  EXPECT_LT(b.leadOut->x, 38.0);  // toward the first hole, the only cut space
  EXPECT_DOUBLE_EQ(b.retractZ, o.safeZ);  // the last plunge of its tool
  EXPECT_NEAR(b.engagement, 8.0, 2 * stockOf(o.tools.all(), o.material, region).spacing());
  EXPECT_EQ(plan.stats.leadOuts + plan.stats.noLeadOutMaterial + plan.stats.noLeadOutWalls, 2);
  EXPECT_NEAR(plan.stats.travelLength, dist(a.leadOut ? *a.leadOut : Vec2{30, 30}, {38, 30}), 1e-9);
  EXPECT_EQ(plan.stats.estimatedMinutes, motionMinutes(plan.plunges, o, false));
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
    std::vector<Plunge> ring;
    for (int k = 0; k < 6; ++k)
      ring.push_back(
          plungeOf(o.tools.byId(1), Vec2{50, 30} + Vec2{std::cos(k * kPi / 3), std::sin(k * kPi / 3)} * 9.0, -20 + step));
    ring.push_back(plungeOf(o.tools.byId(1), {50, 30}, -20));
    const Motion moved = planMotion(region, depths, ring, o);
    Plan plan;
    plan.plunges = moved.plunges;
    const Plunge& deep = plan.plunges.back();
    if (step <= o.settings.leadOut) {
      ASSERT_TRUE(deep.leadOut && deep.leadOutZ);
      EXPECT_NEAR(dist(*deep.leadOut, {50, 30}), o.settings.leadOut, 1e-9);
      EXPECT_GE(*deep.leadOutZ, -20 + step - 1e-9);  // clear of the steps
      EXPECT_LE(*deep.leadOutZ, -20 + step + 0.01);  // and no higher than they need
      EXPECT_EQ(moved.stats.raisedLeadOuts, 1);
      PlanInput in;
      in.tools = o.tools.all();
      const std::string g = planToGcode(in, plan), feedDown = "G1 Z-20.0000 F150.0000\nG1 Z";
      const size_t at = g.rfind(feedDown);  // the deep plunge feeds up, then out
      ASSERT_NE(at, std::string::npos) << g;
      EXPECT_NEAR(std::stod(g.substr(at + feedDown.size())), *deep.leadOutZ, 1e-3);
      EXPECT_EQ(g.substr(g.find('\n', at + feedDown.size()) + 1, 4), "G1 X");
    } else {
      EXPECT_FALSE(deep.leadOut);  // the steps are higher than the lead-out is long
      EXPECT_EQ(moved.stats.raisedLeadOuts, 0);
      EXPECT_GE(moved.stats.noLeadOutMaterial, 1);
    }
    EXPECT_EQ(moved.stats.estimatedMinutes, motionMinutes(moved.plunges, o, false));
  }
}

// Pecks where a plunge drills a deep hole into solid: its axis in uncut
// material deeper than the tool's peck depth (three diameters unless given).
// Replayed on a fresh height field: every such plunge is pecked, a peck at
// most the peck depth below the material's top or the peck before, the last
// short of the bottom; a plunge with its axis in a hole (a crescent beside
// removed material) never is. Without pecking, none, and a shorter estimate.
TEST(Motion, PecksDeepHolesIntoSolid) {
  PlanInput in = pocket();
  in.floor.surface.z = -60;
  in.tools = {{16, 1, 100}, {8, 2, 100}};
  in.tools[1].peckDepth = 10;
  for (bool limited : {false, true}) {
    for (Tool& t : in.tools) t.maxEngagement = limited ? std::optional<double>(0.25 * t.diameter) : std::nullopt;
    const Plan p = plan(in);
    HeightField f({-15, -15}, {135, 95}, 0.1, in.topZ);
    int pecked = 0, holes = 0;
    for (const Plunge& q : p.plunges) {
      const Tool& t = q.toolId == 1 ? in.tools[0] : in.tools[1];
      const double peck = t.peckDepth > 0 ? t.peckDepth : 3 * t.diameter;
      // Material (or none) within 0.5 mm all round the axis: the rasters agree.
      double top = f.heightAt({q.x, q.y}), low = top;
      for (Vec2 d : {Vec2{0.5, 0}, Vec2{-0.5, 0}, Vec2{0, 0.5}, Vec2{0, -0.5}}) {
        top = std::max(top, f.heightAt(Vec2{q.x, q.y} + d));
        low = std::min(low, f.heightAt(Vec2{q.x, q.y} + d));
      }
      const bool hole = low - q.z > peck + 0.2;
      holes += hole;
      if (top < q.z + 0.01) {
        EXPECT_TRUE(q.pecks.empty()) << "a crescent";
      }
      if (hole) {
        EXPECT_FALSE(q.pecks.empty()) << q.x << "," << q.y;
      }
      double above = f.heightAt({q.x, q.y});
      for (double at : q.pecks) {
        EXPECT_LE(above - at, peck + 1e-9);
        EXPECT_GT(at, q.z);
        above = at;
      }
      if (!q.pecks.empty()) {
        EXPECT_LE(above - q.z, peck + 1e-9);
      }
      pecked += !q.pecks.empty();
      f.cut({q.x, q.y}, cutterOf(t), q.z);
      if (q.leadOut) f.cut(*q.leadOut, cutterOf(t), q.z);
    }
    EXPECT_GT(holes, 0) << limited;
    EXPECT_EQ(pecked, p.stats.peckedPlunges);
    PlanInput off = in;
    off.motion.peck = false;
    const Plan none = plan(off);
    EXPECT_EQ(none.stats.peckedPlunges, 0);
    for (const Plunge& q : none.plunges) EXPECT_TRUE(q.pecks.empty());
    EXPECT_LT(none.stats.estimatedMinutes, p.stats.estimatedMinutes);
  }
}

// Every limit a plan breaks is said: which, the worst and where, and why; a
// warning for people and a record for programs. Plunges made by hand, each
// breaking one limit: a ridge left between two holes, cut across (the
// engagement along one radius, most of it); a sliver thinner than the min
// engagement; a non-centre-cutting tool into solid; a plunge deeper than its
// flutes.
TEST(Motion, SaysEveryLimitItBreaks) {
  HandMadeBox box;
  Tool t{20, 1, 150};
  t.maxEngagement = 5;
  t.minEngagement = 3;
  t.fluteLength = 15;
  Tool core{16, 2, 150};
  core.centerCutting = false;
  core.coreDiameter = 5;
  box.o.tools = ToolTable({t, core});
  const Tool& a = box.o.tools.byId(1);
  std::vector<Plunge> ps = {plungeOf(a, {18, 30}, -10), plungeOf(a, {40, 30}, -10),  // two holes: a ridge 2 mm wide
                            plungeOf(a, {29, 30}, -10),                  // along it: its length, not its width
                            plungeOf(a, {29, 31}, -10),                  // a sliver
                            plungeOf(a, {70, 30}, -20),                  // 20 mm deep: the flutes are 15
                            plungeOf(box.o.tools.byId(2), {70, 50}, -5)};  // a core onto solid
  ps[0].start = ps[1].start = ps[4].start = true;
  const Said plan = planMotion(box.region, box.depths, ps, box.o).said;
  std::map<std::string, BrokenLimit> said;
  for (const BrokenLimit& b : plan.broken) said[b.limit] = b;
  ASSERT_EQ(said.count("max_engagement"), 1u);
  EXPECT_NEAR(said["max_engagement"].at.x, 29, 1e-9);
  EXPECT_GT(said["max_engagement"].worst, 9.0);  // the ridge's 2 mm width would have kept the limit
  EXPECT_DOUBLE_EQ(said["max_engagement"].asked, 5);
  ASSERT_EQ(said.count("min_engagement"), 1u);
  EXPECT_NEAR(said["min_engagement"].at.y, 31, 1e-9);
  EXPECT_LT(said["min_engagement"].worst, 3);
  ASSERT_EQ(said.count("flute_length"), 1u);
  EXPECT_NEAR(said["flute_length"].worst, 20, 0.5);
  EXPECT_NEAR(said["flute_length"].at.x, 70, 1e-9);
  ASSERT_EQ(said.count("core_diameter"), 1u);
  EXPECT_NEAR(said["core_diameter"].at.y, 50, 1e-9);
  EXPECT_EQ(plan.warnings.size(), plan.broken.size());
  for (size_t i = 0; i < plan.broken.size(); ++i) {
    EXPECT_FALSE(plan.broken[i].why.empty());
    EXPECT_THAT(plan.warnings[i], HasSubstr("the worst at (")) << plan.warnings[i];
    EXPECT_THAT(plan.warnings[i], HasSubstr(plan.broken[i].why));
  }
}
