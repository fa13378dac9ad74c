// Real plunge mills, part 2: how the machine moves between plunges.
//
// - Levels: a tool whose flutes are shorter than the material under a plunge
//   cuts the tool's plunges level by level, each level at most its flute
//   length (less the height of its corner) below the last.
// - Heights: simulating the stock (heightfield.hpp) in execution order, each
//   plunge rapids down to a clearance above the stock still under it, feeds
//   from there, and retracts only as high as the stock along the move to the
//   next plunge needs (never below it); a new tool starts and ends at safe_z.
// - Lead-out: after reaching depth the tool feeds `lead_out` sideways into
//   space already cleared (no material beyond the skin under its new disk),
//   the direction farthest from the walls, checked against walls, islands and
//   the floor; none where there is no room. A plunge deeper than those around
//   it (uneven depths over a sculptured floor) first feeds up out of their
//   steps, at most `lead_out` (Plunge::leadOutZ).
// - The engagement, core and flute checks of every plunge, measured on the
//   same simulation, and the time model with these heights.
#pragma once
#include <vector>

#include "broken.hpp"
#include "depth.hpp"
#include "heightfield.hpp"
#include "options.hpp"
#include "plunge/progress.hpp"
#include "region.hpp"
#include "plunge/tools.hpp"
#include "plunge/types.hpp"

namespace plunge {

// The plunges of tools with a flute length split into levels (same positions,
// stepping down), in their new order, and the most levels any tool needs.
struct Levels {
  std::vector<Plunge> plunges;
  int levels = 1;
};
Levels splitIntoLevels(const std::vector<Plunge>& ordered, const MotionOptions& options);

// The height field every simulation of a plan uses (bounds, spacing), for the
// tools (largest first) in the region, uncut: the material before this operation.
HeightField stockOf(const std::vector<Tool>& tools, const Material& material, const Region& region);

// What the moves come to: counts of the lead-outs and of the plunges beyond a
// tool's limits, travel and both time estimates (PlanStats' fields of the same names).
struct MotionStats {
  int overEngaged = 0, thinCuts = 0, peckedPlunges = 0;
  int leadOuts = 0, raisedLeadOuts = 0, noLeadOutMaterial = 0, noLeadOutWalls = 0;
  double travelLength = 0.0, estimatedMinutes = 0.0, minutesAtSafeHeight = 0.0;
};

struct Motion {
  std::vector<Plunge> plunges;  // each with its approachZ, retractZ, pecks, lead-out and way there
  MotionStats stats;
  Said said;  // a warning for each limit the plunges break, with its count, the worst and why
};

// The plunges, in their order, with the machine's moves laid out.
Motion planMotion(const Region& region, const DepthSolver& depths, std::vector<Plunge> plunges,
                  const MotionOptions& options);

// Minutes of the plunges' moves as planMotion laid them out; atSafeHeight: as
// if every approach and retract went to safe_z.
double motionMinutes(const std::vector<Plunge>& plunges, const MotionOptions& options, bool atSafeHeight);

}  // namespace plunge
