// The planner's calls (calls.hpp): what the Python module and the program's
// `call` mode serve, each against the library's own functions.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "plunge/calls.hpp"
#include "plunge/error.hpp"
#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "plunge/rest.hpp"
#include "plunge/summary.hpp"
#include "plunge/tools.hpp"
#include "testutil.hpp"

using namespace plunge;
using nlohmann::json;

namespace {

// The plan's value without its timings, which differ run to run.
json withoutTimings(json v) {
  v["stats"].erase("planning_seconds");
  return v;
}

}  // namespace

TEST(Calls, PlanIsThePlanWithItsSummaryAndPictures) {
  const json input = json::parse(test::smallJobJson());
  const json out = call({{"call", "plan"}, {"input", input}, {"svg", true}});
  const Plan direct = plan(planInputFromValue(input));
  json expected = planToValue(direct);
  for (const char* key : {"summary", "svg", "svg_stock"}) EXPECT_TRUE(out.contains(key)) << key;
  EXPECT_FALSE(out.contains("svg_heights"));  // a flat floor has no stop heights to show
  EXPECT_EQ(out["summary"], planSummary(direct));
  json bare = out;
  for (const char* key : {"summary", "svg", "svg_stock"}) bare.erase(key);
  EXPECT_EQ(withoutTimings(bare), withoutTimings(expected));
}

TEST(Calls, StartHoleToolsNameEachDrill) {
  const json tools = json::array({{{"diameter", 20}, {"id", 1}, {"center_cutting", false}, {"core_diameter", 8}},
                                  {{"diameter", 6}, {"id", 2}},
                                  {{"diameter", 10}, {"id", 3}}});
  EXPECT_EQ(call({{"call", "start_hole_tools"}, {"tools", tools}}), json({{"1", 3}}));
}

TEST(Calls, SweepIsTheLibrarysSweep) {
  const json material{{"origin", {0, 0}}, {"spacing", 1.0}, {"nx", 20}, {"ny", 10}, {"top", std::vector<double>(200, 0.0)}};
  const json tool{{"diameter", 6}, {"shape", "ball"}};
  const json moves = json::array({{2, 2, 5, 2, 2, -3}, {2, 2, -3, 15, 6, -3}});
  const json out = call({{"call", "sweep"}, {"material", material}, {"tool", tool}, {"moves", moves}});
  MaterialGrid g = materialGrid({0, 0}, 1.0, 20, 10, 0.0);
  sweep(g, cutterOf(toolsFromValue(json::array({tool})).front()), {{2, 2, 5, 2, 2, -3}, {2, 2, -3, 15, 6, -3}});
  EXPECT_EQ(out["top"].get<std::vector<double>>(), g.top);
}

TEST(Calls, AboutNamesTheFloorsThisBuildReads) {
  const json about = call({{"call", "about"}});
  const auto floors = about["floors"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(floors.begin(), floors.end(), "mesh"), floors.end());
  EXPECT_NE(std::find(floors.begin(), floors.end(), "brep"), floors.end());  // the tests build with OpenCASCADE
  EXPECT_EQ(about["version"], about["planner"].get<std::string>().substr(std::string("PlungeRough ").size()));
}

TEST(Calls, BadRequestsNameTheProblem) {
  auto message = [](const json& request) {
    try {
      call(request);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(json::array()), "request: expected {\"call\": \"plan\" | \"start_hole_tools\" | \"sweep\" | \"about\", ...}");
  EXPECT_EQ(message({{"call", "dance"}}), "call: unknown call \"dance\" (plan, start_hole_tools, sweep or about)");
  EXPECT_EQ(message({{"call", "plan"}}), "plan: \"input\" is required");
  EXPECT_EQ(message({{"call", "plan"}, {"input", json::object()}, {"colour", 1}}), "plan: unknown key \"colour\"");
  EXPECT_EQ(message({{"call", "plan"}, {"input", json::object()}, {"svg", "yes"}}), "plan: \"svg\": expected true or false");
  EXPECT_EQ(message({{"call", "sweep"}, {"material", json::object()}}), "sweep: \"tool\" is required");
}
