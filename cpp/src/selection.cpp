#include "selection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <optional>

#include "detail.hpp"
#include "covering.hpp"
#include "plunge/error.hpp"
#include "limits.hpp"
#include "material.hpp"
#include "plunge/types.hpp"
#include "polygon.hpp"
#include "plunge/tools.hpp"

namespace plunge {

namespace {

std::string fmt(const char* f, double a, double b = 0, double c = 0, double d = 0, double e = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c, d, e);
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

// The thesis's rule for the largest tool of a sub-region (5.1): this fraction of
// its largest inscribed circle's diameter.
constexpr double kInscribedFraction = 0.7;
// The estimate's error on the pockets of the tests (flat and sculptured floors,
// limits): a set must beat the library as given by more to be chosen instead.
constexpr double kEstimateMargin = 0.015;

// The pocket's shape as the choice sees it: inscribed circle, necks, sub-regions
// and their order (5.5), each said in the reasoning.
ToolSelection describePocket(const PlanInput& in, const Region& region) {
  ToolSelection sel;
  const MedialAxis axis = medialAxis(region);
  sel.inscribed = largestInscribedCircle(axis);
  sel.necks = findNecks(region, axis, in.choice.weights.riseFactor);
  sel.parts = subdivide(region, axis, sel.necks);
  sel.order = subRegionOrder(sel.parts, in.motion.start ? *in.motion.start : in.boundary.front());
  sel.reasoning.push_back(fmt("largest inscribed circle: diameter %.2f at (%.2f, %.2f)", 2 * sel.inscribed.r,
                              sel.inscribed.c.x, sel.inscribed.c.y));
  for (size_t k = 0; k < sel.necks.size(); ++k) {
    const Neck& n = sel.necks[k];
    sel.reasoning.push_back(fmt("neck %g: width %.2f at (%.2f, %.2f)", k + 1.0, n.width, n.center.x, n.center.y) +
                            (n.island ? " (island neck)" : " (boundary neck)"));
  }
  return sel;
}

// The largest library tool that alone reaches what the library's smallest must
// cut: the core beyond the wall band (with a band), or all but 1 - min_coverage
// of the smallest's reach, on a flat floor. Below it no tool is needed for
// reach (a die's corner fillets wider than a plunger's radius let that plunger
// do it all).
double reachTool(const PlanInput& in, const Region& region) {
  const std::vector<Tool>& library = in.tools;
  // A sculptured floor (or a ball or bull cutter) needs the small tools in Z
  // too: its hollows keep what a large one leaves above max_floor_stock.
  const bool flat = in.floor.surface.kind == Floor::Kind::Flat &&
                    std::all_of(library.begin(), library.end(), [](const Tool& t) { return t.shape == CutterShape::Flat; });
  if (!flat) return library.back().diameter;
  const double rs = 0.5 * library.back().diameter;
  const Polygons reach = accessibleRegion(region, rs, in.radialAllowance);
  const Polygons must = in.covering.maxWallStock > 0.0 ? coreRegion(region, reach, in.radialAllowance, in.covering.maxWallStock) : reach;
  const double slack = in.covering.maxWallStock > 0.0 ? 1e-6 * poly::area(must) : (1.0 - in.covering.minCoverage) * poly::area(reach);
  for (const Tool& t : library) {
    if (t.diameter <= library.back().diameter) break;
    if (poly::area(poly::subtract(must, accessibleRegion(region, 0.5 * t.diameter, in.radialAllowance))) <= slack)
      return t.diameter;
  }
  return library.back().diameter;
}

// 5.1 candidates, snapped down to the library (in.tools, largest first), largest first.
std::vector<double> candidateTools(const PlanInput& in, const Region& region, ToolSelection& sel) {
  const std::vector<Tool>& library = in.tools;
  const double smallest = reachTool(in, region);
  std::vector<double> cand{smallest};
  auto add = [&](double d) {
    if (d > smallest && std::find(cand.begin(), cand.end(), d) == cand.end()) cand.push_back(d);
  };
  for (size_t i = 0; i < sel.parts.size(); ++i) {
    const SubRegion& s = sel.parts[i];
    const double want = kInscribedFraction * 2 * s.inscribed.r - 2 * in.radialAllowance;
    const double largest = snapDown(library, want);
    std::string line = fmt("sub-region %g: area %.0f mm2, inscribed diameter %.2f; largest tool %g x %.2f", i + 1.0,
                           s.area, 2 * s.inscribed.r, kInscribedFraction, 2 * s.inscribed.r);
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
    sel.reasoning.push_back(line);
  }
  std::sort(cand.begin(), cand.end(), std::greater<double>());
  sel.reasoning.push_back(
      "candidates: " + setName(cand) +
      (smallest == library.back().diameter
           ? fmt(" (the smallest, %g, is in every set: it decides what must be reached)", smallest)
           : fmt(" (%g reaches all that the library's smallest, %g, must cut: it is in every set, no smaller tool "
                 "is needed)",
                 smallest, library.back().diameter)));
  return cand;
}

// A plunge's stop (5.3): the highest floor under its centre and two rings,
// plus the allowance, held at the final depth (NaN where no floor is under it);
// and the share of those points where it leaves more than max_floor_stock
// (what the floor-stock step then plunges again, plan.cpp).
struct Stop {
  double z = 0.0;
  double floorStockShare = 0.0;
};

Stop stopOf(const PlanInput& in, const FloorSurface& floor, Vec2 c, double r) {
  Stop s{floor.height(c), 0.0};
  if (floor.isFlat()) {
    if (in.floor.finalDepth && !std::isnan(s.z)) s.z = std::max(s.z, *in.floor.finalDepth);
    s.z += in.floorAllowance;
    return s;
  }
  std::vector<double> h{s.z};
  for (double ring : {0.5, 0.95})
    for (int k = 0; k < 8; ++k) {
      const double a = kPi * (k + 0.5 * (ring < 0.9)) / 4;
      h.push_back(floor.height({c.x + ring * r * std::cos(a), c.y + ring * r * std::sin(a)}));
    }
  s.z = detail::kNaN;
  for (double v : h)
    if (!std::isnan(v) && !(v <= s.z)) s.z = v;
  if (std::isnan(s.z)) return s;
  if (in.floor.finalDepth) s.z = std::max(s.z, *in.floor.finalDepth);
  int overStock = 0, n = 0;  // samples where a floor-stock plunge would be needed
  for (double v : h)
    if (!std::isnan(v)) {
      ++n;
      overStock += s.z - v > in.floor.maxFloorStock && in.floor.maxFloorStock > 0.0;
    }
  s.floorStockShare = static_cast<double>(overStock) / n;
  s.z += in.floorAllowance;
  return s;
}

// Which of in.tools plunges a disk of radius r.
size_t toolOfRadius(const PlanInput& in, double r) {
  for (size_t k = 0; k < in.tools.size(); ++k)
    if (std::abs(0.5 * in.tools[k].diameter - r) <= 1e-9 * r) return k;
  throw InternalError("a placed disk of no tool's radius");
}

// Sum over each tool's positions of the distance to its nearest other position:
// the rapids of its tour, near enough for an estimate.
// (tool: each disk's index into in.tools)
std::vector<double> nearestNeighbourTravel(const PlanInput& in, const std::vector<CoverDisk>& disks,
                                           const std::vector<size_t>& tool) {
  std::vector<double> travel(in.tools.size(), 0.0);
  for (size_t t = 0; t < in.tools.size(); ++t) {
    std::vector<detail::PointValue> pts;
    for (size_t i = 0; i < disks.size(); ++i)
      if (tool[i] == t) pts.push_back({detail::toBPoint(disks[i].center), static_cast<int>(i)});
    if (pts.size() < 2) continue;
    const detail::RStarTree<detail::PointValue> tree(pts.begin(), pts.end());
    for (const detail::PointValue& p : pts)
      for (auto it = tree.qbegin(detail::bgi::nearest(p.first, 2)); it != tree.qend(); ++it)
        if (it->second != p.second) travel[t] += dist(disks[p.second].center, disks[it->second].center);
  }
  return travel;
}

}  // namespace

double estimateMinutes(const PlanInput& in, const std::vector<CoverDisk>& disks, const FloorSurface& floor) {
  const TimeModel& m = in.motion.timeModel;
  const double c = in.motion.stockAwareHeights ? std::max(0.0, std::min(in.motion.rapidClearance, in.safeZ - in.topZ))
                                        : std::max(0.0, in.safeZ - in.topZ);
  std::vector<size_t> tool;
  for (const CoverDisk& d : disks) tool.push_back(toolOfRadius(in, d.radius));
  const std::vector<double> travel = nearestNeighbourTravel(in, disks, tool);
  std::vector<double> perTool(in.tools.size(), 0.0);
  std::vector<bool> used(in.tools.size(), false);
  const Tool& smallest = in.tools.back();
  // Rest plunging: each plunge from the material left under it, none in air.
  const Material material(in.material, in.topZ);
  double restArea = 0.0;
  for (size_t i = 0; i < disks.size(); ++i) {
    const CoverDisk& d = disks[i];
    const size_t k = tool[i];
    const Tool& t = in.tools[k];
    const Stop stop = stopOf(in, floor, d.center, d.radius);
    if (material.known() && !material.cutsAny(d.center, cutterOf(t), stop.z)) continue;
    used[k] = true;
    const double depth = material.highest(d.center, d.radius) - stop.z;
    if (!(depth > 0.0)) continue;
    restArea += stop.floorStockShare * kPi * d.radius * d.radius;
    // Levels of the flute length (motion.hpp), each fed from the clearance over
    // its stock: depth + c per level in all. Level k rapids down through the k - 1
    // cut above it and retracts from its bottom: L (depth + c) at rapid in all.
    const double levels = t.fluteLength ? std::ceil(depth / *t.fluteLength - 1e-9) : 1.0;
    double minutes = (depth + levels * c) / t.feed + levels * (depth + c) / m.retractRate + in.motion.leadOut / t.feed;
    // Holes into solid deeper than a peck: up out of the hole and back per peck.
    const double pd = peckDepthOf(t), level = depth / levels;
    if (in.motion.peck && d.stage == Stage::Packing && level > pd) {
      const double n = std::ceil(level / pd - 1e-9) - 1.0;
      minutes += levels * ((pd * n * (n + 1) - n * in.motion.rapidClearance) / m.retractRate + in.motion.peckDwell / 60.0);
    }
    perTool[k] += minutes;
  }
  // The floor-stock step: the floor stock beyond the limit plunged again by the
  // smallest tool, in hexagonal cells, each a short plunge through max_floor_stock
  // plus the clearance, and its rapid to the next.
  if (restArea > 0.0) {
    const double r = 0.5 * smallest.diameter, n = restArea / (detail::kHexCellArea * r * r);
    const double path = 2 * in.floor.maxFloorStock + 2 * c;
    perTool.back() += n * (path / smallest.feed + path / m.retractRate + 2 * r / m.rapidRate);
    used.back() = true;
  }
  double total = 0.0;
  for (size_t t = 0; t < in.tools.size(); ++t) {
    if (!used[t]) continue;
    total += perTool[t] + travel[t] / m.rapidRate + m.toolChangeSeconds / 60.0;
  }
  return total;
}

namespace {

// 5.4 branch and bound over subsets of the candidates other than the smallest,
// largest first: each set below the bound is placed and estimated (5.3); then
// the set with the best estimate is planned in full.
class ToolSetSearch {
 public:
  ToolSetSearch(const PlanInput& in, const Region& region, ToolSelection& sel, const ToolSetStages& stages,
                const Progress& progress)
      : in_(in), sel_(sel), stages_(stages), progress_(progress), smallest_(sel.candidates.back()),
        others_(sel.candidates.begin(), sel.candidates.end() - 1),
        accArea_(poly::area(accessibleRegion(region, 0.5 * smallest_, in.radialAllowance))) {
    // The highest the floor (plus its allowance) can be, and the fastest feed.
    const double zHigh = in.floor.surface.kind == Floor::Kind::Flat ? in.floor.surface.z + in.floorAllowance : in.topZ;
    double feed = 0.0;
    for (const Tool& t : in.tools) feed = std::max(feed, t.feed);
    const double retract = in.motion.timeModel.retractRate;
    if (!in.motion.stockAwareHeights) {
      // Every plunge feeds down from safe_z and retracts back to it.
      perPlunge_ = std::max(0.0, in.safeZ - zHigh) * (1.0 / feed + 1.0 / retract);
    } else {
      // A plunge feeds from at least the clearance above its depth (or safe_z)
      // and retracts at least as high (motion.hpp); it feeds from at least the
      // top of the stock under it and removes at most its disk times that, so
      // all plunges feed at least the volume over the largest disk.
      const double c = std::max(0.0, std::min(in.safeZ - zHigh, in.motion.rapidClearance));
      perPlunge_ = c / retract;
      perPlungeFeed_ = c / feed;
      volume_ = in.covering.minCoverage * accArea_ * std::max(0.0, in.topZ - zHigh) / feed;
    }
  }

  // The best plan found; throws when none could be planned, with every set's reason.
  Plan run() {
    search(0);
    // The library as given is a set too: the choice is never a set the search
    // did not look at when the user's own tools would do better.
    for (const Tool& t : in_.tools) library_.push_back(t.diameter);
    if (std::none_of(sel_.sets.begin(), sel_.sets.end(),
                     [&](const ToolSetResult& r) { return r.diameters == library_; }))
      estimate(library_, lowerBound(library_));
    return planBest();
  }
  size_t setCount() const { return (size_t{1} << others_.size()) + 1; }

 private:
  void search(size_t i) {
    const double lb = lowerBound(i);
    if (lb >= best_) return prune(i, lb);
    if (i == others_.size()) return estimate(current(), lb);
    included_.push_back(others_[i]);
    search(i + 1);
    included_.pop_back();
    search(i + 1);
  }

  // Every set below this node has at least these tools, and no disk larger than
  // the largest still possible: a true lower bound on its time, whatever the
  // engagement limits (they only add plunges) and heights (see the constructor).
  double lowerBound(size_t i) const {
    const double big = !included_.empty() ? included_.front() : (i < others_.size() ? others_[i] : smallest_);
    return bound(big, included_.size() + 1.0);
  }
  double lowerBound(const std::vector<double>& set) const { return bound(set.front(), set.size()); }
  double bound(double diameter, double nTools) const {
    const TimeModel& m = in_.motion.timeModel;
    // After earlier operations the area and volume left are not the pocket's:
    // only the tool changes bound the time (every set is estimated).
    if (in_.material) return weighted(nTools * m.toolChangeSeconds / 60.0, nTools);
    const double rBig = 0.5 * diameter;
    const double disk = kPi * rBig * rBig, plunges = in_.covering.minCoverage * accArea_ / disk;
    const double moves = plunges * perPlunge_ + std::max(plunges * perPlungeFeed_, volume_ / disk);
    return weighted(nTools * m.toolChangeSeconds / 60.0 + moves, nTools);
  }
  double weighted(double minutes, double nTools) const {
    return in_.choice.weights.weightTime * minutes + in_.choice.weights.weightTools * nTools;
  }

  // Pruned: this set, and with every set adding smaller candidates when inside the tree.
  void prune(size_t i, double lb) {
    ToolSetResult r;
    r.diameters = current();
    r.subtree = i < others_.size();
    r.minutes = r.weighted = r.bound = lb;
    sel_.sets.push_back(r);
  }

  PlanInput inputOf(const std::vector<double>& diameters) const {
    PlanInput sub = in_;
    sub.choice.automatic = false;
    sub.tools.clear();
    for (double d : diameters) sub.tools.push_back(toolOf(d));
    return sub;
  }

  // 5.3: the set's positions placed and timed. A set this job cannot plan (say a
  // plunge mill without a drill as wide as its core) is kept with its reason;
  // only "no set" is an error.
  void estimate(const std::vector<double>& diameters, double lb) {
    ToolSetResult r;
    r.diameters = diameters;
    r.bound = lb;
    r.minutes = r.weighted = lb;
    try {
      PlanInput sub = inputOf(diameters);
      // The placements share the first fifth of the progress, the full plan the rest.
      const double share = 0.2 / static_cast<double>(setCount());
      CoverResult cover = stages_.place(sub, progress_.sub(placed_ * share, (placed_ + 1) * share));
      ++placed_;
      r.minutes = estimateMinutes(sub, cover.disks, *stages_.floor);
      r.plunges = static_cast<int>(cover.disks.size());
      placements_[sel_.sets.size()] = std::move(cover);
      r.weighted = weighted(r.minutes, diameters.size());
      best_ = std::min(best_, r.weighted);
    } catch (const Error& e) {
      r.refused = e.what();
    }
    sel_.sets.push_back(r);
  }

  // The sets by estimate, the best planned in full (the next when it cannot be).
  Plan planBest() {
    std::vector<size_t> order;
    for (size_t k = 0; k < sel_.sets.size(); ++k)
      if (sel_.sets[k].refused.empty() && sel_.sets[k].plunges > 0) order.push_back(k);
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return sel_.sets[a].weighted < sel_.sets[b].weighted; });
    // The library as given stays first unless another set's estimate beats it
    // by more than the estimate can tell apart.
    for (size_t k = 0; k < order.size(); ++k)
      if (sel_.sets[order[k]].diameters == library_ &&
          sel_.sets[order[k]].weighted <= sel_.sets[order.front()].weighted * (1.0 + kEstimateMargin))
        std::rotate(order.begin(), order.begin() + k, order.begin() + k + 1);
    for (size_t k : order) {
      try {
        Plan p = planSet(k, progress_.sub(0.2, 0.8));
        // Holders: the estimates cannot see where a holder stops a plunger
        // (that needs the posted order). Where the best set's plan leaves the
        // floor to one, the library as given (a slim plunger held far out
        // among it) is planned too, and kept when fewer places are left.
        const int held = heldPlaces(p);
        const auto lib = std::find_if(order.begin(), order.end(),
                                      [&](size_t j) { return sel_.sets[j].diameters == library_; });
        if (held > 0 && lib != order.end() && *lib != k) {
          try {
            Plan q = planSet(*lib, progress_.sub(0.8, 1.0));
            if (heldPlaces(q) < held) p = std::move(q);
          } catch (const Error& e) {
            sel_.sets[*lib].refused = e.what();
          }
        }
        // The tools the plan uses (a tool may fit nowhere or find nothing to cut).
        sel_.chosen.clear();
        for (const ToolCount& c : p.stats.perTool) sel_.chosen.push_back(c.diameter);
        return p;
      } catch (const Error& e) {
        sel_.sets[k].refused = e.what();
      }
    }
    std::string why;
    for (const ToolSetResult& r : sel_.sets)
      if (!r.refused.empty()) why += "; " + setName(r.diameters) + ": " + r.refused;
    throw Error("tool selection: no tool set could be planned" + why);
  }

  // Set k planned in full, its estimate replaced by the plan's own minutes.
  Plan planSet(size_t k, const Progress& progress) {
    ToolSetResult& r = sel_.sets[k];
    Plan p = stages_.plan(inputOf(r.diameters), std::move(placements_[k]), progress);
    r.evaluated = true;
    r.estimate = r.minutes;
    r.plunges = p.stats.plungeCount;
    r.coverage = p.stats.coverage;
    r.minutes = p.stats.estimatedMinutes;
    r.weighted = weighted(r.minutes, r.diameters.size());
    return p;
  }

  // The places a plan's holders leave above their depth (BrokenLimit "stick_out").
  static int heldPlaces(const Plan& p) {
    int n = 0;
    for (const BrokenLimit& b : p.broken)
      if (b.limit == "stick_out") n += b.count;
    return n;
  }

  std::vector<double> current() const {
    std::vector<double> set = included_;
    set.push_back(smallest_);
    return set;
  }

  const Tool& toolOf(double d) const {
    for (const Tool& t : in_.tools)
      if (t.diameter == d) return t;
    throw InternalError("a candidate diameter that is not in the library");
  }

  const PlanInput& in_;
  ToolSelection& sel_;
  const ToolSetStages& stages_;
  const Progress& progress_;
  const double smallest_;
  const std::vector<double> others_;
  const double accArea_;
  // Minutes: per plunge (retract, or both ways at safe_z), per plunge fed, and
  // the volume to feed through times the largest disk.
  double perPlunge_ = 0.0, perPlungeFeed_ = 0.0, volume_ = 0.0;
  double best_ = std::numeric_limits<double>::infinity();  // the best estimate so far
  std::vector<double> included_;
  std::vector<double> library_;  // the library as given, largest first
  std::map<size_t, CoverResult> placements_;  // of each estimated set (index into sel_.sets)
  int placed_ = 0;  // sets placed so far, for the progress
};

// The search's outcome in the reasoning: every estimated set and the choice.
void reportSearch(const PlanInput& in, ToolSelection& sel, size_t setCount) {
  int estimated = 0, refused = 0;
  for (const ToolSetResult& r : sel.sets) {
    estimated += r.plunges > 0 || r.evaluated;
    refused += !r.refused.empty();
  }
  sel.reasoning.push_back(fmt("branch and bound: %g of %g tool sets placed and estimated, %g cannot be, the rest "
                              "pruned by their lower bound; the best estimate planned in full",
                              estimated, static_cast<double>(setCount), refused));
  for (const ToolSetResult& r : sel.sets)
    if (r.evaluated)
      sel.reasoning.push_back("  " + setName(r.diameters) +
                              fmt(": estimated %.1f min; planned: %g plunges, coverage %.2f %%, %.1f min, weighted %.2f",
                                  r.estimate, r.plunges, 100 * r.coverage, r.minutes, r.weighted));
    else if (!r.refused.empty())
      sel.reasoning.push_back("  " + setName(r.diameters) + ": cannot be planned: " + r.refused);
    else if (r.plunges > 0)
      sel.reasoning.push_back("  " + setName(r.diameters) +
                              fmt(": %g positions, estimated %.1f min, weighted %.2f", r.plunges, r.minutes, r.weighted));
  sel.reasoning.push_back("chosen: " + setName(sel.chosen) +
                          fmt(" (weights: time %g, tools %g)", in.choice.weights.weightTime, in.choice.weights.weightTools));
}

}  // namespace

Plan planWithToolSelection(const PlanInput& in, const ToolSetStages& stages, const Progress& progress) {
  // Large boundaries: the medial axis of simplified walls (limits.hpp).
  const Region region = planningRegion(in).region;
  ToolSelection sel = describePocket(in, region);
  sel.candidates = candidateTools(in, region, sel);
  ToolSetSearch search(in, region, sel, stages, progress);
  Plan out = search.run();
  reportSearch(in, sel, search.setCount());
  out.selection = std::move(sel);
  return out;
}

}  // namespace plunge
