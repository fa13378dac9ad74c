#include "plunge/tools.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "plunge/error.hpp"

namespace plunge {

Cutter cutterOf(const Tool& t) {
  return {t.shape, 0.5 * t.diameter, t.shape == CutterShape::Ball ? 0.5 * t.diameter : t.cornerRadius};
}

Plunge plungeOf(const Tool& t, Vec2 c, double z) {
  Plunge p;
  p.x = c.x;
  p.y = c.y;
  p.diameter = t.diameter;
  p.toolId = t.id;
  p.z = z;
  return p;
}

double coreRadius(const Tool& t) { return t.centerCutting ? 0.0 : 0.5 * t.coreDiameter; }

double peckDepthOf(const Tool& t) { return t.peckDepth > 0.0 ? t.peckDepth : 3.0 * t.diameter; }

double spindleSpeedOf(const Tool& t) {
  return t.spindleSpeed.value_or(std::round(1000.0 * kDefaultCuttingSpeed / (kPi * t.diameter)));
}

double engagementLimit(const Tool& t) {
  double e = t.maxEngagement.value_or(std::numeric_limits<double>::infinity());
  if (!t.centerCutting) e = std::min(e, 0.5 * (t.diameter - t.coreDiameter));
  return e;
}

const Tool& startHoleTool(const std::vector<Tool>& tools, const Tool& tool) {
  const Tool* best = nullptr;
  for (const Tool& t : tools)
    if (t.centerCutting && t.diameter >= tool.coreDiameter && (!best || t.diameter < best->diameter)) best = &t;
  if (!best) {
    std::ostringstream m;
    m << "tool " << tool.id << " (diameter " << tool.diameter << ") does not cut at its centre and the job has no "
      << "centre-cutting tool at least " << tool.coreDiameter
      << " mm wide to drill its start holes: add one (a drill or a centre-cutting end mill)";
    throw Error(m.str());
  }
  return *best;
}

size_t ToolTable::indexOf(int id) const {
  for (size_t k = 0; k < tools_.size(); ++k)
    if (tools_[k].id == id) return k;
  throw InternalError("a plunge of tool " + std::to_string(id) + ", which the job does not have");
}

}  // namespace plunge
