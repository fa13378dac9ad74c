// Plan input and output (docs/plan-format.md): JSON text,
// an SVG picture of the plan, and plain RS-274 G-code.
#pragma once
#include <string>

#include "plunge/plan.hpp"

namespace plunge {

// Parses and checks the JSON input; throws plunge::Error naming the bad field.
PlanInput planInputFromJson(const std::string& text);
// The same from a file; a relative floor.brep then starts at the file's folder.
PlanInput readPlanInput(const std::string& path);

// The input's options by their JSON names; each throws plunge::Error naming the
// key and the names it accepts.
Strategy strategyFromName(const std::string& name);         // "strategy"
PackingOrder packingOrderFromName(const std::string& name);  // "packing_order"
TourMethod tourMethodFromName(const std::string& name);      // "sequencing"
GridPattern gridPatternFromName(const std::string& name);    // "grid": {"pattern"}
std::string planToJson(const Plan& plan);
// The pocket, its islands, every plunge disk coloured by tool, the tool paths,
// what is left uncovered (red) and a legend (tool, count, coverage, travel).
std::string planToSvg(const PlanInput& input, const Plan& plan);
// One line for people: plunges per tool, then the stock left (wall band,
// floor stock max/mean, volumes removed and left).
std::string planSummary(const Plan& plan);
// Explicit moves: tool change, rapid to safe_z, G1 plunge at the tool's feed, rapid back.
std::string planToGcode(const PlanInput& input, const Plan& plan);

}  // namespace plunge
