// The plan pipeline: input to plunges and statistics (docs/plan-format.md):
// region, packing, covering, sequencing, depths.
#pragma once
#include "plunge/progress.hpp"
#include "plunge/types.hpp"

namespace plunge {

// The whole pipeline: validate, then the automatic tool choice (selection.hpp)
// or planWithTools. progress: told how far planning got, and able to cancel it
// (progress.hpp).
Plan plan(PlanInput input, const Progress& progress = Progress());

// The plan of a validated input with its tools given (tools, not "auto"):
// region, packing and covering (or the grid), depths, floor-stock step, sequencing,
// engagement limits, levels, motion and the stock left.
Plan planWithTools(PlanInput input, const Progress& progress = Progress());

}  // namespace plunge
