#include "plunge/selection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>

#include "plunge/covering.hpp"
#include "plunge/error.hpp"
#include "plunge/limits.hpp"
#include "plunge/types.hpp"
#include "plunge/polygon.hpp"

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

// The pocket's shape as the choice sees it: inscribed circle, necks, sub-regions
// and their order (5.5), each said in the reasoning.
ToolSelection describePocket(const PlanInput& in, const Region& region) {
  ToolSelection sel;
  const MedialAxis axis = medialAxis(region);
  sel.inscribed = largestInscribedCircle(axis);
  sel.necks = findNecks(region, axis, in.selection.riseFactor);
  sel.parts = subdivide(region, axis, sel.necks);
  sel.order = subRegionOrder(sel.parts, in.start ? *in.start : in.boundary.front());
  sel.reasoning.push_back(fmt("largest inscribed circle: diameter %.2f at (%.2f, %.2f)", 2 * sel.inscribed.r,
                              sel.inscribed.c.x, sel.inscribed.c.y));
  for (size_t k = 0; k < sel.necks.size(); ++k) {
    const Neck& n = sel.necks[k];
    sel.reasoning.push_back(fmt("neck %g: width %.2f at (%.2f, %.2f)", k + 1.0, n.width, n.center.x, n.center.y) +
                            (n.island ? " (island neck)" : " (boundary neck)"));
  }
  return sel;
}

// 5.1 candidates, snapped down to the library (in.tools, largest first), largest first.
std::vector<double> candidateTools(const PlanInput& in, ToolSelection& sel) {
  const std::vector<Tool>& library = in.tools;
  const double smallest = library.back().diameter;
  std::vector<double> cand{smallest};
  auto add = [&](double d) {
    if (d > 0.0 && std::find(cand.begin(), cand.end(), d) == cand.end()) cand.push_back(d);
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
  sel.reasoning.push_back("candidates: " + setName(cand) +
                          fmt(" (the smallest, %g, is in every set: it decides what must be reached)", smallest));
  return cand;
}

// 5.4 branch and bound over subsets of the candidates other than the smallest,
// largest first; each set below the bound is planned with planSet.
class ToolSetSearch {
 public:
  ToolSetSearch(const PlanInput& in, const Region& region, ToolSelection& sel, const ToolSetPlanner& planSet,
                const Progress& progress)
      : in_(in), sel_(sel), planSet_(planSet), progress_(progress), smallest_(sel.candidates.back()),
        others_(sel.candidates.begin(), sel.candidates.end() - 1),
        accArea_(poly::area(accessibleRegion(region, 0.5 * smallest_, in.radialAllowance))) {
    // The highest the floor (plus its allowance) can be, and the fastest feed.
    const double zHigh = in.floor.kind == Floor::Kind::Flat ? in.floor.z + in.floorAllowance : in.topZ;
    double feed = 0.0;
    for (const Tool& t : in.tools) feed = std::max(feed, t.feed);
    const double retract = in.timeModel.retractRate;
    if (!in.stockAwareHeights) {
      // Every plunge feeds down from safe_z and retracts back to it.
      perPlunge_ = std::max(0.0, in.safeZ - zHigh) * (1.0 / feed + 1.0 / retract);
    } else {
      // A plunge feeds from at least the clearance above its depth (or safe_z)
      // and retracts at least as high (motion.hpp); it feeds from at least the
      // top of the stock under it and removes at most its disk times that, so
      // all plunges feed at least the volume over the largest disk.
      const double c = std::max(0.0, std::min(in.safeZ - zHigh, in.rapidClearance));
      perPlunge_ = c / retract;
      perPlungeFeed_ = c / feed;
      volume_ = in.minCoverage * accArea_ * std::max(0.0, in.topZ - zHigh) / feed;
    }
  }

  // The best plan found; throws when none could be planned, with every set's reason.
  Plan run() {
    search(0);
    if (!bestPlan_) {
      std::string why;
      for (const ToolSetResult& r : sel_.sets)
        if (!r.refused.empty()) why += "; " + setName(r.diameters) + ": " + r.refused;
      throw Error("tool selection: no tool set could be planned" + why);
    }
    return std::move(*bestPlan_);
  }
  size_t setCount() const { return size_t{1} << others_.size(); }

 private:
  void search(size_t i) {
    const double lb = lowerBound(i);
    if (lb >= best_) return prune(i, lb);
    if (i == others_.size()) return evaluate(lb);
    included_.push_back(others_[i]);
    search(i + 1);
    included_.pop_back();
    search(i + 1);
  }

  // Every set below this node has at least these tools, and no disk larger than
  // the largest still possible: a true lower bound on its time, whatever the
  // engagement limits (they only add plunges) and heights (see the constructor).
  double lowerBound(size_t i) const {
    const double rBig =
        0.5 * (!included_.empty() ? included_.front() : (i < others_.size() ? others_[i] : smallest_));
    const double nTools = included_.size() + 1.0;
    const TimeModel& m = in_.timeModel;
    const double disk = kPi * rBig * rBig, plunges = in_.minCoverage * accArea_ / disk;
    const double moves = plunges * perPlunge_ + std::max(plunges * perPlungeFeed_, volume_ / disk);
    return in_.selection.weightTime * (nTools * m.toolChangeSeconds / 60.0 + moves) +
           in_.selection.weightTools * nTools;
  }

  // Pruned: this set, and with every set adding smaller candidates when inside the tree.
  void prune(size_t i, double lb) {
    ToolSetResult r;
    r.diameters = current();
    r.subtree = i < others_.size();
    r.minutes = r.weighted = r.bound = lb;
    sel_.sets.push_back(r);
  }

  void evaluate(double lb) {
    ToolSetResult r;
    r.diameters = current();
    r.bound = lb;
    PlanInput sub = in_;
    sub.autoTools = false;
    sub.tools.clear();
    for (double d : r.diameters) sub.tools.push_back(toolOf(d));
    // The k-th planned set takes its share of the progress (at most 2^n sets).
    const double share = 1.0 / static_cast<double>(setCount());
    std::optional<Plan> planned;
    try {
      planned = planSet_(sub, progress_.sub(planned_ * share, (planned_ + 1) * share));
    } catch (const Error& e) {
      // A set this job cannot plan (say a plunge mill without a drill as wide
      // as its core) is skipped with its reason; only "no set" is an error.
      ++planned_;
      r.refused = e.what();
      r.minutes = r.weighted = lb;
      sel_.sets.push_back(r);
      return;
    }
    Plan& p = *planned;
    ++planned_;
    r.evaluated = true;
    r.plunges = p.stats.plungeCount;
    r.coverage = p.stats.coverage;
    r.minutes = p.stats.estimatedMinutes;
    r.weighted = in_.selection.weightTime * r.minutes + in_.selection.weightTools * r.diameters.size();
    sel_.sets.push_back(r);
    if (r.weighted < best_) {
      best_ = r.weighted;
      sel_.chosen = r.diameters;
      bestPlan_ = std::move(p);
    }
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
  const ToolSetPlanner& planSet_;
  const Progress& progress_;
  const double smallest_;
  const std::vector<double> others_;
  const double accArea_;
  // Minutes: per plunge (retract, or both ways at safe_z), per plunge fed, and
  // the volume to feed through times the largest disk.
  double perPlunge_ = 0.0, perPlungeFeed_ = 0.0, volume_ = 0.0;
  double best_ = std::numeric_limits<double>::infinity();
  std::optional<Plan> bestPlan_;
  std::vector<double> included_;
  int planned_ = 0;  // tool sets planned so far, for the progress
};

// The search's outcome in the reasoning: every planned set and the choice.
void reportSearch(const PlanInput& in, ToolSelection& sel, size_t setCount) {
  int evaluated = 0, refused = 0;
  for (const ToolSetResult& r : sel.sets) {
    evaluated += r.evaluated;
    refused += !r.refused.empty();
  }
  sel.reasoning.push_back(fmt("branch and bound: %g of %g tool sets planned, %g cannot be, the rest pruned by their "
                              "lower bound",
                              evaluated, static_cast<double>(setCount), refused));
  for (const ToolSetResult& r : sel.sets)
    if (r.evaluated)
      sel.reasoning.push_back("  " + setName(r.diameters) +
                              fmt(": %g plunges, coverage %.2f %%, %.1f min, weighted %.2f", r.plunges,
                                  100 * r.coverage, r.minutes, r.weighted));
    else if (!r.refused.empty())
      sel.reasoning.push_back("  " + setName(r.diameters) + ": cannot be planned: " + r.refused);
  sel.reasoning.push_back("chosen: " + setName(sel.chosen) +
                          fmt(" (weights: time %g, tools %g)", in.selection.weightTime, in.selection.weightTools));
}

}  // namespace

Plan planWithToolSelection(const PlanInput& in, const ToolSetPlanner& planSet, const Progress& progress) {
  double tolerance = 0.0;  // large boundaries: the medial axis of simplified walls (limits.hpp)
  const Region region = planningRegion(in, tolerance);
  ToolSelection sel = describePocket(in, region);
  sel.candidates = candidateTools(in, sel);
  ToolSetSearch search(in, region, sel, planSet, progress);
  Plan out = search.run();
  reportSearch(in, sel, search.setCount());
  out.selection = std::move(sel);
  return out;
}

}  // namespace plunge
