// Choosing the plungers (polygon-subdivision thesis, chapter 5) and the time
// model that judges a tool set.
//
// 5.1 candidate tools: per sub-region (cut at the necks) the largest tool,
//     0.7 x its largest inscribed circle, and the neck tools, each snapped down to
//     a size in the library; the library's smallest tool is in every set, since it
//     decides how much of the corners the plan must reach.
// 5.3 time: the thesis estimates milling time from areas. Here every tool set the
//     search reaches is actually planned (packing, covering, tour, depths) and its
//     time taken from that plan, so the comparison is between real plans.
// 5.4 branch and bound over subsets of the candidates, largest first, with a lower
//     bound from the plunges no set can do without (accessible area over the
//     largest disk still possible) and the volume they must feed through, true
//     with engagement limits and stock-aware heights; weighted time + number of
//     tools, as the thesis.
// 5.5 sub-regions ordered by a minimum spanning tree (reported; the plunges of
//     each tool are then toured over the whole pocket, which is never longer).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "plunge/medial.hpp"
#include "plunge/progress.hpp"
#include "plunge/types.hpp"

namespace plunge {

// Plans one tool set: an input with its tools given (plan.hpp's planWithTools
// after validating it).
using ToolSetPlanner = std::function<Plan(PlanInput, const Progress&)>;

// Chooses the plungers from input.tools (the validated library, largest first):
// every tool set the search reaches is planned with planSet, the best plan is
// returned carrying the selection.
Plan planWithToolSelection(const PlanInput& input, const ToolSetPlanner& planSet,
                           const Progress& progress = Progress());

}  // namespace plunge
