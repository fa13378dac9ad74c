#include "plunge/json.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "plunge/error.hpp"
#include "limits.hpp"

namespace plunge {

using nlohmann::json;

namespace {

double number(const json& j, const std::string& what) {
  if (!j.is_number()) throw Error(what + ": expected a number");
  return j.get<double>();
}

Vec2 point(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 2) throw Error(what + ": expected a point [x, y]");
  return {number(j[0], what + "[0]"), number(j[1], what + "[1]")};
}

Loop loop(const json& j, const std::string& what) {
  if (!j.is_array()) throw Error(what + ": expected a list of [x, y] points");
  Loop out;
  for (size_t i = 0; i < j.size(); ++i) out.push_back(point(j[i], what + "[" + std::to_string(i) + "]"));
  return out;
}

void onlyKeys(const json& j, const std::set<std::string>& allowed, const std::string& where) {
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!allowed.count(it.key())) throw Error(where + "unknown key '" + it.key() + "'");
}

// One option's value by name: "key: unknown noun 'name' (use "a", "b" or "c")".
template <class E>
E fromName(const std::string& name, const char* key, const char* noun,
           std::initializer_list<std::pair<const char*, E>> names) {
  std::string use;
  size_t k = 0;
  for (const auto& [text, value] : names) {
    if (name == text) return value;
    use += std::string(k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + "\"" + text + "\"";
    ++k;
  }
  throw Error(std::string(key) + ": unknown " + noun + " '" + name + "' (use " + use + ")");
}

std::string stringOf(const json& j, const std::string& what) {
  if (!j.is_string()) throw Error(what + ": expected a string");
  return j.get<std::string>();
}

}  // namespace

Strategy strategyFromName(const std::string& name) {
  return fromName<Strategy>(name, "strategy", "strategy", {{"packing", Strategy::Packing}, {"grid", Strategy::Grid}});
}

PackingOrder packingOrderFromName(const std::string& name) {
  return fromName<PackingOrder>(
      name, "packing_order", "order",
      {{"auto", PackingOrder::Auto}, {"hole_degree", PackingOrder::HoleDegree}, {"lattice", PackingOrder::Lattice}});
}

GrowthPattern growthPatternFromName(const std::string& name) {
  return fromName<GrowthPattern>(
      name, "growth_pattern", "pattern",
      {{"auto", GrowthPattern::Auto}, {"rows", GrowthPattern::Rows}, {"offsets", GrowthPattern::Offsets}});
}

TourMethod tourMethodFromName(const std::string& name) {
  return fromName<TourMethod>(name, "sequencing", "method",
                              {{"local_search", TourMethod::LocalSearch}, {"annealing", TourMethod::Annealing}});
}

Coolant coolantFromName(const std::string& name) {
  return fromName<Coolant>(name, "coolant", "coolant",
                           {{"off", Coolant::Off}, {"flood", Coolant::Flood}, {"mist", Coolant::Mist}});
}

GridPattern gridPatternFromName(const std::string& name) {
  return fromName<GridPattern>(name, "grid.pattern", "pattern",
                               {{"square", GridPattern::Square}, {"honeycomb", GridPattern::Honeycomb}});
}

namespace {

// notes: what was read in an old spelling and migrated, said in the plan.
std::vector<Tool> toolList(const json& ts, const std::string& what, std::vector<std::string>& notes) {
  if (!ts.is_array()) throw Error(what + ": expected a list of {\"diameter\": ...}");
  std::vector<Tool> tools;
  for (size_t i = 0; i < ts.size(); ++i) {
    const std::string name = what + "[" + std::to_string(i) + "]";
    if (!ts[i].is_object()) throw Error(name + ": expected an object with a diameter");
    onlyKeys(ts[i],
             {"diameter", "id", "feed", "shape", "corner_radius", "max_engagement", "min_engagement",
              "center_cutting", "core_diameter", "flute_length", "peck_depth", "stick_out", "holder_diameter",
              "shank_diameter", "spindle_speed"},
             name + ": ");
    if (!ts[i].contains("diameter")) throw Error(name + ".diameter: required");
    Tool t;
    t.diameter = number(ts[i]["diameter"], name + ".diameter");
    t.id = -1;
    if (ts[i].contains("id")) {
      if (!ts[i]["id"].is_number_integer() || ts[i]["id"].get<long long>() <= 0 ||
          ts[i]["id"].get<long long>() > kMaxToolId)
        throw Error(name + ".id: expected a positive integer up to " + std::to_string(kMaxToolId));
      t.id = ts[i]["id"].get<int>();
    }
    if (ts[i].contains("feed")) t.feed = number(ts[i]["feed"], name + ".feed");
    if (ts[i].contains("shape")) {
      const json& sh = ts[i]["shape"];
      const std::string v = sh.is_string() ? sh.get<std::string>() : "";
      if (v == "flat") t.shape = CutterShape::Flat;
      else if (v == "ball") t.shape = CutterShape::Ball;
      else if (v == "bull") t.shape = CutterShape::Bull;
      else throw Error(name + ".shape: expected \"flat\", \"ball\" or \"bull\"");
    }
    if (ts[i].contains("corner_radius")) t.cornerRadius = number(ts[i]["corner_radius"], name + ".corner_radius");
    // A real plunge mill. A length given must be positive.
    auto length = [&](const char* key) {
      const double v = number(ts[i][key], name + "." + key);
      if (!(v > 0.0)) throw Error(name + "." + key + " must be > 0 (leave it out for no limit)");
      return v;
    };
    // No limit is an absent key; 0 and null, its old spellings, are read as
    // absent and said.
    auto limit = [&](const char* key, std::optional<double>& v) {
      if (!ts[i].contains(key)) return;
      const json& given = ts[i][key];
      if (given.is_null() || (given.is_number() && given.get<double>() == 0.0)) {
        notes.push_back(name + "." + key + ": " + (given.is_null() ? "null" : "0") +
                        " is read as no limit (leave the key out to say so)");
        return;
      }
      v = length(key);
    };
    limit("max_engagement", t.maxEngagement);
    limit("min_engagement", t.minEngagement);
    limit("flute_length", t.fluteLength);
    // What holds it (holder.hpp): absent is not known.
    for (const auto& [key, v] : {std::pair{"stick_out", &t.stickOut}, std::pair{"holder_diameter", &t.holderDiameter},
                                 std::pair{"shank_diameter", &t.shankDiameter}})
      if (ts[i].contains(key)) *v = length(key);
    if (ts[i].contains("core_diameter")) t.coreDiameter = length("core_diameter");
    if (ts[i].contains("peck_depth")) t.peckDepth = length("peck_depth");
    if (ts[i].contains("spindle_speed")) {
      const double n = number(ts[i]["spindle_speed"], name + ".spindle_speed");
      if (!(n > 0.0 && n <= kMaxSpindleSpeed))
        throw Error(name + ".spindle_speed: expected rev/min above 0 and up to " +
                    std::to_string(static_cast<int>(kMaxSpindleSpeed)));
      t.spindleSpeed = n;
    }
    if (ts[i].contains("center_cutting")) {
      if (!ts[i]["center_cutting"].is_boolean()) throw Error(name + ".center_cutting: expected true or false");
      t.centerCutting = ts[i]["center_cutting"].get<bool>();
    }
    tools.push_back(t);
  }
  // Default tool numbers: 1, 2, ... by decreasing diameter.
  for (Tool& t : tools)
    if (t.id < 0)
      t.id = 1 + static_cast<int>(std::count_if(tools.begin(), tools.end(),
                                                [&](const Tool& o) { return o.diameter > t.diameter; }));
  return tools;
}

// Checks j[key] is an object with only the given keys. Returns nothing: a
// reference returned past a temporary key set reads as dangling to GCC 14.
void checkObject(const json& j, const char* key, const std::set<std::string>& keys) {
  const json& o = j[key];
  if (!o.is_object()) throw Error(std::string(key) + ": expected an object");
  onlyKeys(o, keys, std::string(key) + ": ");
}

void readTools(const json& j, PlanInput& in) {
  if (j.contains("tools") && j["tools"].is_string() && j["tools"].get<std::string>() == "auto") {
    in.choice.automatic = true;
    if (!j.contains("tool_library")) throw Error("tool_library: required with \"tools\": \"auto\"");
    in.choice.library = toolList(j["tool_library"], "tool_library", in.notes);
    return;
  }
  if (!j.contains("tools") || !j["tools"].is_array())
    throw Error("tools: expected a list of {\"diameter\": ...} or \"auto\" with a tool_library");
  if (j.contains("tool_library")) throw Error("tool_library: only with \"tools\": \"auto\"");
  in.tools = toolList(j["tools"], "tools", in.notes);
}

}  // namespace

MaterialGrid materialFromValue(const json& j) {
  if (!j.is_object()) throw Error("material: expected {\"origin\", \"spacing\", \"nx\", \"ny\", \"top\"}");
  onlyKeys(j, {"origin", "spacing", "nx", "ny", "top"}, "material: ");
  for (const char* key : {"origin", "spacing", "nx", "ny", "top"})
    if (!j.contains(key)) throw Error(std::string("material.") + key + ": required");
  MaterialGrid g;
  g.origin = point(j["origin"], "material.origin");
  g.spacing = number(j["spacing"], "material.spacing");
  for (const auto& [key, n] : {std::pair{"nx", &g.nx}, std::pair{"ny", &g.ny}}) {
    if (!j[key].is_number_integer() || j[key].get<long long>() <= 0)
      throw Error(std::string("material.") + key + ": expected a positive whole number of cells");
    *n = j[key].get<size_t>();
  }
  const json& top = j["top"];
  if (!top.is_array() || top.size() / g.nx / g.ny != 1 || top.size() != g.nx * g.ny)
    throw Error("material.top: expected nx * ny = " + std::to_string(g.nx) + " * " + std::to_string(g.ny) +
                " heights, row by row");
  g.top.reserve(top.size());
  for (const json& v : top) g.top.push_back(number(v, "material.top"));
  return g;
}

namespace {

// "floor" or "part": {"mesh": {"vertices": [[x, y, z], ...], "triangles":
// [[i, j, k], ...], "deviation": mm, or [mm, ...] one per triangle}} (key:
// "floor.mesh" or "part.mesh"); the indices and the deviations' count are
// checked where the mesh is made a surface (mesh_floor.hpp checkMesh).
TriangleMesh readMesh(const json& m, const std::string& key) {
  if (!m.is_object()) throw Error(key + ": expected {\"vertices\", \"triangles\", \"deviation\"}");
  onlyKeys(m, {"vertices", "triangles", "deviation"}, key + ": ");
  for (const char* field : {"vertices", "triangles", "deviation"})
    if (!m.contains(field)) throw Error(key + "." + field + ": required");
  TriangleMesh mesh;
  // One distance for every triangle, or a list of one per triangle.
  const json& dev = m["deviation"];
  mesh.deviation.clear();
  if (dev.is_array()) {
    for (const json& v : dev) mesh.deviation.push_back(number(v, key + ".deviation"));
  } else {
    mesh.deviation.push_back(number(dev, key + ".deviation"));
  }
  const json& vs = m["vertices"];
  if (!vs.is_array()) throw Error(key + ".vertices: expected a list of [x, y, z]");
  mesh.vertices.reserve(vs.size());
  for (size_t i = 0; i < vs.size(); ++i) {
    const std::string what = key + ".vertices[" + std::to_string(i) + "]";
    if (!vs[i].is_array() || vs[i].size() != 3) throw Error(what + ": expected [x, y, z]");
    mesh.vertices.push_back({number(vs[i][0], what), number(vs[i][1], what), number(vs[i][2], what)});
  }
  const json& ts = m["triangles"];
  if (!ts.is_array()) throw Error(key + ".triangles: expected a list of [i, j, k] vertex indices");
  mesh.triangles.reserve(ts.size());
  for (size_t i = 0; i < ts.size(); ++i) {
    const std::string what = key + ".triangles[" + std::to_string(i) + "]";
    if (!ts[i].is_array() || ts[i].size() != 3) throw Error(what + ": expected [i, j, k]");
    std::array<std::uint32_t, 3> t{};
    for (size_t k = 0; k < 3; ++k) {
      if (!ts[i][k].is_number_integer() || ts[i][k].get<long long>() < 0 ||
          ts[i][k].get<long long>() > std::numeric_limits<std::uint32_t>::max())
        throw Error(what + ": expected vertex indices (whole numbers from 0)");
      t[k] = ts[i][k].get<std::uint32_t>();
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

Floor readFloor(const json& j) {
  if (!j.contains("floor") || !j["floor"].is_object()) throw Error("floor: required, e.g. {\"z\": -10}");
  const json& f = j["floor"];
  onlyKeys(f, {"z", "expression", "brep", "mesh"}, "floor: ");
  if (f.size() != 1) throw Error("floor: give exactly one of z, expression, brep, mesh");
  Floor floor;
  if (f.contains("z")) {
    floor.kind = Floor::Kind::Flat;
    floor.z = number(f["z"], "floor.z");
  } else if (f.contains("expression")) {
    floor.kind = Floor::Kind::Expression;
    floor.expression = stringOf(f["expression"], "floor.expression");
  } else if (f.contains("mesh")) {
    floor.kind = Floor::Kind::Mesh;
    floor.mesh = readMesh(f["mesh"], "floor.mesh");
  } else {
    if (!f["brep"].is_string()) throw Error("floor.brep: expected a file name");
    floor.kind = Floor::Kind::Brep;
    floor.brep = f["brep"].get<std::string>();
  }
  return floor;
}

// The objects of options: allowance, selection, time_model, grid.
void readOptionObjects(const json& j, PlanInput& in) {
  if (j.contains("allowance")) {
    const json& a = j["allowance"];
    if (!a.is_object()) throw Error("allowance: expected {\"radial\": ..., \"floor\": ...}");
    onlyKeys(a, {"radial", "floor"}, "allowance: ");
    if (a.contains("radial")) in.radialAllowance = number(a["radial"], "allowance.radial");
    if (a.contains("floor")) in.floorAllowance = number(a["floor"], "allowance.floor");
  }
  if (j.contains("selection")) {
    checkObject(j, "selection", {"weight_time", "weight_tools", "rise_factor"});
    const json& o = j["selection"];
    if (o.contains("weight_time")) in.choice.weights.weightTime = number(o["weight_time"], "selection.weight_time");
    if (o.contains("weight_tools")) in.choice.weights.weightTools = number(o["weight_tools"], "selection.weight_tools");
    if (o.contains("rise_factor")) in.choice.weights.riseFactor = number(o["rise_factor"], "selection.rise_factor");
  }
  if (j.contains("time_model")) {
    checkObject(j, "time_model", {"rapid_rate", "retract_rate", "tool_change_seconds"});
    const json& o = j["time_model"];
    if (o.contains("rapid_rate")) in.motion.timeModel.rapidRate = number(o["rapid_rate"], "time_model.rapid_rate");
    if (o.contains("retract_rate")) in.motion.timeModel.retractRate = number(o["retract_rate"], "time_model.retract_rate");
    if (o.contains("tool_change_seconds"))
      in.motion.timeModel.toolChangeSeconds = number(o["tool_change_seconds"], "time_model.tool_change_seconds");
  }
  if (j.contains("grid")) {
    checkObject(j, "grid", {"pattern", "step"});
    const json& o = j["grid"];
    if (o.contains("pattern")) in.packing.gridPattern = gridPatternFromName(stringOf(o["pattern"], "grid.pattern"));
    if (o.contains("step")) in.packing.gridStep = number(o["step"], "grid.step");
  }
}

// The top-level numbers, flags and named options.
void readScalars(const json& j, PlanInput& in) {
  const std::pair<const char*, double*> numbers[] = {
      {"top_z", &in.topZ},
      {"safe_z", &in.safeZ},
      {"min_coverage", &in.covering.minCoverage},
      {"max_wall_stock", &in.covering.maxWallStock},
      {"max_floor_stock", &in.floor.maxFloorStock},
      {"lead_out", &in.motion.leadOut},
      {"rapid_clearance", &in.motion.rapidClearance},
      {"holder_clearance", &in.motion.holderClearance},
      {"max_plunges", &in.maxPlunges},
      {"contact_ratio", &in.packing.contactRatio},
      {"peck_dwell", &in.motion.peckDwell}};
  for (const auto& [key, value] : numbers)
    if (j.contains(key)) *value = number(j[key], key);
  if (j.contains("final_depth")) in.floor.finalDepth = number(j["final_depth"], "final_depth");
  if (j.contains("peck")) {
    if (!j["peck"].is_boolean()) throw Error("peck: expected true or false");
    in.motion.peck = j["peck"].get<bool>();
  }
  if (j.contains("stock_aware_heights")) {
    if (!j["stock_aware_heights"].is_boolean()) throw Error("stock_aware_heights: expected true or false");
    in.motion.stockAwareHeights = j["stock_aware_heights"].get<bool>();
  }
  if (j.contains("seed")) {
    if (!j["seed"].is_number_integer() || j["seed"].get<long long>() < 0)
      throw Error("seed: expected a non-negative integer");
    in.seed = j["seed"].get<std::uint64_t>();
  }
  if (j.contains("start")) in.motion.start = point(j["start"], "start");
  if (j.contains("strategy")) in.packing.strategy = strategyFromName(stringOf(j["strategy"], "strategy"));
  if (j.contains("packing_order"))
    in.packing.order = packingOrderFromName(stringOf(j["packing_order"], "packing_order"));
  if (j.contains("growth_pattern"))
    in.engagement.pattern = growthPatternFromName(stringOf(j["growth_pattern"], "growth_pattern"));
  if (j.contains("sequencing")) in.motion.sequencing = tourMethodFromName(stringOf(j["sequencing"], "sequencing"));
  if (j.contains("coolant")) in.motion.coolant = coolantFromName(stringOf(j["coolant"], "coolant"));
}

}  // namespace

namespace {

// The text as JSON; syntax errors and numbers out of range are bad input.
json parsed(const std::string& text, const std::string& what) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    std::string msg = e.what();
    throw Error(what + "invalid JSON: " + msg.substr(msg.find(']') == std::string::npos ? 0 : msg.find(']') + 2));
  }
}

}  // namespace

std::vector<Tool> toolsFromValue(const json& value) {
  std::vector<std::string> notes;
  return toolList(value, "tools", notes);
}

PlanInput planInputFromJson(const std::string& text) { return planInputFromValue(parsed(text, "")); }

PlanInput planInputFromValue(const json& j) {
  if (!j.is_object()) throw Error("input: expected a JSON object");
  onlyKeys(j,
           {"version", "boundary", "islands", "tools", "top_z", "safe_z", "floor", "allowance", "strategy", "seed",
            "min_coverage", "contact_ratio", "packing_order", "growth_pattern", "sequencing", "start",
            "tool_library", "selection", "time_model", "grid", "max_wall_stock", "max_floor_stock", "lead_out",
            "stock_aware_heights", "rapid_clearance", "holder_clearance", "max_plunges", "final_depth", "peck", "peck_dwell",
            "sections", "material", "coolant", "part"},
           "input: ");
  PlanInput in;
  if (j.contains("version") && !(j["version"].is_number_integer() && j["version"].get<long long>() == 1))
    throw Error("version: only version 1 is supported");
  if (!j.contains("boundary")) throw Error("boundary: required");
  in.boundary = loop(j["boundary"], "boundary");
  if (j.contains("islands")) {
    const json& is = j["islands"];
    if (!is.is_array()) throw Error("islands: expected a list of polylines");
    for (size_t i = 0; i < is.size(); ++i) in.islands.push_back(loop(is[i], "islands[" + std::to_string(i) + "]"));
  }
  if (j.contains("sections")) {
    const json& ss = j["sections"];
    if (!ss.is_array()) throw Error("sections: expected a list of {\"z\", \"boundary\", \"islands\"}");
    for (size_t k = 0; k < ss.size(); ++k) {
      const std::string name = "sections[" + std::to_string(k) + "]";
      if (!ss[k].is_object() || !ss[k].contains("z") || !ss[k].contains("boundary"))
        throw Error(name + ": expected {\"z\", \"boundary\", \"islands\"}");
      onlyKeys(ss[k], {"z", "boundary", "islands"}, name + ": ");
      Section s;
      s.z = number(ss[k]["z"], name + ".z");
      s.boundary = loop(ss[k]["boundary"], name + ".boundary");
      if (ss[k].contains("islands")) {
        if (!ss[k]["islands"].is_array()) throw Error(name + ".islands: expected a list of polylines");
        for (size_t i = 0; i < ss[k]["islands"].size(); ++i)
          s.islands.push_back(loop(ss[k]["islands"][i], name + ".islands[" + std::to_string(i) + "]"));
      }
      in.floor.sections.push_back(std::move(s));
    }
  }
  if (j.contains("material")) in.material = materialFromValue(j["material"]);
  if (j.contains("part")) {
    const json& part = j["part"];
    if (!part.is_object() || part.size() != 1 || !part.contains("mesh"))
      throw Error("part: expected {\"mesh\": {\"vertices\", \"triangles\", \"deviation\"}}");
    in.part = readMesh(part["mesh"], "part.mesh");
  }
  readTools(j, in);
  in.floor.surface = readFloor(j);
  readOptionObjects(j, in);
  readScalars(j, in);
  return in;
}

PlanInput readPlanInput(const std::string& path) {
  // UTF-8 paths: on Windows a narrow path would be read in the ANSI code page.
  const std::filesystem::path file = std::filesystem::u8path(path);
  std::error_code ec;
  std::ifstream f(file, std::ios::binary);
  if (!f || std::filesystem::is_directory(file, ec)) throw Error("cannot read " + path);
  std::ostringstream text;
  text << f.rdbuf();
  PlanInput in = planInputFromJson(text.str());
  const std::filesystem::path folder = std::filesystem::absolute(file, ec).parent_path();
  in.baseDir = ec ? file.parent_path().u8string() : folder.u8string();
  if (in.baseDir.empty()) in.baseDir = ".";
  return in;
}

std::string planToJson(const Plan& plan) { return planToValue(plan).dump(1) + "\n"; }

json planToValue(const Plan& plan) {
  json out;
  out["plunges"] = json::array();
  for (const Plunge& p : plan.plunges) {
    json o = {{"x", p.x},
              {"y", p.y},
              {"diameter", p.diameter},
              {"tool_id", p.toolId},
              {"z", p.z},
              {"approach_z", p.approachZ},
              {"retract_z", p.retractZ},
              {"engagement", p.engagement},
              {"level", p.level},
              {"start", p.start},
              {"start_hole", p.startHole}};
    if (p.leadOut) o["lead_out"] = {p.leadOut->x, p.leadOut->y};
    if (p.leadOutZ) o["lead_out_z"] = *p.leadOutZ;
    if (!p.via.empty()) {
      nlohmann::json via = nlohmann::json::array();
      for (Vec2 v : p.via) via.push_back({v.x, v.y});
      o["via"] = via;
    }
    if (!p.pecks.empty()) o["pecks"] = p.pecks;
    if (p.holderLimited) o["holder_limited"] = true;
    out["plunges"].push_back(o);
  }
  const PlanStats& s = plan.stats;
  json per = json::array();
  for (const ToolCount& t : s.perTool) {
    json o = {{"tool_id", t.toolId}, {"diameter", t.diameter}, {"count", t.count}, {"peck_depth", t.peckDepth}};
    // The tool as mounted, when given, and what its holder stopped.
    if (t.stickOut) o["stick_out"] = *t.stickOut;
    if (t.holderDiameter) o["holder_diameter"] = *t.holderDiameter;
    if (t.shankDiameter) o["shank_diameter"] = *t.shankDiameter;
    if (t.stickOut) o["holder_limited"] = t.holderLimited;
    per.push_back(o);
  }
  out["stats"] = {{"plunge_count", s.plungeCount},
                  {"per_tool", per},
                  {"region_area", s.regionArea},
                  {"accessible_area", s.accessibleArea},
                  {"covered_area", s.coveredArea},
                  {"coverage", s.coverage},
                  {"travel_length", s.travelLength},
                  {"planning_seconds", s.planningSeconds},
                  {"hex_reference_count", s.hexReferenceCount},
                  {"estimated_minutes", s.estimatedMinutes},
                  {"core_area", s.coreArea},
                  {"core_coverage", s.coreCoverage},
                  {"max_wall_stock_left", s.maxWallStockLeft},
                  {"max_floor_stock_left", s.maxFloorStockLeft},
                  {"mean_floor_stock", s.meanFloorStock},
                  {"volume_removed", s.volumeRemoved},
                  {"volume_left", s.volumeLeft},
                  {"volume_before", s.volumeBefore},
                  {"air_plunges", s.airPlunges},
                  {"rest_material", s.restMaterial},
                  {"floor_stock_plunges", s.floorStockPlunges},
                  // Its old name, still written for readers of older plans (docs/plan-format.md).
                  {"rest_plunges", s.floorStockPlunges},
                  {"start_holes", s.startHoles},
                  {"over_engaged", s.overEngaged},
                  {"thin_cuts", s.thinCuts},
                  {"lead_outs", s.leadOuts},
                  {"raised_lead_outs", s.raisedLeadOuts},
                  {"no_lead_out_material", s.noLeadOutMaterial},
                  {"no_lead_out_walls", s.noLeadOutWalls},
                  {"levels", s.levels},
                  {"minutes_at_safe_height", s.minutesAtSafeHeight},
                  {"boundary_tolerance", s.boundaryTolerance},
                  {"pecked_plunges", s.peckedPlunges},
                  {"depth_fallbacks", s.depthFallbacks},
                  {"floor_kind", s.floorKind}};
  if (!plan.warnings.empty()) out["warnings"] = plan.warnings;
  if (!plan.broken.empty()) {
    json broken = json::array();
    for (const BrokenLimit& b : plan.broken)
      broken.push_back({{"limit", b.limit}, {"asked", b.asked}, {"worst", b.worst}, {"at", {b.at.x, b.at.y}},
                        {"count", b.count}, {"why", b.why}});
    out["broken_limits"] = broken;
  }
  if (plan.selection) {
    const ToolSelection& sel = *plan.selection;
    json necks = json::array(), parts = json::array(), sets = json::array();
    for (const Neck& n : sel.necks)
      necks.push_back({{"x", n.center.x}, {"y", n.center.y}, {"width", n.width}, {"island", n.island},
                       {"line", {{n.a.x, n.a.y}, {n.b.x, n.b.y}}}});
    for (const SubRegion& p : sel.parts)
      parts.push_back({{"area", p.area}, {"inscribed_diameter", 2 * p.inscribed.r},
                       {"inscribed_center", {p.inscribed.c.x, p.inscribed.c.y}}, {"necks", p.necks}});
    for (const ToolSetResult& r : sel.sets) {
      json o = {{"diameters", r.diameters}, {"evaluated", r.evaluated}, {"estimated_minutes", r.minutes},
                {"weighted", r.weighted}};
      if (r.evaluated) {
        o["plunges"] = r.plunges;
        o["coverage"] = r.coverage;
        o["estimate"] = r.estimate;
      } else if (r.plunges > 0) {
        o["plunges"] = r.plunges;
      } else if (!r.refused.empty()) {
        o["refused"] = r.refused;
      } else {
        o["pruned"] = r.subtree ? "with every set adding smaller candidates" : "lower bound";
      }
      sets.push_back(o);
    }
    out["tool_selection"] = {{"largest_inscribed_diameter", 2 * sel.inscribed.r},
                             {"necks", necks},
                             {"subregions", parts},
                             {"subregion_order", sel.order},
                             {"candidates", sel.candidates},
                             {"sets", sets},
                             {"chosen", sel.chosen},
                             {"reasoning", sel.reasoning}};
  }
  return out;
}

}  // namespace plunge
