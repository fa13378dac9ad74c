#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "plunge/error.hpp"
#include "plunge/gcode.hpp"
#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "plunge/svg.hpp"
#include "plunge/validate.hpp"

using namespace plunge;
using nlohmann::json;

namespace {

json base() {
  return json::parse(R"({"version": 1, "boundary": [[0,0],[100,0],[100,60],[0,60]],
    "islands": [[[40,20],[60,20],[50,40]]], "tools": [{"diameter": 12, "id": 4}, {"diameter": 6}],
    "top_z": 0, "safe_z": 5, "floor": {"z": -10}, "allowance": {"radial": 0.2, "floor": 0.1},
    "strategy": "packing", "seed": 3})");
}

std::string parseError(const std::string& text) {
  try {
    PlanInput in = planInputFromJson(text);
    plan(in);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string withChange(const std::string& pointer, const json& value) {
  json j = base();
  if (value.is_discarded())
    j.erase(pointer.substr(1));
  else
    j[json::json_pointer(pointer)] = value;
  return j.dump();
}

}  // namespace

TEST(Io, ParsesTheContractExample) {
  const PlanInput in = planInputFromJson(base().dump());
  EXPECT_EQ(in.boundary.size(), 4u);
  EXPECT_EQ(in.islands.size(), 1u);
  ASSERT_EQ(in.tools.size(), 2u);
  EXPECT_EQ(in.tools[0].id, 4);
  EXPECT_EQ(in.tools[1].id, 2);  // default: rank by decreasing diameter
  EXPECT_DOUBLE_EQ(in.floor.z, -10);
  EXPECT_DOUBLE_EQ(in.radialAllowance, 0.2);
  EXPECT_EQ(in.seed, 3u);
}

TEST(Io, BadInputNamesTheProblem) {
  EXPECT_NE(parseError("{not json").find("invalid JSON"), std::string::npos);
  EXPECT_NE(parseError("[1,2]").find("expected a JSON object"), std::string::npos);
  EXPECT_NE(parseError(withChange("/boundary", json::value_t::discarded)).find("boundary: required"), std::string::npos);
  EXPECT_NE(parseError(withChange("/boundary/1", json::array({1}))).find("boundary[1]"), std::string::npos);
  EXPECT_NE(parseError(withChange("/boundary/1/0", "x")).find("boundary[1][0]: expected a number"), std::string::npos);
  EXPECT_NE(parseError(withChange("/tools/0/diameter", 0)).find("diameter must be > 0"), std::string::npos);
  EXPECT_NE(parseError(withChange("/tools/0/id", -2)).find("tools[0].id"), std::string::npos);
  EXPECT_NE(parseError(withChange("/tools/0/colour", 1)).find("unknown key 'colour'"), std::string::npos);
  EXPECT_NE(parseError(withChange("/allowances", 1)).find("unknown key 'allowances'"), std::string::npos);
  EXPECT_NE(parseError(withChange("/floor", json::object({{"z", 1}, {"brep", "f"}}))).find("exactly one"),
            std::string::npos);
  EXPECT_NE(parseError(withChange("/floor", json::value_t::discarded)).find("floor: required"), std::string::npos);
  EXPECT_NE(parseError(withChange("/version", 2)).find("version"), std::string::npos);
  EXPECT_NE(parseError(withChange("/seed", -1)).find("seed"), std::string::npos);
  EXPECT_NE(parseError(withChange("/islands/0", json::array({json::array({1, 1}), json::array({2, 2})})))
                .find("island 1: needs at least 3 distinct points"),
            std::string::npos);
  EXPECT_NE(parseError(withChange("/islands/0/0", json::array({140, 20}))).find("island 1: crosses"), std::string::npos);
  EXPECT_EQ(parseError(base().dump()), "");
}

TEST(Io, OptionsAreParsedByName) {
  json j = base();
  j["strategy"] = "grid";
  j["packing_order"] = "lattice";
  j["sequencing"] = "annealing";
  j["grid"] = {{"pattern", "square"}, {"step", 0.5}};
  const PlanInput in = planInputFromJson(j.dump());
  EXPECT_EQ(in.strategy, Strategy::Grid);
  EXPECT_EQ(in.packingOrder, PackingOrder::Lattice);
  EXPECT_EQ(in.sequencing, TourMethod::Annealing);
  EXPECT_EQ(in.gridPattern, GridPattern::Square);
  const PlanInput defaults = planInputFromJson(withChange("/strategy", json::value_t::discarded));
  EXPECT_EQ(defaults.strategy, Strategy::Packing);
  EXPECT_EQ(defaults.packingOrder, PackingOrder::Auto);
  EXPECT_EQ(defaults.sequencing, TourMethod::LocalSearch);
  EXPECT_EQ(defaults.gridPattern, GridPattern::Honeycomb);
  // Unknown names: the key, the name and every accepted one.
  EXPECT_EQ(parseError(withChange("/strategy", "spiral")),
            "strategy: unknown strategy 'spiral' (use \"packing\" or \"grid\")");
  EXPECT_EQ(parseError(withChange("/packing_order", "random")),
            "packing_order: unknown order 'random' (use \"auto\", \"hole_degree\" or \"lattice\")");
  EXPECT_EQ(parseError(withChange("/sequencing", "genetic")),
            "sequencing: unknown method 'genetic' (use \"local_search\" or \"annealing\")");
  EXPECT_EQ(parseError(withChange("/grid", {{"pattern", "hexagon"}})),
            "grid.pattern: unknown pattern 'hexagon' (use \"square\" or \"honeycomb\")");
  EXPECT_EQ(parseError(withChange("/strategy", 3)), "strategy: expected a string");
  EXPECT_THROW(tourMethodFromName("genetic"), Error);  // plunge.tour's method too
}

TEST(Io, RelativePathsStartAtTheInputFilesFolder) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("plunge-io-test-" + std::to_string(::getpid()));
  fs::create_directories(dir / "job");
  json j = base();
  j["floor"] = {{"brep", "floor.brep"}};
  std::ofstream(dir / "job" / "in.json") << j.dump();
  const PlanInput in = readPlanInput((dir / "job" / "in.json").string());
  EXPECT_EQ(fs::path(resolveInputPath(in, "floor.brep")), dir / "job" / "floor.brep");
  EXPECT_EQ(resolveInputPath(in, "/abs/floor.brep"), "/abs/floor.brep");
  // From a relative file name: still that file's folder, whatever the current directory.
  const fs::path here = fs::current_path();
  fs::current_path(dir);
  const PlanInput rel = readPlanInput("job/in.json");
  fs::current_path(here);
  EXPECT_EQ(fs::path(resolveInputPath(rel, "floor.brep")), dir / "job" / "floor.brep");
  // Parsed from text there is no file: the current directory.
  EXPECT_EQ(resolveInputPath(planInputFromJson(j.dump()), "floor.brep"), "floor.brep");
  EXPECT_NE(parseError(j.dump()).find("floor.brep"), std::string::npos);
  try {
    readPlanInput((dir / "missing.json").string());
    ADD_FAILURE() << "a missing file was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read"), std::string::npos);
  }
  EXPECT_THROW(readPlanInput(dir.string()), Error);  // a folder
  fs::remove_all(dir);
}

TEST(Io, JsonOutputFollowsTheContract) {
  PlanInput in = planInputFromJson(base().dump());
  const Plan p = plan(in);
  const json out = json::parse(planToJson(p));
  ASSERT_TRUE(out["plunges"].is_array());
  EXPECT_EQ(out["plunges"].size(), p.plunges.size());
  for (const auto& q : out["plunges"])
    for (const char* k : {"x", "y", "diameter", "tool_id", "z"}) EXPECT_TRUE(q.contains(k)) << k;
  for (const char* k : {"plunge_count", "per_tool", "region_area", "accessible_area", "covered_area", "coverage",
                        "travel_length", "planning_seconds"})
    EXPECT_TRUE(out["stats"].contains(k)) << k;
  EXPECT_EQ(out["stats"]["plunge_count"].get<int>(), static_cast<int>(p.plunges.size()));
}

TEST(Io, SvgDrawsEveryPlungeAndALegend) {
  PlanInput in = planInputFromJson(base().dump());
  const Plan p = plan(in);
  const std::string svg = planToSvg(in, p);
  size_t circles = 0;
  for (size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) ++circles;
  EXPECT_EQ(circles, p.plunges.size() + p.stats.perTool.size());  // plunges + legend swatches
  EXPECT_NE(svg.find("% covered"), std::string::npos);
  EXPECT_NE(svg.find("T4"), std::string::npos);
  EXPECT_EQ(svg.rfind("</svg>"), svg.size() - 7);
}

// The G-code parsed back gives the plan: one tool change per tool, one feed
// plunge per plunge at its depth and position, from its approach height, its
// lead-out, and rapids across at the retract height the plan gives.
TEST(Io, GcodeParsesBackToThePlan) {
  PlanInput in = planInputFromJson(base().dump());
  const Plan p = plan(in);
  std::istringstream g(planToGcode(in, p));
  std::string line;
  double x = NAN, y = NAN, z = NAN;
  int tool = -1;
  std::vector<Plunge> seen;
  std::vector<double> rapidHeights;  // z of each rapid across, before each plunge
  std::vector<int> changes;
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
    if (rapid && (v.count('X') || v.count('Y'))) rapidHeights.push_back(z);
    if (feed && v.count('Z')) {
      EXPECT_TRUE(v.count('F'));
      Plunge q;
      q.x = x;
      q.y = y;
      q.toolId = tool;
      q.approachZ = z;  // where the feed starts
      q.z = v['Z'];
      seen.push_back(q);
    } else if (feed) {
      ASSERT_FALSE(seen.empty());
      seen.back().leadOut = Vec2{v['X'], v['Y']};
    }
    if (v.count('X')) x = v['X'];
    if (v.count('Y')) y = v['Y'];
    if (v.count('Z')) z = v['Z'];
  }
  ASSERT_EQ(seen.size(), p.plunges.size());
  ASSERT_EQ(rapidHeights.size(), p.plunges.size());
  int leadOuts = 0;
  for (size_t i = 0; i < seen.size(); ++i) {
    const Plunge& q = p.plunges[i];
    EXPECT_NEAR(seen[i].x, q.x, 1e-4);
    EXPECT_NEAR(seen[i].y, q.y, 1e-4);
    EXPECT_NEAR(seen[i].z, q.z, 1e-4);
    EXPECT_NEAR(seen[i].approachZ, q.approachZ, 1e-4);
    EXPECT_EQ(seen[i].toolId, q.toolId);
    ASSERT_EQ(seen[i].leadOut.has_value(), q.leadOut.has_value());
    if (q.leadOut) {
      ++leadOuts;
      EXPECT_NEAR(dist(*seen[i].leadOut, *q.leadOut), 0.0, 1e-3);
    }
    // Across at the previous plunge's retract height (safe_z after a tool change).
    const bool first = i == 0 || p.plunges[i - 1].toolId != q.toolId;
    EXPECT_NEAR(rapidHeights[i], first ? in.safeZ : p.plunges[i - 1].retractZ, 1e-4);
    EXPECT_LE(q.approachZ, rapidHeights[i] + 1e-4);
  }
  EXPECT_GT(leadOuts, 0);
  EXPECT_EQ(changes.size(), p.stats.perTool.size());
}
