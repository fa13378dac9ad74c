// The plan input's checks, before any planning: every number, with a message
// naming the field and the fix (plunge::Error); docs/plan-format.md.
#pragma once
#include <string>

#include "plunge/types.hpp"

namespace plunge {

// Checks every number of the input (its options are enums, parsed by io.hpp)
// and sorts the tools largest first; throws plunge::Error naming the problem.
void validate(PlanInput& input);

// A path of the input (floor.brep) as the planner opens it: absolute, or relative
// to input.baseDir (the current directory when that is empty).
std::string resolveInputPath(const PlanInput& input, const std::string& path);

}  // namespace plunge
