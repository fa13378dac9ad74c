// A job's tools by id, and what is derived from a tool, each written once: its
// cutter (depth.hpp), its core, its engagement limit (engagement.hpp) and the
// drill of its start holes.
#pragma once
#include <cstddef>
#include <vector>

#include "plunge/types.hpp"

namespace plunge {

// The cutter shape of a tool (depth.hpp).
Cutter cutterOf(const Tool& tool);
// A plunge of the tool at c stopping at z.
Plunge plungeOf(const Tool& tool, Vec2 c, double z);
// The radius of the part that does not cut (0 for a centre-cutting tool).
double coreRadius(const Tool& tool);
// How deep one peck of a hole into solid goes: the tool's own, or three
// diameters (beyond that, makers advise chip-clearing retracts).
double peckDepthOf(const Tool& tool);
// The cutting speed of a tool with no spindle_speed, m/min: carbide in a
// plain steel, near the low end of makers' tables (docs/feeds-and-speeds.md).
constexpr double kDefaultCuttingSpeed = 100.0;
// Its spindle speed in rev/min: its own, or kDefaultCuttingSpeed's, rounded.
double spindleSpeedOf(const Tool& tool);
// The band a tool may cut in one plunge, from its limit and core (infinite when free).
double engagementLimit(const Tool& tool);
// The centre-cutting tool that drills start holes for `tool`: the smallest one
// at least as wide as its core. Throws plunge::Error naming the fix when the
// job has none.
const Tool& startHoleTool(const std::vector<Tool>& tools, const Tool& tool);

// The tools of a job, looked up by id one way: an id no tool has is a fault of
// the planner (plunge::InternalError), never bad input.
class ToolTable {
 public:
  ToolTable() = default;
  explicit ToolTable(std::vector<Tool> tools) : tools_(std::move(tools)) {}
  const Tool& byId(int id) const { return tools_[indexOf(id)]; }
  size_t indexOf(int id) const;
  const std::vector<Tool>& all() const { return tools_; }
  const Tool& startHoleFor(const Tool& tool) const { return startHoleTool(tools_, tool); }

 private:
  std::vector<Tool> tools_;
};

}  // namespace plunge
