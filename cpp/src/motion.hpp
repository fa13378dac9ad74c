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

#include "depth.hpp"
#include "heightfield.hpp"
#include "plunge/progress.hpp"
#include "region.hpp"
#include "plunge/tools.hpp"
#include "plunge/types.hpp"

namespace plunge {

// What the machine's moves need of the job (PlanInput's fields of the same names).
struct MotionOptions {
  ToolTable tools;  // largest first
  Material material{std::nullopt, 0.0};  // what the operations before left, up to top_z
  double safeZ = 5.0;
  double radialAllowance = 0.0;
  double floorAllowance = 0.0;
  double maxWallStock = 0.0;  // the wall band the covering may leave (rapids go around it)
  MotionSettings settings;  // lead-outs, heights, pecks, the time model (PlanInput::motion)
  Progress progress;  // ticked per plunge (it may cancel)
};

// Splits the plunges of tools with a flute length into levels (same positions,
// stepping down); returns the new order and sets stats.levels.
std::vector<Plunge> splitIntoLevels(const std::vector<Plunge>& ordered, const MotionOptions& options,
                                    PlanStats& stats);

// The height field every simulation of a plan uses (bounds, spacing), for the
// tools (largest first) in the region, uncut: the material before this operation.
HeightField stockOf(const std::vector<Tool>& tools, const Material& material, const Region& region);

// Fills every plunge's approachZ, retractZ, leadOut and engagement, counts the
// plunges beyond a tool's limits (stats.overEngaged, thinCuts) and adds a
// warning for each kind; travel length and both time estimates.
void planMotion(const Region& region, const DepthSolver& depths, Plan& plan, const MotionOptions& options);

// Minutes of a plan's moves as planMotion laid them out; atSafeHeight: as if
// every approach and retract went to safe_z.
double motionMinutes(const Plan& plan, const MotionOptions& options, bool atSafeHeight);

}  // namespace plunge
