#include "plunge/io.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "detail.hpp"
#include "plunge/error.hpp"
#include "plunge/limits.hpp"

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

TourMethod tourMethodFromName(const std::string& name) {
  return fromName<TourMethod>(name, "sequencing", "method",
                              {{"local_search", TourMethod::LocalSearch}, {"annealing", TourMethod::Annealing}});
}

GridPattern gridPatternFromName(const std::string& name) {
  return fromName<GridPattern>(name, "grid.pattern", "pattern",
                               {{"square", GridPattern::Square}, {"honeycomb", GridPattern::Honeycomb}});
}

namespace {

std::vector<Tool> toolList(const json& ts, const std::string& what) {
  if (!ts.is_array()) throw Error(what + ": expected a list of {\"diameter\": ...}");
  std::vector<Tool> tools;
  for (size_t i = 0; i < ts.size(); ++i) {
    const std::string name = what + "[" + std::to_string(i) + "]";
    if (!ts[i].is_object()) throw Error(name + ": expected an object with a diameter");
    onlyKeys(ts[i],
             {"diameter", "id", "feed", "shape", "corner_radius", "max_engagement", "min_engagement",
              "center_cutting", "core_diameter", "flute_length"},
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
    // A real plunge mill (absent: no limit). A given limit must be a positive length.
    auto limit = [&](const char* key, double& v) {
      if (!ts[i].contains(key)) return;
      v = number(ts[i][key], name + "." + key);
      if (!(v > 0.0)) throw Error(name + "." + key + " must be > 0 (leave it out for no limit)");
    };
    limit("max_engagement", t.maxEngagement);
    limit("min_engagement", t.minEngagement);
    limit("flute_length", t.fluteLength);
    limit("core_diameter", t.coreDiameter);
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
    in.autoTools = true;
    if (!j.contains("tool_library")) throw Error("tool_library: required with \"tools\": \"auto\"");
    in.library = toolList(j["tool_library"], "tool_library");
    return;
  }
  if (!j.contains("tools") || !j["tools"].is_array())
    throw Error("tools: expected a list of {\"diameter\": ...} or \"auto\" with a tool_library");
  if (j.contains("tool_library")) throw Error("tool_library: only with \"tools\": \"auto\"");
  in.tools = toolList(j["tools"], "tools");
}

Floor readFloor(const json& j) {
  if (!j.contains("floor") || !j["floor"].is_object()) throw Error("floor: required, e.g. {\"z\": -10}");
  const json& f = j["floor"];
  onlyKeys(f, {"z", "expression", "brep"}, "floor: ");
  if (f.size() != 1) throw Error("floor: give exactly one of z, expression, brep");
  Floor floor;
  if (f.contains("z")) {
    floor.kind = Floor::Kind::Flat;
    floor.z = number(f["z"], "floor.z");
  } else if (f.contains("expression")) {
    floor.kind = Floor::Kind::Expression;
    floor.expression = stringOf(f["expression"], "floor.expression");
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
    if (o.contains("weight_time")) in.selection.weightTime = number(o["weight_time"], "selection.weight_time");
    if (o.contains("weight_tools")) in.selection.weightTools = number(o["weight_tools"], "selection.weight_tools");
    if (o.contains("rise_factor")) in.selection.riseFactor = number(o["rise_factor"], "selection.rise_factor");
  }
  if (j.contains("time_model")) {
    checkObject(j, "time_model", {"rapid_rate", "retract_rate", "tool_change_seconds"});
    const json& o = j["time_model"];
    if (o.contains("rapid_rate")) in.timeModel.rapidRate = number(o["rapid_rate"], "time_model.rapid_rate");
    if (o.contains("retract_rate")) in.timeModel.retractRate = number(o["retract_rate"], "time_model.retract_rate");
    if (o.contains("tool_change_seconds"))
      in.timeModel.toolChangeSeconds = number(o["tool_change_seconds"], "time_model.tool_change_seconds");
  }
  if (j.contains("grid")) {
    checkObject(j, "grid", {"pattern", "step"});
    const json& o = j["grid"];
    if (o.contains("pattern")) in.gridPattern = gridPatternFromName(stringOf(o["pattern"], "grid.pattern"));
    if (o.contains("step")) in.gridStep = number(o["step"], "grid.step");
  }
}

// The top-level numbers, flags and named options.
void readScalars(const json& j, PlanInput& in) {
  const std::pair<const char*, double*> numbers[] = {
      {"top_z", &in.topZ},
      {"safe_z", &in.safeZ},
      {"min_coverage", &in.minCoverage},
      {"max_wall_stock", &in.maxWallStock},
      {"max_floor_stock", &in.maxFloorStock},
      {"lead_out", &in.leadOut},
      {"rapid_clearance", &in.rapidClearance},
      {"max_plunges", &in.maxPlunges},
      {"contact_ratio", &in.contactRatio}};
  for (const auto& [key, value] : numbers)
    if (j.contains(key)) *value = number(j[key], key);
  if (j.contains("final_depth")) in.finalDepth = number(j["final_depth"], "final_depth");
  if (j.contains("stock_aware_heights")) {
    if (!j["stock_aware_heights"].is_boolean()) throw Error("stock_aware_heights: expected true or false");
    in.stockAwareHeights = j["stock_aware_heights"].get<bool>();
  }
  if (j.contains("seed")) {
    if (!j["seed"].is_number_integer() || j["seed"].get<long long>() < 0)
      throw Error("seed: expected a non-negative integer");
    in.seed = j["seed"].get<std::uint64_t>();
  }
  if (j.contains("start")) in.start = point(j["start"], "start");
  if (j.contains("strategy")) in.strategy = strategyFromName(stringOf(j["strategy"], "strategy"));
  if (j.contains("packing_order"))
    in.packingOrder = packingOrderFromName(stringOf(j["packing_order"], "packing_order"));
  if (j.contains("sequencing")) in.sequencing = tourMethodFromName(stringOf(j["sequencing"], "sequencing"));
}

}  // namespace

PlanInput planInputFromJson(const std::string& text) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // syntax errors, numbers out of range
    std::string msg = e.what();
    throw Error("invalid JSON: " + msg.substr(msg.find(']') == std::string::npos ? 0 : msg.find(']') + 2));
  }
  if (!j.is_object()) throw Error("input: expected a JSON object");
  onlyKeys(j,
           {"version", "boundary", "islands", "tools", "top_z", "safe_z", "floor", "allowance", "strategy", "seed",
            "min_coverage", "contact_ratio", "packing_order", "sequencing", "start", "tool_library", "selection",
            "time_model", "grid", "max_wall_stock", "max_floor_stock", "lead_out", "stock_aware_heights",
            "rapid_clearance", "max_plunges", "final_depth"},
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
  readTools(j, in);
  in.floor = readFloor(j);
  readOptionObjects(j, in);
  readScalars(j, in);
  return in;
}

PlanInput readPlanInput(const std::string& path) {
  std::error_code ec;
  std::ifstream f(path, std::ios::binary);
  if (!f || std::filesystem::is_directory(path, ec)) throw Error("cannot read " + path);
  std::ostringstream text;
  text << f.rdbuf();
  PlanInput in = planInputFromJson(text.str());
  const std::filesystem::path folder = std::filesystem::absolute(path, ec).parent_path();
  in.baseDir = ec ? std::filesystem::path(path).parent_path().string() : folder.string();
  if (in.baseDir.empty()) in.baseDir = ".";
  return in;
}

std::string planToJson(const Plan& plan) {
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
    out["plunges"].push_back(o);
  }
  const PlanStats& s = plan.stats;
  json per = json::array();
  for (const ToolCount& t : s.perTool) per.push_back({{"tool_id", t.toolId}, {"diameter", t.diameter}, {"count", t.count}});
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
                  {"rest_plunges", s.restPlunges},
                  {"start_holes", s.startHoles},
                  {"over_engaged", s.overEngaged},
                  {"thin_cuts", s.thinCuts},
                  {"lead_outs", s.leadOuts},
                  {"no_lead_out_material", s.noLeadOutMaterial},
                  {"no_lead_out_walls", s.noLeadOutWalls},
                  {"levels", s.levels},
                  {"minutes_at_safe_height", s.minutesAtSafeHeight},
                  {"boundary_tolerance", s.boundaryTolerance}};
  if (!plan.warnings.empty()) out["warnings"] = plan.warnings;
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
  return out.dump(1) + "\n";
}

namespace {

const char* kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#17becf", "#bcbd22"};
// Darker shades of the same hues for the tool paths drawn over the disks.
const char* kPathPalette[] = {"#0b3c61", "#a34f00", "#13561a", "#4b2a6e", "#4a2c25", "#8c2a73", "#0b6570", "#66660f"};

std::string pathData(const Polygons& loops) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(3);
  for (const Loop& L : loops) {
    for (size_t i = 0; i < L.size(); ++i) s << (i ? " L" : "M") << L[i].x << " " << -L[i].y;
    s << " Z ";
  }
  return s.str();
}

// Colour of a floor stock: green (none) to yellow (the limit), then to red (twice
// the limit and more); quantized in 16 steps so that equal runs merge.
std::string stockColour(double stock, double limit) {
  const double t = std::clamp(stock / std::max(limit, 1e-9), 0.0, 2.0);
  const double q = std::round(t * 8) / 8;
  int r, g, b;
  if (q <= 1) {
    r = static_cast<int>(40 + 215 * q);
    g = static_cast<int>(170 + 50 * q);
    b = 60;
  } else {
    r = 230;
    g = static_cast<int>(220 * (2 - q));
    b = 40;
  }
  std::ostringstream c;
  c << "rgb(" << r << "," << g << "," << b << ")";
  return c.str();
}

// The floor stock left as coloured cells, runs of one colour in a row merged.
std::string stockMapSvg(const StockMap& m, double limit) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(3) << "<g stroke=\"none\">\n";
  for (size_t j = 0; j < m.ny; ++j) {
    size_t i = 0;
    while (i < m.nx) {
      const float v = m.stock[j * m.nx + i];
      if (std::isnan(v)) {
        ++i;
        continue;
      }
      const std::string c = stockColour(v, limit);
      size_t k = i + 1;
      while (k < m.nx && !std::isnan(m.stock[j * m.nx + k]) && stockColour(m.stock[j * m.nx + k], limit) == c) ++k;
      const double x = m.origin.x + (i - 0.5) * m.spacing, y = m.origin.y + (j + 0.5) * m.spacing;
      s << "<rect x=\"" << x << "\" y=\"" << -y << "\" width=\"" << (k - i) * m.spacing << "\" height=\"" << m.spacing
        << "\" fill=\"" << c << "\"/>\n";
      i = k;
    }
  }
  s << "</g>\n";
  return s.str();
}

// The plan's picture, layer by layer (planToSvg); y is drawn downwards.
class SvgPicture {
 public:
  SvgPicture(const PlanInput& input, const Plan& plan) : in_(input), plan_(plan) {
    detail::Bounds box;
    box.add(input.boundary);
    lo_ = box.lo;
    hi_ = box.hi;
    size_ = std::max(hi_.x - lo_.x, hi_.y - lo_.y);
    sw_ = size_ / 900.0;
    fs_ = 0.032 * size_;
    for (const ToolCount& t : plan.stats.perTool) colour_.emplace(t.toolId, static_cast<int>(colour_.size()));
    // The stock map's colour scale: yellow at the limit (1 mm when none is set).
    stockScale_ = input.maxFloorStock > 0.0 ? input.maxFloorStock : 1.0;
    for (const Plunge& p : plan.plunges) {
      zLo_ = std::min(zLo_, p.z);
      zHi_ = std::max(zHi_, p.z);
    }
    depthDots_ = !plan.plunges.empty() && zHi_ - zLo_ > 1e-9;
    s_ << std::fixed << std::setprecision(3);
  }

  std::string draw() {
    frame();
    pocket();
    plunges();
    marks();
    legend();
    s_ << "</svg>\n";
    return s_.str();
  }

 private:
  void frame() {
    const double w = hi_.x - lo_.x, h = hi_.y - lo_.y, margin = 0.04 * size_;
    legendH_ = 0.05 * size_ * (5 + plan_.stats.perTool.size() + (plan_.stockMap ? 1 : 0));
    const double vx = lo_.x - margin, vy = -hi_.y - margin - legendH_, vw = w + 2 * margin,
                 vh = h + 2 * margin + legendH_;
    const double pxW = 1200.0, pxH = pxW * vh / vw;
    s_ << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << pxW << "\" height=\"" << pxH << "\" viewBox=\""
       << vx << " " << vy << " " << vw << " " << vh << "\">\n";
    s_ << "<rect x=\"" << vx << "\" y=\"" << vy << "\" width=\"" << vw << "\" height=\"" << vh
       << "\" fill=\"white\"/>\n";
  }

  // The pocket, its islands and the accessible region's outline (dashed).
  void pocket() {
    Polygons all{in_.boundary};
    for (const Loop& L : in_.islands) all.push_back(L);
    s_ << "<path d=\"" << pathData(all) << "\" fill=\"#e8e8e8\" fill-rule=\"evenodd\" stroke=\"#222\" stroke-width=\""
       << 2 * sw_ << "\"/>\n";
    for (const Loop& L : in_.islands)
      s_ << "<path d=\"" << pathData({L}) << "\" fill=\"#9a9a9a\" stroke=\"#222\" stroke-width=\"" << 2 * sw_
         << "\"/>\n";
    s_ << "<path d=\"" << pathData(plan_.accessible) << "\" fill=\"none\" stroke=\"#555\" stroke-dasharray=\""
       << 4 * sw_ << "\" stroke-width=\"" << sw_ << "\"/>\n";
  }

  // The stock map under the disks, each disk, then each tool's path in execution order.
  void plunges() {
    if (plan_.stockMap) s_ << stockMapSvg(*plan_.stockMap, stockScale_);
    const char* fillOpacity = plan_.stockMap ? "0.06" : "0.22";  // the stock map shows through
    for (const Plunge& p : plan_.plunges) {
      const char* c = kPalette[colour_[p.toolId] % 8];
      s_ << "<circle cx=\"" << p.x << "\" cy=\"" << -p.y << "\" r=\"" << p.diameter / 2 << "\" fill=\"" << c
         << "\" fill-opacity=\"" << fillOpacity << "\" stroke=\"" << c << "\" stroke-width=\"" << sw_ << "\"/>\n";
    }
    // Each tool's path from faint (its first plunges) to strong (its last):
    // the order a limited tool grows its cut in, at a glance.
    for (const ToolCount& t : plan_.stats.perTool) {
      std::vector<const Plunge*> mine;
      for (const Plunge& p : plan_.plunges)
        if (p.toolId == t.toolId) mine.push_back(&p);
      const int parts = 8;
      for (int k = 0; k < parts && mine.size() > 1; ++k) {
        const size_t from = (mine.size() - 1) * k / parts, to = (mine.size() - 1) * (k + 1) / parts;
        if (to <= from) continue;
        s_ << "<polyline fill=\"none\" stroke=\"" << kPathPalette[colour_[t.toolId] % 8] << "\" stroke-width=\""
           << 1.5 * sw_ << "\" stroke-opacity=\"" << 0.25 + 0.75 * (k + 1) / parts << "\" points=\"";
        for (size_t i = from; i <= to; ++i) s_ << mine[i]->x << "," << -mine[i]->y << " ";
        s_ << "\"/>\n";
      }
    }
    // Start holes (black rings), starts into solid or onto a hole (black dots)
    // and lead-outs (black ticks from the plunge's centre).
    for (const Plunge& p : plan_.plunges) {
      if (p.startHole) {
        s_ << "<circle cx=\"" << p.x << "\" cy=\"" << -p.y << "\" r=\"" << p.diameter / 2
           << "\" fill=\"none\" stroke=\"#000\" stroke-width=\"" << 3 * sw_ << "\"/>\n";
      } else if (p.start) {
        s_ << "<circle cx=\"" << p.x << "\" cy=\"" << -p.y << "\" r=\"" << 0.15 * p.diameter << "\" fill=\"#000\"/>\n";
      }
      if (p.leadOut)
        s_ << "<line x1=\"" << p.x << "\" y1=\"" << -p.y << "\" x2=\"" << p.leadOut->x << "\" y2=\"" << -p.leadOut->y
           << "\" stroke=\"#000\" stroke-width=\"" << 2 * sw_ << "\"/>\n";
    }
  }

  // What is left uncovered (red), the necks of an automatic tool choice, and
  // over a sculptured floor a dot at each plunge, dark (deep) to light (high).
  void marks() {
    if (!plan_.uncovered.empty())
      s_ << "<path d=\"" << pathData(plan_.uncovered)
         << "\" fill=\"#e00000\" fill-rule=\"nonzero\" stroke=\"none\"/>\n";
    if (plan_.selection)
      for (const Neck& n : plan_.selection->necks)
        s_ << "<line x1=\"" << n.a.x << "\" y1=\"" << -n.a.y << "\" x2=\"" << n.b.x << "\" y2=\"" << -n.b.y
           << "\" stroke=\"#d000d0\" stroke-width=\"" << 3 * sw_ << "\" stroke-dasharray=\"" << 6 * sw_ << "\"/>\n";
    if (depthDots_)
      for (const Plunge& p : plan_.plunges)
        s_ << "<rect x=\"" << p.x - 0.12 * p.diameter << "\" y=\"" << -p.y - 0.12 * p.diameter << "\" width=\""
           << 0.24 * p.diameter << "\" height=\"" << 0.24 * p.diameter << "\" fill=\"" << depthColour(p.z)
           << "\"/>\n";
  }

  std::string depthColour(double z) const {
    const double t = (z - zLo_) / (zHi_ - zLo_);
    std::ostringstream c;
    c << "rgb(" << static_cast<int>(30 + 225 * t) << "," << static_cast<int>(20 + 200 * t) << ","
      << static_cast<int>(90 + 40 * (1 - t)) << ")";
    return c.str();
  }

  void text(double x, double y, const std::string& what) {
    s_ << "<text x=\"" << x << "\" y=\"" << y << "\" font-family=\"sans-serif\" font-size=\"" << fs_ << "\">" << what
       << "</text>\n";
  }

  std::string number(double v) const {
    std::ostringstream t;
    t << std::fixed << std::setprecision(2) << v;
    return t.str();
  }

  void swatch(double x, double y, const std::string& fill) {
    s_ << "<rect x=\"" << x << "\" y=\"" << y + 0.2 * fs_ << "\" width=\"" << fs_ << "\" height=\"" << 0.8 * fs_
       << "\" fill=\"" << fill << "\"/>";
  }

  // Counts, then a line per tool, the stock map's scale and the depth dots' scale.
  void legend() {
    double y = -hi_.y - legendH_ + fs_ * 0.5;
    s_ << std::setprecision(2);
    text(lo_.x, y + fs_,
         std::to_string(plan_.stats.plungeCount) + " plunges, " + number(100.0 * plan_.stats.coverage) +
             " % covered (red: left), travel " + number(plan_.stats.travelLength) + " mm");
    y += 1.4 * fs_;
    for (const ToolCount& t : plan_.stats.perTool) {
      const char* c = kPalette[colour_[t.toolId] % 8];
      s_ << "<circle cx=\"" << lo_.x + fs_ * 0.5 << "\" cy=\"" << y + fs_ * 0.6 << "\" r=\"" << fs_ * 0.45
         << "\" fill=\"" << c << "\" fill-opacity=\"0.5\" stroke=\"" << c << "\"  stroke-width=\"" << sw_ << "\"/>\n";
      text(lo_.x + fs_ * 1.4, y + fs_,
           "T" + std::to_string(t.toolId) + " D" + number(t.diameter) + ": " + std::to_string(t.count) + " plunges");
      y += 1.4 * fs_;
    }
    int starts = 0;
    for (const Plunge& p : plan_.plunges) starts += p.start && !p.startHole;
    text(lo_.x, y + fs_,
         "black: " + std::to_string(starts) + " starts (dots), " + std::to_string(plan_.stats.startHoles) +
             " start holes (rings), " + std::to_string(plan_.stats.leadOuts) + " lead-outs (ticks)");
    y += 1.4 * fs_;
    text(lo_.x, y + fs_, "each tool's path: faint (first plunges) to strong (last)");
    y += 1.4 * fs_;
    if (plan_.stockMap) {
      for (int k = 0; k <= 4; ++k) {
        swatch(lo_.x + k * fs_, y, stockColour(0.5 * k * stockScale_, stockScale_));
        s_ << "\n";
      }
      text(lo_.x + fs_ * 5.4, y + fs_,
           "floor stock, " + std::string(in_.maxFloorStock > 0.0 ? "limit " : "yellow ") + number(stockScale_) +
               ": max " + number(plan_.stats.maxFloorStockLeft) + " mm");
      y += 1.4 * fs_;
    }
    if (depthDots_) {
      swatch(lo_.x, y, depthColour(zLo_));
      swatch(lo_.x + fs_, y, depthColour(zHi_));
      s_ << "\n";
      text(lo_.x + fs_ * 2.4, y + fs_, "stop height " + number(zLo_) + " (dark) to " + number(zHi_) + " mm");
    }
  }

  const PlanInput& in_;
  const Plan& plan_;
  std::ostringstream s_;
  Vec2 lo_, hi_;
  double size_ = 0.0, sw_ = 0.0, fs_ = 0.0, legendH_ = 0.0, stockScale_ = 1.0;
  std::map<int, int> colour_;  // tool id -> palette slot
  double zLo_ = INFINITY, zHi_ = -INFINITY;
  bool depthDots_ = false;
};

}  // namespace

std::string planToSvg(const PlanInput& input, const Plan& plan) { return SvgPicture(input, plan).draw(); }

std::string planSummary(const Plan& plan) {
  const PlanStats& st = plan.stats;
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << st.plungeCount << " plunges (";
  for (size_t i = 0; i < st.perTool.size(); ++i)
    s << (i ? ", " : "") << "T" << st.perTool[i].toolId << " " << std::defaultfloat << std::setprecision(6)
      << st.perTool[i].diameter << std::fixed << std::setprecision(2) << " mm: " << st.perTool[i].count;
  s << "); stock left: walls up to " << st.maxWallStockLeft << " mm (" << 100 * st.coreCoverage
    << " % of the core cut), floor up to " << st.maxFloorStockLeft << " mm (mean " << st.meanFloorStock << " mm); "
    << std::setprecision(1) << st.volumeRemoved / 1000 << " cm3 removed, " << st.volumeLeft / 1000 << " cm3 left";
  if (st.restPlunges) s << "; " << st.restPlunges << " plunges added for the floor stock";
  if (st.startHoles) s << "; " << st.startHoles << " start holes";
  if (st.levels > 1) s << "; " << st.levels << " levels (flute length)";
  if (const int without = st.noLeadOutMaterial + st.noLeadOutWalls; st.leadOuts + without > 0) {
    s << "; lead-outs on " << st.leadOuts << " plunges";
    if (without)
      s << " (none on " << st.noLeadOutMaterial << " with material all round, " << st.noLeadOutWalls
        << " with no room at the walls)";
  }
  s << "; about " << st.estimatedMinutes << " min";
  if (st.minutesAtSafeHeight > st.estimatedMinutes + 0.05)
    s << " (" << st.minutesAtSafeHeight - st.estimatedMinutes << " min saved by stock-aware heights)";
  return s.str();
}

std::string planToGcode(const PlanInput& input, const Plan& plan) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(4);
  s << "(PlungeRough: " << plan.stats.plungeCount << " plunges, coverage " << std::setprecision(2)
    << 100.0 * plan.stats.coverage << " %)\n"
    << std::setprecision(4);
  s << "G21 G90 G17\n";
  std::map<int, double> feed;
  for (const Tool& t : input.autoTools ? input.library : input.tools) feed[t.id] = t.feed;
  int current = -1;
  for (const Plunge& p : plan.plunges) {
    if (p.toolId != current) {
      if (current >= 0) s << "M5\n";
      s << "G0 Z" << input.safeZ << "\n";
      s << "(T" << p.toolId << ": plunger diameter " << p.diameter << ")\n";
      s << "T" << p.toolId << " M6\n";
      s << "M3\n";
      s << "G0 Z" << input.safeZ << "\n";
      current = p.toolId;
    }
    if (p.startHole) s << "(start hole)\n";
    // Rapid over at the last retract height, down to the approach height, feed
    // through the material, lead out, rapid up only as high as the next move needs.
    s << "G0 X" << p.x << " Y" << p.y << "\n";
    s << "G0 Z" << p.approachZ << "\n";
    s << "G1 Z" << p.z << " F" << feed[p.toolId] << "\n";
    if (p.leadOut) s << "G1 X" << p.leadOut->x << " Y" << p.leadOut->y << "\n";
    s << "G0 Z" << p.retractZ << "\n";
  }
  if (current >= 0) s << "M5\n";
  s << "M30\n";
  return s.str();
}

}  // namespace plunge
