// The plan's input and output as JSON text or values (docs/plan-format.md, the schemas in
// docs/).
#pragma once
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "plunge/types.hpp"

namespace plunge {

// Parses and checks the JSON input; throws plunge::Error naming the bad field.
PlanInput planInputFromJson(const std::string& text);
// The same from a file; a relative floor.brep then starts at the file's folder.
PlanInput readPlanInput(const std::string& path);

// A list of tools as in the input's "tools" (ids as given, not yet checked).
std::vector<Tool> toolsFromValue(const nlohmann::json& value);
// The input's "material": the top of the material the operations before left,
// over a raster.
MaterialGrid materialFromValue(const nlohmann::json& value);

// The input's options by their JSON names; each throws plunge::Error naming the
// key and the names it accepts.
Strategy strategyFromName(const std::string& name);         // "strategy"
PackingOrder packingOrderFromName(const std::string& name);  // "packing_order"
GrowthPattern growthPatternFromName(const std::string& name);  // "growth_pattern"
TourMethod tourMethodFromName(const std::string& name);      // "sequencing"
GridPattern gridPatternFromName(const std::string& name);    // "grid": {"pattern"}
Coolant coolantFromName(const std::string& name);            // "coolant"

// The plan: plunges, statistics, warnings, the tool choice (docs/plan-output.schema.json).
std::string planToJson(const Plan& plan);

// The same as JSON values, for a front end that holds its data as values
// already (the Python module): no text in between.
PlanInput planInputFromValue(const nlohmann::json& value);
nlohmann::json planToValue(const Plan& plan);

}  // namespace plunge
