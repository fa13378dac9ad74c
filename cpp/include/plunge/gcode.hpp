// The plan as plain RS-274 G-code (the CLI's --gcode; FreeCAD posts its own
// Path commands, freecad_plugin/generator.py).
#pragma once
#include <string>

#include "plunge/types.hpp"

namespace plunge {

// Explicit moves: tool change, spindle (S: spindleSpeedOf) and coolant on,
// rapid to safe_z, G1 plunge at the tool's feed, lead-out, rapid back up to the
// retract height; coolant and spindle off before each tool change and the end.
std::string planToGcode(const PlanInput& input, const Plan& plan);

}  // namespace plunge
