// What the planner refuses or simplifies before planning, so that no input
// makes it run for more than about a minute or take more than a few GB on a
// small machine (2 cores): work it cannot finish, and scales no machine has.
// Every refusal names the likely cause, usually a unit slip. Documented in
// docs/plan-format.md, "Limits".
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "region.hpp"
#include "plunge/types.hpp"

namespace plunge {

// Any length (coordinate, height, allowance, lead-out ...): 100 m, more than
// any machine travels.
constexpr double kMaxLength = 1e5;
// A milling tool's diameter, mm.
constexpr double kMaxToolDiameter = 1000.0;
// Tool numbers (G-code T words) run from 1 to this.
constexpr int kMaxToolId = 1000000;
// Spindle speeds, rev/min: beyond the fastest spindles made.
constexpr double kMaxSpindleSpeed = 100000.0;
// Boundary and island vertices together.
constexpr size_t kMaxVertices = 1000000;
// Cells of the material before the operation ("material"): 4 million (2000 x 2000).
constexpr size_t kMaxMaterialCells = 4000000;
// Boundaries with more vertices plan on walls simplified within at most
// kMaxBoundaryTolerance mm, added to the radial allowance (region.hpp).
constexpr size_t kPlanningVertices = 4000;
constexpr double kMaxBoundaryTolerance = 0.05;

// A plunge grown within an engagement limit (engagement.hpp) costs about this
// many packed plunges of planning: the 600 x 400 mm benchmark at 0.25 D grows
// about 7,000 plunges in 15 s; packed, its estimate of 11,600 takes 3.8 s.
constexpr double kGrowthCost = 6.0;

// The planner's work in plunges: the pocket's area over the smallest tool's
// disk (packing and covering place fewer, since larger tools go first); with
// an engagement limit e on the largest limited tool (diameter D), at least
// kGrowthCost x its row bound, area / (0.87 D e).
double estimatedPlunges(const PlanInput& in);

// The region a plan is made on: the given loops, or with more than
// kPlanningVertices vertices those simplified (region.hpp's simplifiedRegion);
// `tolerance` says by how much (0: as given), to add to the radial allowance.
struct PlanningRegion {
  Region region;
  double tolerance = 0.0;
};
PlanningRegion planningRegion(const PlanInput& in);

// Throws plunge::Error for input beyond the limits above or estimated above
// in.maxPlunges. Needs validated input (tools sorted, numbers finite).
void checkScale(const PlanInput& in);

// The tools (largest first) without those that fit nowhere in the pocket
// (region.hpp's accessible region is empty), and a warning naming those (empty
// if none). The smallest tool is kept: plan() reports a pocket that no tool fits.
struct ToolsThatFit {
  std::vector<Tool> tools;
  std::string warning;
};
ToolsThatFit toolsThatFit(const std::vector<Tool>& tools, const Region& region, double radialAllowance);

}  // namespace plunge
