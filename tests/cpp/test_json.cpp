#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "plunge/error.hpp"
#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "validate.hpp"
#include "testutil.hpp"

using namespace plunge;
using ::testing::HasSubstr;
using nlohmann::json;

namespace {

json base() { return json::parse(test::smallJobJson()); }

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

TEST(Json, ParsesTheContractExample) {
  const PlanInput in = planInputFromJson(base().dump());
  EXPECT_EQ(in.boundary.size(), 4u);
  EXPECT_EQ(in.islands.size(), 1u);
  ASSERT_EQ(in.tools.size(), 2u);
  EXPECT_EQ(in.tools[0].id, 4);
  EXPECT_EQ(in.tools[1].id, 2);  // default: rank by decreasing diameter
  EXPECT_DOUBLE_EQ(in.floor.surface.z, -10);
  EXPECT_DOUBLE_EQ(in.radialAllowance, 0.2);
  EXPECT_EQ(in.seed, 3u);
}

TEST(Json, BadInputNamesTheProblem) {
  EXPECT_THAT(parseError("{not json"), HasSubstr("invalid JSON"));
  EXPECT_THAT(parseError("[1,2]"), HasSubstr("expected a JSON object"));
  EXPECT_THAT(parseError(withChange("/boundary", json::value_t::discarded)), HasSubstr("boundary: required"));
  EXPECT_THAT(parseError(withChange("/boundary/1", json::array({1}))), HasSubstr("boundary[1]"));
  EXPECT_THAT(parseError(withChange("/boundary/1/0", "x")), HasSubstr("boundary[1][0]: expected a number"));
  EXPECT_THAT(parseError(withChange("/tools/0/diameter", 0)), HasSubstr("diameter must be > 0"));
  EXPECT_THAT(parseError(withChange("/tools/0/id", -2)), HasSubstr("tools[0].id"));
  EXPECT_THAT(parseError(withChange("/tools/0/colour", 1)), HasSubstr("unknown key 'colour'"));
  EXPECT_THAT(parseError(withChange("/allowances", 1)), HasSubstr("unknown key 'allowances'"));
  EXPECT_THAT(parseError(withChange("/floor", json::object({{"z", 1}, {"brep", "f"}}))), HasSubstr("exactly one"));
  EXPECT_THAT(parseError(withChange("/floor", json::value_t::discarded)), HasSubstr("floor: required"));
  EXPECT_THAT(parseError(withChange("/version", 2)), HasSubstr("version"));
  EXPECT_THAT(parseError(withChange("/seed", -1)), HasSubstr("seed"));
  EXPECT_THAT(parseError(withChange("/islands/0", json::array({json::array({1, 1}), json::array({2, 2})}))), HasSubstr("island 1: needs at least 3 distinct points"));
  EXPECT_THAT(parseError(withChange("/islands/0/0", json::array({140, 20}))), HasSubstr("island 1: crosses"));
  EXPECT_EQ(parseError(base().dump()), "");
}

TEST(Json, OptionsAreParsedByName) {
  json j = base();
  j["strategy"] = "grid";
  j["packing_order"] = "lattice";
  j["growth_pattern"] = "offsets";
  j["sequencing"] = "annealing";
  j["grid"] = {{"pattern", "square"}, {"step", 0.5}};
  const PlanInput in = planInputFromJson(j.dump());
  EXPECT_EQ(in.packing.strategy, Strategy::Grid);
  EXPECT_EQ(in.packing.order, PackingOrder::Lattice);
  EXPECT_EQ(in.engagement.pattern, GrowthPattern::Offsets);
  EXPECT_EQ(in.motion.sequencing, TourMethod::Annealing);
  EXPECT_EQ(in.packing.gridPattern, GridPattern::Square);
  const PlanInput defaults = planInputFromJson(withChange("/strategy", json::value_t::discarded));
  EXPECT_EQ(defaults.packing.strategy, Strategy::Packing);
  EXPECT_EQ(defaults.packing.order, PackingOrder::Auto);
  EXPECT_EQ(defaults.engagement.pattern, GrowthPattern::Auto);
  EXPECT_EQ(defaults.motion.sequencing, TourMethod::LocalSearch);
  EXPECT_EQ(defaults.packing.gridPattern, GridPattern::Honeycomb);
  // Unknown names: the key, the name and every accepted one.
  EXPECT_EQ(parseError(withChange("/strategy", "spiral")),
            "strategy: unknown strategy 'spiral' (use \"packing\" or \"grid\")");
  EXPECT_EQ(parseError(withChange("/packing_order", "random")),
            "packing_order: unknown order 'random' (use \"auto\", \"hole_degree\" or \"lattice\")");
  EXPECT_EQ(parseError(withChange("/growth_pattern", "spiral")),
            "growth_pattern: unknown pattern 'spiral' (use \"auto\", \"rows\" or \"offsets\")");
  EXPECT_EQ(parseError(withChange("/sequencing", "genetic")),
            "sequencing: unknown method 'genetic' (use \"local_search\" or \"annealing\")");
  EXPECT_EQ(parseError(withChange("/grid", {{"pattern", "hexagon"}})),
            "grid.pattern: unknown pattern 'hexagon' (use \"square\" or \"honeycomb\")");
  EXPECT_EQ(parseError(withChange("/strategy", 3)), "strategy: expected a string");
  EXPECT_THROW(tourMethodFromName("genetic"), Error);  // plunge.tour's method too
}

TEST(Json, RelativePathsStartAtTheInputFilesFolder) {
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
  EXPECT_THAT(parseError(j.dump()), HasSubstr("floor.brep"));
  try {
    readPlanInput((dir / "missing.json").string());
    ADD_FAILURE() << "a missing file was read";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot read"));
  }
  EXPECT_THROW(readPlanInput(dir.string()), Error);  // a folder
  fs::remove_all(dir);
}

TEST(Json, JsonOutputFollowsTheContract) {
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

// No limit is an absent key. Its old spellings, 0 and null, plan as if the
// key were absent and are said first among the plan's warnings.
TEST(Json, OldNoLimitSpellingsAreMigratedAndSaid) {
  nlohmann::json j = nlohmann::json::parse(test::smallJobJson());
  const Plan absent = plan(planInputFromValue(j));
  j["tools"][0]["max_engagement"] = 0;
  j["tools"][1]["flute_length"] = nullptr;
  const PlanInput in = planInputFromValue(j);
  ASSERT_EQ(in.notes.size(), 2u);
  const Plan migrated = plan(in);
  ASSERT_EQ(migrated.plunges.size(), absent.plunges.size());
  for (size_t i = 0; i < absent.plunges.size(); ++i) {
    EXPECT_EQ(migrated.plunges[i].x, absent.plunges[i].x);
    EXPECT_EQ(migrated.plunges[i].y, absent.plunges[i].y);
    EXPECT_EQ(migrated.plunges[i].z, absent.plunges[i].z);
  }
  ASSERT_GE(migrated.warnings.size(), 2u);
  EXPECT_EQ(migrated.warnings[0], "tools[0].max_engagement: 0 is read as no limit (leave the key out to say so)");
  EXPECT_EQ(migrated.warnings[1], "tools[1].flute_length: null is read as no limit (leave the key out to say so)");
  j["tools"][0]["max_engagement"] = -1;
  EXPECT_THAT(parseError(j.dump()), HasSubstr("max_engagement must be > 0"));
}
