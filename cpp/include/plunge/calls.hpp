// The planner's calls as JSON values: what the Python module and the
// command-line tool's `call` mode both serve (docs/cli.md, "The planner as a
// program"), so that both give the same answer to the same request.
#pragma once
#include <nlohmann/json.hpp>

#include "plunge/progress.hpp"

namespace plunge {

// The plan of `input` (docs/plan-format.md): the output's value, with
// "summary" (planSummary) and, when `svg`, the pictures: "svg" (the plan),
// "svg_stock", "svg_heights" (sculptured floors).
nlohmann::json planCall(const nlohmann::json& input, bool svg, const Progress& progress = {});
// The drill of each tool that does not cut at its centre, for `tools` as in
// the input's "tools": {"<id>": drill id}.
nlohmann::json startHoleToolsCall(const nlohmann::json& tools);
// Rest plunging: the "top" of `material` (as in the input's "material") after
// `tool` (as in its "tools") moves along `moves` [[x0, y0, z0, x1, y1, z1]].
nlohmann::json sweepCall(const nlohmann::json& material, const nlohmann::json& tool, const nlohmann::json& moves,
                         const Progress& progress = {});
// What this build of the planner is: {"planner", "version", "floors": the
// floor kinds it reads}.
nlohmann::json aboutCall();
// One request {"call": "plan" | "start_hole_tools" | "sweep" | "about", and
// the call's own keys}: the call's answer. Throws plunge::Error naming a
// missing or unknown key.
nlohmann::json call(const nlohmann::json& request, const Progress& progress = {});

}  // namespace plunge
