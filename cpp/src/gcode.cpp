#include "plunge/gcode.hpp"

#include "plunge/tools.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace plunge {

std::string planToGcode(const PlanInput& input, const Plan& plan) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(4);
  s << "(PlungeRough: " << plan.stats.plungeCount << " plunges, coverage " << std::setprecision(2)
    << 100.0 * plan.stats.coverage << " %)\n"
    << std::setprecision(4);
  s << "G21 G90 G17\n";
  // A plunge's tool by its id, as everywhere: one the input lacks is the
  // planner's fault (InternalError), never a feed of 0.
  const ToolTable tools(input.choice.automatic ? input.choice.library : input.tools);
  const char* stop = input.motion.coolant == Coolant::Off ? "M5\n" : "M9\nM5\n";
  int current = -1;
  for (const Plunge& p : plan.plunges) {
    if (p.toolId != current) {
      if (current >= 0) s << stop;
      s << "G0 Z" << input.safeZ << "\n";
      s << "(T" << p.toolId << ": plunger diameter " << p.diameter << ")\n";
      s << "T" << p.toolId << " M6\n";
      // The spindle, and the coolant with it (off before the tool change).
      s << "M3 S" << std::setprecision(0) << spindleSpeedOf(tools.byId(p.toolId)) << std::setprecision(4) << "\n";
      if (input.motion.coolant == Coolant::Flood) s << "M8\n";
      if (input.motion.coolant == Coolant::Mist) s << "M7\n";
      s << "G0 Z" << input.safeZ << "\n";
      current = p.toolId;
    }
    if (p.startHole) s << "(start hole)\n";
    // Rapid over at the last retract height, down to the approach height, feed
    // through the material, lead out (fed up to its height first if raised),
    // rapid up only as high as the next move needs.
    s << "G0 X" << p.x << " Y" << p.y << "\n";
    s << "G0 Z" << p.approachZ << "\n";
    // A deep hole into solid is pecked: up out of it after each peck to clear
    // the chips, back down to just above where it stopped.
    for (double at : p.pecks)
      s << "G1 Z" << at << " F" << tools.byId(p.toolId).feed << "\nG0 Z" << p.approachZ << "\nG0 Z"
        << std::min(p.approachZ, at + input.motion.rapidClearance) << "\n";
    s << "G1 Z" << p.z << " F" << tools.byId(p.toolId).feed << "\n";
    if (!p.pecks.empty() && input.motion.peckDwell > 0) s << "G4 P" << input.motion.peckDwell << "\n";
    if (p.leadOutZ) s << "G1 Z" << *p.leadOutZ << "\n";
    if (p.leadOut) s << "G1 X" << p.leadOut->x << " Y" << p.leadOut->y << "\n";
    s << "G0 Z" << p.retractZ << "\n";
    for (Vec2 v : p.via) s << "G0 X" << v.x << " Y" << v.y << "\n";
  }
  if (current >= 0) s << stop;
  s << "M30\n";
  return s.str();
}



}  // namespace plunge
