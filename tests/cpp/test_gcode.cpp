// The plan as RS-274 G-code (gcode.hpp), parsed back.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <string>
#include <vector>
#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "plunge/gcode.hpp"
#include "testutil.hpp"

using namespace plunge;
using ::testing::Not;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

namespace {

// The small job over a wavy floor, its tools limited to half their diameter:
// plunges stop at different heights, and some lead out raised.
std::string wavyLimitedJob() {
  std::string j = test::smallJobJson();
  auto swap = [&](const std::string& from, const std::string& to) { j.replace(j.find(from), from.size(), to); };
  swap(R"("floor": {"z": -10})", R"j("floor": {"expression": "-10 + 1.5*sin(0.15*x)*cos(0.2*y)"})j");
  swap(R"({"diameter": 12, "id": 4}, {"diameter": 6})",
       R"({"diameter": 12, "id": 4, "max_engagement": 6}, {"diameter": 6, "max_engagement": 3})");
  return j;
}

}  // namespace

// Checks the program against the plan; returns how many lead-outs it raises.
static int parsesBack(const PlanInput& in, const Plan& p) {
  std::istringstream g(planToGcode(in, p));
  std::string line;
  double x = NAN, y = NAN, z = NAN;
  int tool = -1;
  std::vector<Plunge> seen;
  std::vector<double> rapidHeights;  // z of the rapids across, before each plunge
  std::vector<Vec2> across;          // where the rapids across since the last plunge went
  std::vector<double> acrossZ;
  std::vector<int> changes;
  bool inHole = false;  // since the last feed down, no move sideways: a feed down goes on with the hole
  double dwell = 0;
  while (std::getline(g, line)) {
    if (line.empty() || line[0] == '(') continue;
    std::istringstream w(line);
    std::string word;
    std::map<char, double> v;
    std::vector<std::string> codes;
    while (w >> word) {
      if (word[0] == 'G' || word[0] == 'M') codes.push_back(word);
      else v[word[0]] = std::stod(word.substr(1));
    }
    if (v.count('T')) {
      tool = static_cast<int>(v['T']);
      changes.push_back(tool);
    }
    const bool rapid = !codes.empty() && codes[0] == "G0", feed = !codes.empty() && codes[0] == "G1";
    if (rapid && (v.count('X') || v.count('Y'))) {
      across.push_back({v.count('X') ? v['X'] : x, v.count('Y') ? v['Y'] : y});
      acrossZ.push_back(z);
    }
    if (!codes.empty() && codes[0] == "G4") dwell = v['P'];
    if ((rapid || feed) && (v.count('X') || v.count('Y'))) inHole = false;
    if (rapid && v.count('Z') && inHole && !seen.empty() && v['Z'] < z) {
      // Back into a pecked hole: to just above where the last peck stopped.
      const Plunge& q = seen.back();
      EXPECT_NEAR(z, q.approachZ, 1e-4) << "a peck clears the hole";
      EXPECT_GT(v['Z'], q.z);
      EXPECT_LE(v['Z'], q.z + in.motion.rapidClearance + 1e-4);
    }
    if (feed && v.count('Z') && inHole && !seen.empty() && v['Z'] < seen.back().z) {
      seen.back().pecks.push_back(seen.back().z);  // the stop before was a peck
      seen.back().z = v['Z'];
    } else if (feed && v.count('Z') && !seen.empty() && v['Z'] > z) {
      seen.back().leadOutZ = v['Z'];  // up before a raised lead-out
    } else if (feed && v.count('Z')) {
      EXPECT_TRUE(v.count('F'));
      Plunge q;
      q.x = x;
      q.y = y;
      q.toolId = tool;
      q.approachZ = z;  // where the feed starts
      q.z = v['Z'];
      // The rapids across before it: at one height, through the way's points.
      if (!acrossZ.empty()) rapidHeights.push_back(acrossZ.front());
      for (double h : acrossZ) EXPECT_NEAR(h, acrossZ.front(), 1e-9) << "a way across at one height";
      if (!seen.empty() && !across.empty()) seen.back().via.assign(across.begin(), across.end() - 1);
      across.clear();
      acrossZ.clear();
      seen.push_back(q);
      inHole = true;
    } else if (feed) {
      if (seen.empty()) {
        ADD_FAILURE() << "a feed sideways before any plunge";
        return -1;
      }
      seen.back().leadOut = Vec2{v['X'], v['Y']};
    }
    if (v.count('X')) x = v['X'];
    if (v.count('Y')) y = v['Y'];
    if (v.count('Z')) z = v['Z'];
  }
  if (seen.size() != p.plunges.size() || rapidHeights.size() != p.plunges.size()) {
    ADD_FAILURE() << seen.size() << " plunges and " << rapidHeights.size() << " rapids across for "
                  << p.plunges.size() << " plunges planned";
    return -1;
  }
  int leadOuts = 0, raised = 0;
  for (size_t i = 0; i < seen.size(); ++i) {
    const Plunge& q = p.plunges[i];
    EXPECT_NEAR(seen[i].x, q.x, 1e-4);
    EXPECT_NEAR(seen[i].y, q.y, 1e-4);
    EXPECT_NEAR(seen[i].z, q.z, 1e-4);
    EXPECT_NEAR(seen[i].approachZ, q.approachZ, 1e-4);
    EXPECT_EQ(seen[i].pecks.size(), q.pecks.size()) << i;
    for (size_t k = 0; k < std::min(seen[i].pecks.size(), q.pecks.size()); ++k)
      EXPECT_NEAR(seen[i].pecks[k], q.pecks[k], 1e-4);
    EXPECT_EQ(seen[i].toolId, q.toolId);
    EXPECT_EQ(seen[i].leadOut.has_value(), q.leadOut.has_value());
    if (q.leadOut && seen[i].leadOut) {
      ++leadOuts;
      EXPECT_NEAR(dist(*seen[i].leadOut, *q.leadOut), 0.0, 1e-3);
    }
    EXPECT_EQ(seen[i].leadOutZ.has_value(), q.leadOutZ.has_value());
    if (q.leadOutZ && seen[i].leadOutZ) {
      ++raised;
      EXPECT_NEAR(*seen[i].leadOutZ, *q.leadOutZ, 1e-4);
      EXPECT_GT(*q.leadOutZ, q.z);
      EXPECT_LE(*q.leadOutZ, q.z + in.motion.leadOut + 1e-9);
    }
    EXPECT_EQ(seen[i].via.size(), q.via.size()) << i;
    for (size_t k = 0; k < std::min(seen[i].via.size(), q.via.size()); ++k)
      EXPECT_NEAR(dist(seen[i].via[k], q.via[k]), 0.0, 1e-3) << i;
    // Across at the previous plunge's retract height (safe_z after a tool change).
    const bool first = i == 0 || p.plunges[i - 1].toolId != q.toolId;
    EXPECT_NEAR(rapidHeights[i], first ? in.safeZ : p.plunges[i - 1].retractZ, 1e-4);
    EXPECT_LE(q.approachZ, rapidHeights[i] + 1e-4);
  }
  EXPECT_GT(leadOuts, 0);
  EXPECT_EQ(changes.size(), p.stats.perTool.size());
  if (p.stats.peckedPlunges > 0) {
    EXPECT_DOUBLE_EQ(dwell, in.motion.peckDwell);
  }
  return raised;
}

// The G-code parsed back gives the plan: one tool change per tool, one feed
// plunge per plunge at its depth and position, from its approach height, its
// lead-out (fed up to its height first where raised), and rapids across at
// the retract height the plan gives.
TEST(Gcode, ParsesBackToThePlan) {
  for (const std::string& job : {test::smallJobJson(), wavyLimitedJob()}) {
    SCOPED_TRACE(job);
    const PlanInput in = planInputFromJson(job);
    const Plan p = plan(in);
    const int raised = parsesBack(in, p);
    EXPECT_EQ(raised, p.stats.raisedLeadOuts);
    if (job != test::smallJobJson()) {
      EXPECT_GT(raised, 0);
    }
  }
}

// A 60 mm deep pocket: the 12 and 8 mm plungers' holes into solid go deeper
// than three diameters and are pecked, in the program as planned (each peck
// up out of the hole and back to just above it, a dwell at the bottom).
TEST(Gcode, PecksDeepHolesAsPlanned) {
  std::string j = test::smallJobJson();
  auto swap = [&](const std::string& from, const std::string& to) { j.replace(j.find(from), from.size(), to); };
  swap(R"("floor": {"z": -10})", R"("floor": {"z": -60}, "peck_dwell": 0.5)");
  swap(R"({"diameter": 12, "id": 4}, {"diameter": 6})", R"({"diameter": 12, "id": 4}, {"diameter": 8})");
  const PlanInput in = planInputFromJson(j);
  const Plan p = plan(in);
  EXPECT_GT(p.stats.peckedPlunges, 0);
  parsesBack(in, p);
}

// Each plunge's feed is its tool's, found by the tool id as in every layer: a
// plunge of a tool the input lacks is the planner's fault, never a feed of 0.
TEST(Gcode, FeedsByToolIdAndRefusesAnUnknownOne) {
  PlanInput in = planInputFromJson(test::smallJobJson());
  in.tools[0].feed = 321;  // each tool its own feed
  in.tools[1].feed = 123;
  Plan p = plan(in);
  ASSERT_FALSE(p.plunges.empty());
  const std::string g = planToGcode(in, p);
  for (const Tool& t : in.tools) {
    const bool used = std::any_of(p.plunges.begin(), p.plunges.end(), [&](const Plunge& q) { return q.toolId == t.id; });
    std::ostringstream f;
    f << " F" << std::fixed << std::setprecision(4) << t.feed << "\n";
    EXPECT_EQ(used, g.find(f.str()) != std::string::npos) << t.id;
  }
  EXPECT_THAT(g, Not(HasSubstr(" F200.0000")));  // no default feed
  p.plunges.back().toolId = 999;
  EXPECT_THROW(planToGcode(in, p), InternalError);
}

// The spindle runs at each tool's speed (its own, or 100 m/min of cutting
// speed) and the coolant the input asks for is on, at every feed move; both
// are off at each tool change and at the end. Read back as a machine would.
TEST(Gcode, SpindleAndCoolantAreOnWhereverTheToolCuts) {
  for (const char* coolant : {"off", "flood", "mist"}) {
    SCOPED_TRACE(coolant);
    std::string j = test::smallJobJson();
    const std::string from = R"({"diameter": 12, "id": 4})";
    j.replace(j.find(from), from.size(), R"({"diameter": 12, "id": 4, "spindle_speed": 4321})");
    j.insert(j.rfind('}'), std::string(R"(, "coolant": ")") + coolant + "\"");
    const PlanInput in = planInputFromJson(j);
    const Plan p = plan(in);
    std::istringstream g(planToGcode(in, p));
    std::map<int, double> expected;
    for (const Tool& t : in.tools)
      expected[t.id] = t.spindleSpeed ? *t.spindleSpeed : std::round(100000.0 / (kPi * t.diameter));
    EXPECT_DOUBLE_EQ(expected.at(4), 4321.0);
    const std::string wanted = std::string(coolant) == "flood" ? "M8" : std::string(coolant) == "mist" ? "M7" : "";
    int tool = -1, feeds = 0;
    double speed = 0;  // 0: spindle stopped
    std::string on;    // the coolant code in force
    std::string line;
    while (std::getline(g, line)) {
      if (line.empty() || line[0] == '(') continue;
      std::istringstream w(line);
      std::string word;
      while (w >> word) {
        if (word[0] == 'T') {
          EXPECT_EQ(speed, 0) << "a tool change with the spindle on";
          EXPECT_EQ(on, "") << "a tool change with the coolant on";
          tool = std::stoi(word.substr(1));
        } else if (word == "M3") {
          std::string s;
          ASSERT_TRUE(w >> s) << line;
          ASSERT_EQ(s[0], 'S') << line;
          speed = std::stod(s.substr(1));
          EXPECT_EQ(speed, expected.at(tool)) << "tool " << tool;
        } else if (word == "M5") {
          EXPECT_EQ(on, "") << "the spindle stops under coolant";
          speed = 0;
        } else if (word == "M7" || word == "M8") {
          on = word;
        } else if (word == "M9") {
          on = "";
        } else if (word == "G1") {
          ++feeds;
          EXPECT_GT(speed, 0) << line;
          EXPECT_EQ(on, wanted) << line;
        } else if (word == "M30") {
          EXPECT_EQ(speed, 0);
          EXPECT_EQ(on, "");
        }
      }
    }
    EXPECT_GT(feeds, 0);
  }
}

TEST(Gcode, SpindleSpeedAndCoolantAreChecked) {
  std::string j = test::smallJobJson();
  const std::string from = R"({"diameter": 12, "id": 4})";
  for (const char* bad : {R"("spindle_speed": 0)", R"("spindle_speed": -5)", R"("spindle_speed": 2e6)",
                          R"("spindle_speed": "fast")"}) {
    std::string k = j;
    k.replace(k.find(from), from.size(), std::string(R"({"diameter": 12, "id": 4, )") + bad + "}");
    EXPECT_THAT([&] { planInputFromJson(k); }, ThrowsMessage<Error>(HasSubstr("spindle_speed"))) << bad;
  }
  std::string k = j;
  k.insert(k.rfind('}'), R"(, "coolant": "oil")");
  EXPECT_THAT([&] { planInputFromJson(k); },
              ThrowsMessage<Error>(HasSubstr(R"(coolant: unknown coolant 'oil' (use "off", "flood" or "mist"))")));
}
