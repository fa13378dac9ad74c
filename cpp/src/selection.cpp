#include "plunge/selection.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include "plunge/covering.hpp"
#include "plunge/error.hpp"
#include "plunge/limits.hpp"
#include "plunge/plan.hpp"
#include "plunge/polygon.hpp"

namespace plunge {

double estimateMinutes(const Plan& plan, const std::vector<Tool>& tools, double safeZ, const TimeModel& m) {
  double minutes = 0.0;
  for (const Plunge& p : plan.plunges) {
    double feed = 200.0;
    for (const Tool& t : tools)
      if (t.id == p.toolId) feed = t.feed;
    const double depth = safeZ - p.z;
    minutes += depth / feed + depth / m.retractRate;
  }
  // perTool lists the tools that plunge: one change each.
  return minutes + plan.stats.travelLength / m.rapidRate + plan.stats.perTool.size() * m.toolChangeSeconds / 60.0;
}

namespace {

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d);
  return buf;
}

// The largest library diameter not above d (the thesis snaps down to a standard size).
double snapDown(const std::vector<Tool>& library, double d) {
  double best = 0.0;
  for (const Tool& t : library)
    if (t.diameter <= d + 1e-9 && t.diameter > best) best = t.diameter;
  return best;
}

std::string setName(const std::vector<double>& ds) {
  std::string s;
  for (double d : ds) s += (s.empty() ? "" : "/") + fmt("%g", d);
  return s;
}

}  // namespace

Plan planWithToolSelection(const PlanInput& input, const Progress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  PlanInput in = input;
  in.tools = in.library;
  validate(in);  // the library, largest first, and every other field
  const std::vector<Tool> library = in.tools;
  double tolerance = 0.0;  // large boundaries: the medial axis of simplified walls (limits.hpp)
  const Region region = planningRegion(in, tolerance);

  ToolSelection sel;
  const MedialAxis axis = medialAxis(region);
  sel.inscribed = largestInscribedCircle(axis);
  sel.necks = findNecks(region, axis, in.selection.riseFactor);
  sel.parts = subdivide(region, axis, sel.necks);
  sel.order = subRegionOrder(sel.parts, in.start ? *in.start : in.boundary.front());
  auto& why = sel.reasoning;
  why.push_back(fmt("largest inscribed circle: diameter %.2f at (%.2f, %.2f)", 2 * sel.inscribed.r,
                    sel.inscribed.c.x, sel.inscribed.c.y));
  for (size_t k = 0; k < sel.necks.size(); ++k) {
    const Neck& n = sel.necks[k];
    why.push_back(fmt("neck %g: width %.2f at (%.2f, %.2f)", k + 1.0, n.width, n.center.x, n.center.y) +
                  (n.island ? " (island neck)" : " (boundary neck)"));
  }

  // 5.1 candidates, snapped down to the library.
  const double smallest = library.back().diameter;
  std::vector<double> cand{smallest};
  auto add = [&](double d) {
    if (d > 0.0 && std::find(cand.begin(), cand.end(), d) == cand.end()) cand.push_back(d);
  };
  for (size_t i = 0; i < sel.parts.size(); ++i) {
    const SubRegion& s = sel.parts[i];
    const double want = 0.7 * 2 * s.inscribed.r - 2 * in.radialAllowance;
    const double largest = snapDown(library, want);
    std::string line = fmt("sub-region %g: area %.0f mm2, inscribed diameter %.2f; largest tool 0.7 x %.2f",
                           i + 1.0, s.area, 2 * s.inscribed.r, 2 * s.inscribed.r);
    line += largest > 0 ? fmt(" -> %g", largest) : std::string(" -> none in the library");
    add(largest);
    // Beyond the thesis: packing fills the gaps between large disks with mid-size
    // ones, so the size half-way (in scale) between the largest and the smallest
    // is a candidate too.
    if (largest > smallest) {
      const double mid = snapDown(library, std::sqrt(largest * smallest));
      if (mid > smallest && mid < largest) {
        line += fmt("; between %g and %g -> %g", largest, smallest, mid);
        add(mid);
      }
    }
    for (int k : s.necks) {
      const double neck = snapDown(library, sel.necks[k].width - 2 * in.radialAllowance);
      line += fmt("; neck %g tool -> %g", k + 1.0, neck);
      add(neck);
    }
    why.push_back(line);
  }
  std::sort(cand.begin(), cand.end(), std::greater<double>());
  sel.candidates = cand;
  why.push_back("candidates: " + setName(cand) + fmt(" (the smallest, %g, is in every set: it decides what must be reached)", smallest));

  // 5.4 branch and bound over subsets of the other candidates, largest first.
  std::vector<double> others(cand.begin(), cand.end() - 1);
  const Polygons acc = accessibleRegion(region, 0.5 * smallest, in.radialAllowance);
  const double accArea = poly::area(acc);
  double perPlungeLB = std::numeric_limits<double>::infinity();  // minutes
  const double zHigh = in.floor.kind == Floor::Kind::Flat ? in.floor.z + in.floorAllowance : in.topZ;
  for (const Tool& t : library)
    perPlungeLB = std::min(perPlungeLB, (in.safeZ - zHigh) * (1.0 / t.feed + 1.0 / in.timeModel.retractRate));
  auto toolOf = [&](double d) {
    for (const Tool& t : library)
      if (t.diameter == d) return t;
    return library.back();
  };
  const double wT = in.selection.weightTime, wN = in.selection.weightTools;
  double best = std::numeric_limits<double>::infinity();
  std::optional<Plan> bestPlan;
  std::vector<double> chosen;
  std::vector<double> included;
  int planned = 0;  // tool sets planned so far, for the progress
  std::function<void(size_t)> search = [&](size_t i) {
    // Bound: every set below this node has at least these tools, and no disk
    // larger than the largest still possible.
    const double rBig = 0.5 * (!included.empty() ? included.front() : (i < others.size() ? others[i] : smallest));
    const double nTools = included.size() + 1.0;
    const double lb = wT * (nTools * in.timeModel.toolChangeSeconds / 60.0 + accArea / (M_PI * rBig * rBig) * perPlungeLB) +
                      wN * nTools;
    if (lb >= best) {  // pruned: this set, and with every set adding smaller candidates when inside the tree
      ToolSetResult r;
      r.diameters = included;
      r.diameters.push_back(smallest);
      r.subtree = i < others.size();
      r.minutes = r.weighted = lb;
      sel.sets.push_back(r);
      return;
    }
    if (i == others.size()) {
      std::vector<double> set = included;
      set.push_back(smallest);
      ToolSetResult r;
      r.diameters = set;
      PlanInput sub = in;
      sub.autoTools = false;
      sub.tools.clear();
      for (double d : set) sub.tools.push_back(toolOf(d));
      // The k-th planned set takes its share of the progress (at most 2^n sets).
      const double share = 1.0 / std::ldexp(1.0, static_cast<int>(others.size()));
      Plan p = plan(sub, progress.sub(planned * share, (planned + 1) * share));
      ++planned;
      r.evaluated = true;
      r.plunges = p.stats.plungeCount;
      r.coverage = p.stats.coverage;
      r.minutes = p.stats.estimatedMinutes;
      r.weighted = wT * r.minutes + wN * set.size();
      sel.sets.push_back(r);
      if (r.weighted < best) {
        best = r.weighted;
        chosen = set;
        bestPlan = std::move(p);
      }
      return;
    }
    included.push_back(others[i]);
    search(i + 1);
    included.pop_back();
    search(i + 1);
  };
  search(0);
  if (!bestPlan) throw Error("tool selection: no tool set could be planned");

  int evaluated = 0;
  for (const ToolSetResult& r : sel.sets) evaluated += r.evaluated;
  why.push_back(fmt("branch and bound: %g of %g tool sets planned, the rest pruned by their lower bound",
                    evaluated, std::pow(2.0, static_cast<double>(others.size()))));
  for (const ToolSetResult& r : sel.sets)
    if (r.evaluated)
      why.push_back("  " + setName(r.diameters) + fmt(": %g plunges, coverage %.2f %%, %.1f min, weighted %.2f",
                                                       r.plunges, 100 * r.coverage, r.minutes, r.weighted));
  sel.chosen = chosen;
  why.push_back("chosen: " + setName(chosen) + fmt(" (weights: time %g, tools %g)", wT, wN));

  Plan out = std::move(*bestPlan);
  out.selection = std::move(sel);
  out.stats.planningSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace plunge
