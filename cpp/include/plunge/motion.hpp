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
//   the floor; none where there is no room.
// - The engagement, core and flute checks of every plunge, measured on the
//   same simulation, and the time model with these heights.
#pragma once
#include <vector>

#include "plunge/depth.hpp"
#include "plunge/heightfield.hpp"
#include "plunge/plan.hpp"
#include "plunge/region.hpp"

namespace plunge {

// Splits the plunges of tools with a flute length into levels (same positions,
// stepping down); returns the new order and sets stats.levels.
std::vector<Plunge> splitIntoLevels(const PlanInput& in, const std::vector<Plunge>& ordered,
                                    PlanStats& stats);

// The height field every simulation of a plan uses (bounds, spacing).
HeightField stockOf(const PlanInput& in, const Region& region);

// Fills every plunge's approachZ, retractZ, leadOut and engagement, counts the
// plunges beyond a tool's limits (stats.overEngaged, thinCuts) and adds a
// warning for each kind; travel length and both time estimates.
void planMotion(const PlanInput& in, const Region& region, const DepthSolver& depths, Plan& plan);

// Minutes of a plan's moves as planMotion laid them out; atSafeHeight: as if
// every approach and retract went to safe_z.
double motionMinutes(const Plan& plan, const std::vector<Tool>& tools, const PlanInput& in, bool atSafeHeight);

}  // namespace plunge
