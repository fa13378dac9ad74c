#include "plunge/calls.hpp"

#include <string>

#include "plunge/error.hpp"
#include "plunge/json.hpp"
#include "plunge/plan.hpp"
#include "plunge/rest.hpp"
#include "plunge/summary.hpp"
#include "plunge/svg.hpp"
#include "plunge/tools.hpp"

#ifndef PLUNGE_VERSION
#define PLUNGE_VERSION "unknown"
#endif

namespace plunge {

using nlohmann::json;

namespace {

const json& required(const json& request, const char* key, const std::string& call) {
  if (!request.contains(key)) throw Error(call + ": \"" + key + "\" is required");
  return request[key];
}

void onlyKeys(const json& request, std::initializer_list<const char*> keys, const std::string& call) {
  for (auto it = request.begin(); it != request.end(); ++it) {
    bool known = it.key() == "call";
    for (const char* k : keys) known = known || it.key() == k;
    if (!known) throw Error(call + ": unknown key \"" + it.key() + "\"");
  }
}

}  // namespace

json planCall(const json& input, bool svg, const Progress& progress) {
  const PlanInput in = planInputFromValue(input);
  const Plan plan = plunge::plan(in, progress);
  json out = planToValue(plan);
  out["summary"] = planSummary(plan);
  if (svg)
    for (SvgView view : svgViews(in, plan))
      out[view == SvgView::Plan ? std::string("svg") : std::string("svg_") + svgViewName(view)] =
          planToSvg(in, plan, view);
  return out;
}

json startHoleToolsCall(const json& tools) {
  const std::vector<Tool> ts = toolsFromValue(tools);
  json out = json::object();
  for (const Tool& t : ts)
    if (!t.centerCutting) out[std::to_string(t.id)] = startHoleTool(ts, t).id;
  return out;
}

json sweepCall(const json& material, const json& tool, const json& moves, const Progress& progress) {
  MaterialGrid grid = materialFromValue(material);
  const Tool t = toolsFromValue(json::array({tool})).front();
  if (!moves.is_array()) throw Error("moves: expected a list of [x0, y0, z0, x1, y1, z1]");
  std::vector<Move> ms;
  ms.reserve(moves.size());
  for (size_t i = 0; i < moves.size(); ++i) {
    const json& m = moves[i];
    if (!m.is_array() || m.size() != 6)
      throw Error("moves[" + std::to_string(i) + "]: expected [x0, y0, z0, x1, y1, z1]");
    double v[6];
    for (size_t k = 0; k < 6; ++k) {
      if (!m[k].is_number()) throw Error("moves[" + std::to_string(i) + "]: expected numbers");
      v[k] = m[k].get<double>();
    }
    ms.push_back({v[0], v[1], v[2], v[3], v[4], v[5]});
  }
  sweep(grid, cutterOf(t), ms, progress);
  return json{{"top", std::move(grid.top)}};
}

json aboutCall() {
  json floors = json::array({"z", "expression", "mesh"});
#ifdef PLUNGE_WITH_OCCT
  floors.push_back("brep");
#endif
#if defined(_WIN32)
  const char* system = "windows";
#elif defined(__APPLE__)
  const char* system = "macos";
#else
  const char* system = "linux";
#endif
  // The folder of the universal zip's bin/ this program is built for
  // (resources/bundle.sh): macOS names its ARM arm64, Linux aarch64.
#if defined(__aarch64__) || defined(_M_ARM64)
  const std::string arch = std::string(system) == "macos" ? "arm64" : "aarch64";
#elif defined(__x86_64__) || defined(_M_X64)
  const std::string arch = "x86_64";
#else
  const std::string arch = "other";
#endif
  return {{"planner", std::string("PlungeRough ") + PLUNGE_VERSION}, {"version", PLUNGE_VERSION},
          {"system", system}, {"platform", std::string(system) + "-" + arch}, {"floors", floors}};
}

json call(const json& request, const Progress& progress) {
  if (!request.is_object() || !request.contains("call") || !request["call"].is_string())
    throw Error("request: expected {\"call\": \"plan\" | \"start_hole_tools\" | \"sweep\" | \"about\", ...}");
  const std::string name = request["call"].get<std::string>();
  if (name == "plan") {
    onlyKeys(request, {"input", "svg"}, name);
    const bool svg = request.contains("svg") && request["svg"].is_boolean() ? request["svg"].get<bool>() : false;
    if (request.contains("svg") && !request["svg"].is_boolean()) throw Error("plan: \"svg\": expected true or false");
    return planCall(required(request, "input", name), svg, progress);
  }
  if (name == "start_hole_tools") {
    onlyKeys(request, {"tools"}, name);
    return startHoleToolsCall(required(request, "tools", name));
  }
  if (name == "sweep") {
    onlyKeys(request, {"material", "tool", "moves"}, name);
    const json& material = required(request, "material", name);
    const json& tool = required(request, "tool", name);
    return sweepCall(material, tool, required(request, "moves", name), progress);
  }
  if (name == "about") {
    onlyKeys(request, {}, name);
    return aboutCall();
  }
  throw Error("call: unknown call \"" + name + "\" (plan, start_hole_tools, sweep or about)");
}

}  // namespace plunge
