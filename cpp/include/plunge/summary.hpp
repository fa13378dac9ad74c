// The plan in one line for people: what the CLI prints, the Python module
// returns and the FreeCAD addon shows in its report view.
#pragma once
#include <string>

#include "plunge/types.hpp"

namespace plunge {

// Plunges per tool, coverage and travel, then the stock left (wall band, floor stock max/mean,
// volumes removed and left), floor-stock plunges, start holes, levels, lead-outs and
// the estimated time.
// With the automatic tool choice, its outcome (choiceSummary), and last what the
// depths were found on (floorKindSaid).
std::string planSummary(const Plan& plan);

// The floor kind (PlanStats::floorKind) in words: "depths on the floor's faces"
// or "... as a mesh", for the summary and the pictures' legend.
std::string floorKindSaid(const std::string& kind);

// The plungers chosen, those of the library left out and the minutes that
// saves by the choice's estimate (selection.hpp).
std::string choiceSummary(const ToolSelection& selection);

}  // namespace plunge
