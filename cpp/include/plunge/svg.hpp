// The plan's picture (SVG).
#pragma once
#include <string>

#include "plunge/types.hpp"

namespace plunge {

// The pocket, its islands, every plunge disk coloured by tool, the tool paths,
// what is left uncovered (red) and a legend (tool, count, coverage, travel).
std::string planToSvg(const PlanInput& input, const Plan& plan);

}  // namespace plunge
