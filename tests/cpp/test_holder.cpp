// Holders and shanks (holder.hpp), checked by replaying the plan on a raster
// of this file's own: the part (outside the boundary, inside the islands)
// stands at top_z, the pocket's material is lowered by each plunge and
// lead-out in the posted order, and at every move each tool's shank and holder
// must keep the clearance from it. Nothing of the planner's stock models
// (Touched, HeightField) is used.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "plunge/json.hpp"
#include "plunge/plan.hpp"

#include "testutil.hpp"

using namespace plunge;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

namespace {

// The deep pocket of the issue that asked for holders: 150 x 90 x 70 mm, a
// 20 x 20 mm island; a 20 mm plunger with 40 mm flutes held 60 mm from its
// tip in a 40 mm holder.
PlanInput deepPocket(double stickOut = 60.0) {
  PlanInput in;
  in.boundary = {{0, 0}, {150, 0}, {150, 90}, {0, 90}};
  in.islands = {{{65, 35}, {85, 35}, {85, 55}, {65, 55}}};
  Tool t{20, 1, 300};
  t.fluteLength = 40.0;
  t.stickOut = stickOut;
  t.holderDiameter = 40.0;
  in.tools = {t};
  in.topZ = 0.0;
  in.safeZ = 5.0;
  in.floor.surface.z = -70.0;
  in.radialAllowance = 0.3;
  in.floorAllowance = 0.2;
  return in;
}

// The issue's second tool: a slim 12 mm plunger with 50 mm flutes held 95 mm
// out in a 32 mm holder (id 2).
Tool slimTool() {
  Tool slim{12, 2, 300};
  slim.fluteLength = 50.0;
  slim.stickOut = 95.0;
  slim.holderDiameter = 32.0;
  return slim;
}

// The replay's raster: cells of `h` mm over the pocket and 60 mm around.
class Raster {
 public:
  Raster(const PlanInput& in, double h) : h_(h), top_(in.topZ) {
    loops_ = {in.boundary};
    loops_.insert(loops_.end(), in.islands.begin(), in.islands.end());
    nx_ = static_cast<int>((150 + 2 * kMargin) / h_) + 1;
    ny_ = static_cast<int>((90 + 2 * kMargin) / h_) + 1;
    z_.assign(static_cast<size_t>(nx_) * ny_, top_);
  }
  Vec2 centre(int i, int j) const { return {-kMargin + (i + 0.5) * h_, -kMargin + (j + 0.5) * h_}; }
  // A flat tool of radius r moved from a to b with its tip at z (a plunge: a == b).
  void cut(Vec2 a, Vec2 b, double r, double z) {
    forCells(a, b, r, [&](int i, int j) {
      if (test::bruteInside(loops_, centre(i, j))) z_[idx(i, j)] = std::min(z_[idx(i, j)], z);
    });
  }
  // The highest material left in the pocket farther than d from its walls
  // and than `corner` from the boundary's corners (a round tool leaves them).
  double highestBeyond(double d, double corner) const {
    double best = -INFINITY;
    for (int j = 0; j < ny_; ++j)
      for (int i = 0; i < nx_; ++i) {
        const Vec2 c = centre(i, j);
        if (!test::bruteInside(loops_, c) || test::bruteWallDistance(loops_, c) < d) continue;
        if (std::any_of(loops_[0].begin(), loops_[0].end(), [&](Vec2 v) { return dist(v, c) < corner; })) continue;
        best = std::max(best, z_[idx(i, j)]);
      }
    return best;
  }
  // The highest material (the part included) within reach of the segment.
  double highest(Vec2 a, Vec2 b, double reach) const {
    double best = -INFINITY;
    forCells(a, b, reach, [&](int i, int j) { best = std::max(best, z_[idx(i, j)]); });
    return best;
  }

 private:
  static constexpr double kMargin = 60.0;
  size_t idx(int i, int j) const { return static_cast<size_t>(j) * nx_ + i; }
  template <class F>
  void forCells(Vec2 a, Vec2 b, double r, F f) const {
    const int i0 = std::max(0, static_cast<int>((std::min(a.x, b.x) - r + kMargin) / h_) - 1);
    const int i1 = std::min(nx_ - 1, static_cast<int>((std::max(a.x, b.x) + r + kMargin) / h_) + 1);
    const int j0 = std::max(0, static_cast<int>((std::min(a.y, b.y) - r + kMargin) / h_) - 1);
    const int j1 = std::min(ny_ - 1, static_cast<int>((std::max(a.y, b.y) + r + kMargin) / h_) + 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i)
        if (distanceToSegment({a, b}, centre(i, j)) <= r) f(i, j);
  }
  double h_, top_;
  int nx_ = 0, ny_ = 0;
  std::vector<Loop> loops_;
  std::vector<double> z_;
};

// Each tool's parts above its flutes, as cylinders: from (mm above the tip), radius.
struct Part {
  double from, radius;
};

std::vector<Part> partsOf(const Tool& t, double pocketDiagonal) {
  std::vector<Part> parts;
  if (!t.stickOut) return parts;
  if (t.shankDiameter && *t.shankDiameter > t.diameter) parts.push_back({*t.fluteLength, 0.5 * *t.shankDiameter});
  parts.push_back({*t.stickOut, t.holderDiameter ? 0.5 * *t.holderDiameter : 2 * pocketDiagonal});
  return parts;
}

struct Collision {
  int count = 0;
  double worst = 0.0;  // mm into the clearance
  std::string first;
  double left = 0.0;  // the highest material left beyond the wall band
};

// Replays the posted moves: each plunge's feed down, its lead-out, the rapid
// to the next plunge at its retract height. The raster's cut disks are
// `slack` mm short of the planner's exact ones.
Collision replay(const PlanInput& in, const Plan& p, double h = 0.25) {
  Raster stock(in, h);
  const double slack = 0.75 * h, c = in.motion.holderClearance;
  std::map<int, Tool> tools;
  for (const Tool& t : in.tools) tools[t.id] = t;
  Collision out;
  auto check = [&](const Tool& t, Vec2 a, Vec2 b, double z, const std::string& what) {
    for (const Part& part : partsOf(t, 100.0)) {
      const double gap = z + part.from - stock.highest(a, b, part.radius + c - slack);
      if (gap < c - 1e-6) {
        if (out.count++ == 0) out.first = what;
        out.worst = std::max(out.worst, c - gap);
      }
    }
  };
  for (size_t i = 0; i < p.plunges.size(); ++i) {
    const Plunge& q = p.plunges[i];
    const Tool& t = tools.at(q.toolId);
    const Vec2 at{q.x, q.y};
    check(t, at, at, q.z, "plunge " + std::to_string(i));
    stock.cut(at, at, 0.5 * q.diameter, q.z);
    Vec2 end = at;
    if (q.leadOut) {
      const double z = q.leadOutZ.value_or(q.z);
      check(t, at, *q.leadOut, z, "lead-out " + std::to_string(i));
      stock.cut(at, *q.leadOut, 0.5 * q.diameter, z);
      end = *q.leadOut;
    }
    if (i + 1 < p.plunges.size() && p.plunges[i + 1].toolId == q.toolId) {
      // The rapid across, the way around the wall band included: the holder
      // keeps the clearance, the flutes pass over the material.
      auto across = [&](Vec2 a, Vec2 b) {
        const std::string what = "move after " + std::to_string(i);
        check(t, a, b, q.retractZ, what);
        if (stock.highest(a, b, 0.5 * q.diameter - slack) > q.retractZ + 1e-6) {
          if (out.count++ == 0) out.first = what + " (the flutes)";
          out.worst = std::max(out.worst, stock.highest(a, b, 0.5 * q.diameter - slack) - q.retractZ);
        }
      };
      for (Vec2 v : q.via) {
        across(end, v);
        end = v;
      }
      across(end, {p.plunges[i + 1].x, p.plunges[i + 1].y});
    }
  }
  const double rMin = 0.5 * in.tools.back().diameter + in.radialAllowance;
  out.left = stock.highestBeyond(in.radialAllowance + in.covering.maxWallStock + 2 * h, 1.5 * rMin);
  return out;
}

}  // namespace

// The issue's pocket: without the holder, the plan reaches the floor beside
// the walls and the holder goes 9.7 mm into the part there (checked here
// first, so the replay can fail); with it, no move of the holder comes within
// the clearance, and the plunges it stops are said.
TEST(Holder, DeepPocketNoPostedMoveMeetsThePartOrTheStock) {
  PlanInput blind = deepPocket();
  blind.tools[0].stickOut.reset();
  blind.tools[0].holderDiameter.reset();
  const Plan unaware = plan(blind);
  PlanInput seen = blind;
  seen.tools[0] = deepPocket().tools[0];
  const Collision before = replay(seen, unaware);
  EXPECT_GT(before.count, 0);
  EXPECT_GT(before.worst, 5.0);

  const PlanInput in = deepPocket();
  const Plan p = plan(in);
  const Collision after = replay(in, p);
  EXPECT_EQ(after.count, 0) << after.first << ", " << after.worst << " mm into the clearance";
  const int limited = static_cast<int>(std::count_if(p.plunges.begin(), p.plunges.end(),
                                                     [](const Plunge& q) { return q.holderLimited; }));
  EXPECT_GT(limited, 0);
  ASSERT_EQ(p.stats.perTool.size(), 1u);
  EXPECT_EQ(p.stats.perTool[0].holderLimited, limited);
  // Said: which tool, the stick-out that would reach, where.
  const auto b = std::find_if(p.broken.begin(), p.broken.end(), [](const BrokenLimit& x) { return x.limit == "stick_out"; });
  ASSERT_NE(b, p.broken.end());
  // Counted by place: a tool's levels at one place are one.
  std::set<std::pair<double, double>> places;
  for (const Plunge& q : p.plunges)
    if (q.holderLimited) places.insert({q.x, q.y});
  EXPECT_EQ(b->count, static_cast<int>(places.size()));
  EXPECT_DOUBLE_EQ(b->asked, 60.0);
  // Beside a wall the face must stay above top_z + clearance, so the tip at
  // 61 mm above: 70.2 - 61 = 9.2 mm more stick-out reaches the floor there.
  EXPECT_NEAR(b->worst, 60.0 + 70.0 - 0.2 - 59.0 + 0.0, 0.05) << b->why;
  EXPECT_THAT(b->why, HasSubstr("40.00 mm holder of tool 1"));
  EXPECT_THAT(b->why, HasSubstr("a stick-out of"));
  EXPECT_LT(test::bruteWallDistance({in.boundary, in.islands[0]}, b->at), 20.0 + 1.0 + 1e-6);
  // Every limited plunge stops above the floor: it is raised, never lowered.
  for (const Plunge& q : p.plunges) {
    if (q.holderLimited) {
      EXPECT_GT(q.z, in.floor.surface.z + in.floorAllowance + 1e-6);
    }
  }
}

// The issue's second tool: a slim 12 mm plunger held 95 mm out. Where the
// holder stops the 20 mm one (beside the walls and the island), the slim one
// goes to the floor; nothing is left to say, and no holder meets the stock.
TEST(Holder, TheToolThatReachesGoesDeep) {
  PlanInput in = deepPocket();
  in.tools.push_back(slimTool());
  const Plan p = plan(in);
  const Collision c = replay(in, p);
  EXPECT_EQ(c.count, 0) << c.first << ", " << c.worst << " mm into the clearance";
  // The replay's own floor: every cell beyond the wall band is cut to the floor.
  EXPECT_LE(c.left, in.floor.surface.z + in.floorAllowance + 1e-6);
  EXPECT_TRUE(std::none_of(p.broken.begin(), p.broken.end(), [](const BrokenLimit& x) { return x.limit == "stick_out"; }));
  // The slim tool reaches the floor beside the walls, where the holder stops the other.
  int deepAtWalls = 0;
  for (const Plunge& q : p.plunges)
    if (q.toolId == 2 && q.z < in.floor.surface.z + in.floorAllowance + 1e-6 &&
        test::bruteWallDistance({in.boundary, in.islands[0]}, {q.x, q.y}) < 20.0 + 1.0)
      ++deepAtWalls;
  EXPECT_GT(deepAtWalls, 20);
  // Without it, the same replay finds the floor left where the holder stopped.
  const PlanInput alone = deepPocket();
  const Collision a = replay(alone, plan(alone));
  EXPECT_GT(a.left, in.floor.surface.z + 5.0);
}

// The automatic tool choice counts the holders: its estimates cannot see them,
// so where the set it estimates best leaves the floor to a holder, the whole
// library is planned too and kept when it leaves less.
TEST(Holder, TheToolChoiceKeepsTheToolThatReaches) {
  PlanInput in = deepPocket();
  const Tool slim = slimTool();
  Tool small{6, 3, 300};  // short: held 45 mm out (the choice always keeps the smallest)
  small.fluteLength = 20.0;
  small.stickOut = 45.0;
  small.holderDiameter = 30.0;
  in.choice.automatic = true;
  in.choice.library = {in.tools[0], slim, small};
  in.tools.clear();
  // A tool change so dear that the estimates alone choose the 20 mm plunger.
  in.motion.timeModel.toolChangeSeconds = 1800.0;
  const Plan p = plan(in);
  EXPECT_TRUE(std::any_of(p.plunges.begin(), p.plunges.end(), [](const Plunge& q) { return q.toolId == 2; }));
  // What is still said is the short 6 mm plunger's, in the corners only it fits.
  for (const BrokenLimit& b : p.broken) {
    if (b.limit == "stick_out") {
      EXPECT_THAT(b.why, HasSubstr("of tool 3"));
    }
  }
  ASSERT_TRUE(p.selection);
  PlanInput used = in;
  used.choice.automatic = false;
  used.tools = used.choice.library;
  const Collision c = replay(used, p);
  EXPECT_EQ(c.count, 0) << c.first;
  EXPECT_LE(c.left, in.floor.surface.z + in.floorAllowance + 1e-6);
}

// Levels that stay low: in a 120 x 80 x 60 mm pocket cut in two levels, the
// moves between the second level's plunges go around the cusps the first left
// standing along the walls (the wall band) instead of climbing over them, and
// neither the flutes nor the holder meet anything on the way.
TEST(Holder, LevelsStayLowAroundTheWallBand) {
  PlanInput in = deepPocket(70.0);
  in.boundary = {{0, 0}, {120, 0}, {120, 80}, {0, 80}};
  in.islands.clear();
  in.floor.surface.z = -60.0;
  const Plan p = plan(in);
  ASSERT_EQ(p.stats.levels, 2);
  const Collision c = replay(in, p);
  EXPECT_EQ(c.count, 0) << c.first << ", " << c.worst << " mm into the clearance";
  int moves = 0, high = 0, around = 0;
  for (size_t i = 0; i + 1 < p.plunges.size(); ++i) {
    const Plunge& q = p.plunges[i];
    if (q.level != 1 || p.plunges[i + 1].level != 1) continue;
    ++moves;
    high += q.retractZ > in.topZ;
    around += !q.via.empty();
  }
  EXPECT_GT(moves, 30);
  EXPECT_LE(high, 2) << "of " << moves << " moves between the second level's plunges";
  EXPECT_GT(around, 10);
}

// Short flutes and a holder just above them: three levels, the moves between
// the deeper ones pass the walls and the island within the holder's reach.
TEST(Holder, MovesBetweenDeepLevelsKeepTheHolderClear) {
  for (const bool leadOut : {true, false}) {
    PlanInput in = deepPocket(30.0);
    in.tools[0].fluteLength = 25.0;
    in.motion.leadOut = leadOut ? 1.0 : 0.0;
    const Plan p = plan(in);
    EXPECT_GE(p.stats.levels, 3);
    const Collision c = replay(in, p);
    EXPECT_EQ(c.count, 0) << c.first << ", " << c.worst << " mm into the clearance";
  }
}

// The stick-out the plan names reaches: planned with it, no plunge is stopped.
TEST(Holder, TheStickOutSaidReaches) {
  const Plan p = plan(deepPocket());
  const auto b = std::find_if(p.broken.begin(), p.broken.end(), [](const BrokenLimit& x) { return x.limit == "stick_out"; });
  ASSERT_NE(b, p.broken.end());
  const PlanInput longer = deepPocket(b->worst + 0.01);
  const Plan q = plan(longer);
  for (const Plunge& x : q.plunges) EXPECT_FALSE(x.holderLimited) << x.x << ", " << x.y << ", " << x.z;
  EXPECT_EQ(replay(longer, q).count, 0);
}

// A holder that never comes near changes nothing: the same plan as without it.
TEST(Holder, AHolderOutOfReachChangesNothing) {
  PlanInput with = deepPocket(200.0);
  PlanInput without = with;
  without.tools[0].stickOut.reset();
  without.tools[0].holderDiameter.reset();
  const Plan a = plan(with), b = plan(without);
  test::expectSamePlunges(a, b);
  for (size_t i = 0; i < a.plunges.size(); ++i) EXPECT_EQ(a.plunges[i].retractZ, b.plunges[i].retractZ) << i;
  EXPECT_TRUE(a.broken.empty() || std::none_of(a.broken.begin(), a.broken.end(),
                                               [](const BrokenLimit& x) { return x.limit == "stick_out"; }));
}

// A holder whose diameter is not given is as wide as the pocket: its face
// never goes below top_z + the clearance, anywhere.
TEST(Holder, AnUnknownHolderIsAsWideAsThePocket) {
  PlanInput in = deepPocket(50.0);
  in.tools[0].holderDiameter.reset();
  in.motion.holderClearance = 2.0;
  const Plan p = plan(in);
  for (const Plunge& q : p.plunges) EXPECT_GE(q.z + 50.0, in.topZ + 2.0 - 1e-9);
  EXPECT_EQ(replay(in, p).count, 0);
  const auto b = std::find_if(p.broken.begin(), p.broken.end(), [](const BrokenLimit& x) { return x.limit == "stick_out"; });
  ASSERT_NE(b, p.broken.end());
  EXPECT_THAT(b->why, HasSubstr("its diameter not given"));
  EXPECT_NEAR(b->worst, 70.0 - 0.2 + 2.0, 1e-6);
}

// A slim tool on a wider shank: the shank, from the flutes' top, keeps clear too.
TEST(Holder, AWiderShankKeepsClear) {
  PlanInput in = deepPocket();
  Tool t{8, 1, 200};
  t.fluteLength = 20.0;
  t.shankDiameter = 12.0;
  t.stickOut = 120.0;
  t.holderDiameter = 30.0;
  in.tools = {t};
  in.floor.surface.z = -40.0;
  in.boundary = {{0, 0}, {60, 0}, {60, 40}, {0, 40}};
  in.islands.clear();
  const Plan p = plan(in);
  EXPECT_EQ(replay(in, p).count, 0);
  const auto b = std::find_if(p.broken.begin(), p.broken.end(), [](const BrokenLimit& x) { return x.limit == "stick_out"; });
  ASSERT_NE(b, p.broken.end());
  EXPECT_THAT(b->why, HasSubstr("12.00 mm shank of tool 1"));
  EXPECT_THAT(b->why, HasSubstr("flutes"));
}

// Read from JSON and written back; bad values named.
TEST(Holder, ReadFromTheInputAndRefusedWhenInconsistent) {
  const std::string base =
      R"({"boundary": [[0,0],[100,0],[100,60],[0,60]], "floor": {"z": -50}, "holder_clearance": 1.5, "tools": [)";
  const PlanInput in =
      planInputFromJson(base + R"({"diameter": 16, "flute_length": 25, "stick_out": 45, "holder_diameter": 32, "shank_diameter": 16}]})");
  EXPECT_DOUBLE_EQ(*in.tools[0].stickOut, 45.0);
  EXPECT_DOUBLE_EQ(*in.tools[0].holderDiameter, 32.0);
  EXPECT_DOUBLE_EQ(*in.tools[0].shankDiameter, 16.0);
  EXPECT_DOUBLE_EQ(in.motion.holderClearance, 1.5);
  const Plan p = plan(in);
  const nlohmann::json out = planToValue(p);
  EXPECT_EQ(out["stats"]["per_tool"][0]["stick_out"], 45.0);
  EXPECT_EQ(out["stats"]["per_tool"][0]["holder_diameter"], 32.0);
  EXPECT_GT(out["stats"]["per_tool"][0]["holder_limited"].get<int>(), 0);

  struct Bad {
    std::string tool, message;
  };
  for (const Bad& bad : std::vector<Bad>{
           {R"({"diameter": 16, "holder_diameter": 32})", "need the stick_out"},
           {R"({"diameter": 16, "flute_length": 25, "stick_out": 20})", "shorter than its flute_length"},
           {R"({"diameter": 16, "stick_out": 40, "shank_diameter": 20})", "must say where the shank starts"},
       }) {
    EXPECT_THAT(test::planError(planInputFromJson(base + bad.tool + "]}")), HasSubstr(bad.message)) << bad.tool;
  }
  EXPECT_THAT([&] { planInputFromJson(base + R"({"diameter": 16, "stick_out": -4}]})"); },
              ThrowsMessage<Error>(HasSubstr("stick_out must be > 0")));
  PlanInput negative = planInputFromJson(base + R"({"diameter": 16}]})");
  negative.motion.holderClearance = -1.0;
  EXPECT_THAT(test::planError(negative), HasSubstr("holder_clearance must be >= 0"));
}
