// Choosing the plungers (polygon-subdivision thesis, chapter 5) and the time
// model that judges a tool set.
//
// 5.1 candidate tools: per sub-region (cut at the necks) the largest tool,
//     0.7 x its largest inscribed circle, and the neck tools, each snapped down to
//     a size in the library. The largest tool that alone reaches what the
//     library's smallest must cut (the core beyond the wall band; on a flat
//     floor: a sculptured one needs the smallest in its hollows) is in every
//     set, and none smaller is a candidate: it decides how much of the corners
//     the plan reaches. The library as given (what the operation uses without
//     the choice) is a set too.
// 5.3 time: the thesis estimates milling time from areas. Here each set's plunge
//     positions are placed (packing and covering, the cheap part of a plan) and
//     each position timed on the floor under it: feed through the stock to its
//     depth, flute-length levels, pecks, retract, rapids, tool changes
//     (estimateMinutes). Only the set with the best estimate is planned in full,
//     so the choice costs one plan plus the placements.
// 5.4 branch and bound over subsets of the candidates, largest first, with a lower
//     bound from the plunges no set can do without (accessible area over the
//     largest disk still possible) and the volume they must feed through, true
//     with engagement limits and stock-aware heights: a set whose bound is above
//     the best estimate is not placed. Weighted time + number of tools, as the thesis.
// 5.5 sub-regions ordered by a minimum spanning tree (reported; the plunges of
//     each tool are then toured over the whole pocket, which is never longer).
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "covering.hpp"
#include "floor.hpp"
#include "medial.hpp"
#include "plunge/progress.hpp"
#include "plunge/types.hpp"

namespace plunge {

// What the choice needs of the pipeline (plan.cpp).
struct ToolSetStages {
  // Its plunge positions alone (packing and covering; a tool dropped when it
  // fits nowhere, so a disk's tool is known by its radius).
  std::function<CoverResult(PlanInput, const Progress&)> place;
  // A full plan of one tool set (validated there), from its positions when placed.
  std::function<Plan(PlanInput, std::optional<CoverResult>, const Progress&)> plan;
  // The floor under the pocket (for each position's depth).
  const FloorSurface* floor = nullptr;
};

// 5.3: the minutes a plan of input.tools would take with plunges at `disks`
// (each of the input.tools of its radius), each stopping on the floor under it: tool
// changes, feed through the stock in flute-length levels, pecks of holes into
// solid, retracts and rapids between neighbours, and the floor-stock step where
// a position leaves more than max_floor_stock. Engagement limits are not seen
// (their growth replaces the covering, engagement.hpp): the sets are ranked as
// if free, and only the chosen one is planned with them.
double estimateMinutes(const PlanInput& input, const std::vector<CoverDisk>& disks, const FloorSurface& floor);

// Chooses the plungers from input.tools (the validated library, largest first):
// every set the search reaches is placed and estimated, the best planned in
// full and returned carrying the selection.
Plan planWithToolSelection(const PlanInput& input, const ToolSetStages& stages,
                           const Progress& progress = Progress());

}  // namespace plunge
