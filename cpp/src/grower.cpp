#include "grower.hpp"

#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <memory>

#include "covering.hpp"
#include "growth_paths.hpp"
#include "polygon.hpp"
#include "plunge/sequencing.hpp"

namespace plunge {

namespace {

// Centres this much farther from the allowed region than the radius: the
// offset's arcs are chords whose midpoints lie up to kArcTolerance inside, and
// a plunge there must still fit (Region::diskFits); and a lead-out along a
// wall that bulges in (a chord to the plunge before) keeps the allowance.
constexpr double kCentreMargin = 0.05;
// The floor stock a limited tool leaves to the finishing pass, as a share of
// max_floor_stock (the raster's heights and the stock samples' differ a little).
constexpr double kFloorBand = 0.9;
// Rings (the fallback after the paths): a ring lies this share of the band
// inside what is cut, and its plunges a chord of that band apart times
// kRingChord, so that every plunge measures a little under the band.
constexpr double kRingBand = 0.98;
constexpr double kRingChord = 0.9;
// A plunge is worth making when it cuts this share of its disk's raster cells,
// and at least kMinGainCells of them (fewer is the raster's noise).
constexpr double kMinGainShare = 0.003;
constexpr int kMinGainCells = 3;
// Rounds of rings that cut nothing before a tool gives up on its targets.
constexpr int kStallRounds = 3;

}  // namespace

void Grower::add(const Plunge& p) {
  order_.push_back(p);
  stock_.cut({p.x, p.y}, cutterOf(toolOf(p.toolId)), p.z);
  cuts_.add({p.x, p.y}, cutterOf(toolOf(p.toolId)), p.z);
  newDisks_.push_back({{p.x, p.y}, 0.5 * p.diameter});
}

void Grower::settle() {
  if (newDisks_.empty()) return;
  cleared_ = poly::unite(cleared_, poly::unionOfDisks(newDisks_, 0.01));
  newDisks_.clear();
}

// The tip height of a plunge at c (its gouge-free depth, 4.4), or nothing above top_z.
std::optional<double> Grower::stopAt(Vec2 c, const Tool& t) const {
  const double z = depths_.plungeHeight(c, cutterOf(t), in_.floorAllowance, in_.radialAllowance);
  if (z >= in_.material.topZ()) return std::nullopt;
  return z;
}

// Grows the tool's cut over its targets along the pattern asked for; with
// Auto twice, along rows and along offsets of the contour, keeping the one
// with fewer plunges, a start into solid counted twice (it drills the whole
// disk and cannot lead out), rows on a tie. Rows suit long straight
// pockets, offsets rings and narrow necks. The two run at once, one per
// core, the second on its own copies of the stock and of the floor (whose
// evaluation is not thread-safe, floor.hpp).
void Grower::grow(const Tool& tool, const std::vector<Plunge>& planned) {
  if (in_.pattern != GrowthPattern::Auto) return grow(tool, planned, in_.pattern);
  settle();
  const size_t begin = order_.size();
  HeightField otherStock = stock_;
  const std::unique_ptr<FloorSurface> otherFloor = depths_.floor().clone();
  const DepthSolver otherDepths(*otherFloor, depths_);
  Grower other(in_, region_, otherDepths, otherStock);
  other.cleared_ = cleared_;
  other.order_ = order_;
  other.holes_ = holes_;
  other.cuts_ = cuts_;
  std::future<void> trial =
      std::async(std::launch::async, [&] { other.grow(tool, planned, GrowthPattern::Offsets); });
  grow(tool, planned, GrowthPattern::Rows);
  progress_.await(trial);
  auto cost = [begin](const Grower& g) {
    size_t n = g.order_.size() + g.holes_.size();
    for (size_t k = begin; k < g.order_.size(); ++k) n += g.order_[k].start;
    return n;
  };
  if (cost(other) < cost(*this)) adopt(other, otherStock);
}

// Takes the other trial's growth as this one's.
void Grower::adopt(Grower& other, HeightField& otherStock) {
  stock_ = std::move(otherStock);
  cleared_ = std::move(other.cleared_);
  newDisks_ = std::move(other.newDisks_);
  order_ = std::move(other.order_);
  holes_ = std::move(other.holes_);
  cuts_ = std::move(other.cuts_);
}

// Grows the tool's cut over its targets (the plunges the plan gave it): along
// the paths, then ring by ring, then the slivers the raster cannot see.
void Grower::grow(const Tool& tool, const std::vector<Plunge>& planned, GrowthPattern pattern) {
  settle();
  const size_t begin = order_.size();
  const Cutter cutter = cutterOf(tool);
  const double r = cutter.radius, h = stock_.spacing();
  Targets targets(planned, cutter, stock_, progress_);
  keepFloorStock(targets);
  for (const Plunge& p : planned) targets.update({p.x, p.y}, r, stock_);
  forgetWallBand(targets);
  const Polygons centres = poly::offset(allowedRegion(region_, in_.radialAllowance), -(r + kCentreMargin));
  const int minGain = std::max(kMinGainCells, static_cast<int>(kMinGainShare * kPi * r * r / (h * h)));
  const Vec2 at = order_.empty() ? (in_.start ? *in_.start : region_.loops()[0].front())
                                 : Vec2{order_.back().x, order_.back().y};
  ToolRun run{tool, cutter, std::min(engagementLimit(tool), 2 * r), coreRadius(tool), planned, targets, minGain, at};
  growAlongPaths(run, centres, pattern);
  growInRings(run, centres);
  finishSlivers(run);
  shortenTour(begin);
}

// Material in the wall band is the walls' stock (kept within max_wall_stock
// by the contour's spacing), not a target: chasing the scallops the planned
// disks would have left elsewhere costs plunges and leaves no less stock.
void Grower::forgetWallBand(Targets& targets) {
  if (!(in_.maxWallStock > 0)) return;
  const double band = in_.radialAllowance + kWallBand * in_.maxWallStock;
  targets.forget([&](Vec2 q) {
    progress_.tick();
    return region_.wallDistance(q, band + 1.0) < band;
  });
}

// What the paths missed, ring by ring: a ring lies inside what is cut by a
// little under the band; where a ring cuts nothing, the planned plunges that
// keep the limits, else a start.
void Grower::growInRings(ToolRun& run, const Polygons& centres) {
  const double r = run.cutter.radius, depthIn = r - kRingBand * run.limit;
  // Along a ring, plunges a chord of the band apart: the next ring's offset
  // follows the scallops they leave.
  const double step = std::clamp(kRingChord * std::sqrt(std::max(0.0, r * r - depthIn * depthIn)),
                                 std::max(run.tool.minEngagement.value_or(0.0), 2 * stock_.spacing()), r);
  std::vector<bool> triedStart(run.planned.size(), false);
  int stalls = 0;  // rounds that cut no target point (a guard: each round should)
  while (run.targets.left() > 0 && stalls < kStallRounds) {
    progress_.tick();
    const size_t before = run.targets.left();
    const Polygons ring = poly::intersect(poly::offset(cleared_, -depthIn, 0.01), centres);
    int accepted = ringRound(run, walk(ring, run.at, step));
    if (accepted == 0) accepted = finishPlanned(run);
    if (accepted == 0 && !startAt(run, triedStart)) break;
    settle();
    stalls = run.targets.left() < before ? 0 : stalls + 1;
  }
}

// A ring plunge at c, or none where it would cut too little, not fit, cut
// over the limit or over its core. Cheap tests first: a stop height costs an
// optimization on sculptured floors.
std::optional<Grower::RingPlunge> Grower::ringPlunge(ToolRun& run, Vec2 c) {
  const double r = run.cutter.radius;
  if (run.targets.open(c, r) < run.minGain || !region_.diskFits(c, r + in_.radialAllowance)) return std::nullopt;
  const std::optional<double> z = stopAt(c, run.tool);
  if (!z) return std::nullopt;
  if (run.targets.gain(c, run.cutter, *z, stock_) < run.minGain) {
    run.targets.defer(c, run.cutter, *z, stock_);
    return std::nullopt;
  }
  if (!stock_.contact(c, run.cutter, *z, run.coreR).coreClear) return std::nullopt;
  const double engaged = cuts_.engagement(c, run.cutter, *z, run.limit + kExactSlack);
  if (engaged > run.limit + kExactSlack) return std::nullopt;
  return RingPlunge{*z, engaged < run.tool.minEngagement.value_or(0.0)};
}

// The plunges of one ring; returns how many were made.
int Grower::ringRound(ToolRun& run, const std::vector<Vec2>& positions) {
  int accepted = 0;
  std::vector<std::pair<Vec2, double>> thin;
  for (const Vec2 c : positions) {
    const std::optional<RingPlunge> p = ringPlunge(run, c);
    if (!p) continue;
    if (p->thin) {
      thin.push_back({c, p->z});
      continue;
    }
    place(run, c, p->z, false);
    ++accepted;
  }
  // Where only thin cuts are left, make them (measured and reported).
  if (accepted == 0)
    for (const auto& [c, z] : thin)
      if (run.targets.gain(c, run.cutter, z, stock_) >= run.minGain &&
          stock_.contact(c, run.cutter, z, run.coreR).coreClear) {
        place(run, c, z, false);
        ++accepted;
      }
  return accepted;
}

// The tour within the order the growth allows: a plunge measured against
// the stock the plunges before it left meets the same stock in any order
// that keeps it after every plunge whose disk reaches its own (the raster's
// cells, a margin of two, included), so depths, engagement, cores and starts
// stay as measured while the tour shortens (sequencing.hpp).
void Grower::shortenTour(size_t begin) {
  if (order_.size() - begin < 3) return;
  std::vector<Vec2> at;
  for (size_t k = begin; k < order_.size(); ++k) at.push_back({order_[k].x, order_[k].y});
  const double reach = order_[begin].diameter + 2 * stock_.spacing() + 0.01;
  const std::vector<int> order = shortenKeepingOrder(
      at, [&](int a, int b) { return dist(at[a], at[b]) < reach; }, [this] { progress_.tick(); });
  const std::vector<Plunge> was(order_.begin() + static_cast<long>(begin), order_.end());
  for (size_t k = 0; k < order.size(); ++k) order_[begin + k] = was[order[k]];
}

// Over a sculptured floor the growth's plunges stop at their own heights,
// a little above the planned ones in places. What they leave within the
// floor stock limit (max_floor_stock, kFloorBand of it) is the floor's
// stock, as in the floor-stock step (stock.hpp), not a target: a plunge for it
// would cut a sliver of a few tenths (the planned floor-stock plunges, where it is
// thicker, stay targets). A target point is done as soon as it is cut that
// low, so a path position that would only deepen such points is not made.
void Grower::keepFloorStock(Targets& targets) const {
  if (!(in_.maxFloorStock > 0) || !sculptured()) return;
  const FloorSurface& floor = depths_.floor();
  const double keep = in_.floorAllowance + kFloorBand * in_.maxFloorStock;
  targets.keepAbove([&](Vec2 q) {
    const double f = floor.height(q);
    return std::isfinite(f) ? f + keep : -std::numeric_limits<double>::infinity();
  });
}

bool Grower::sculptured() const {
  return !depths_.floor().isFlat() || std::any_of(in_.tools.all().begin(), in_.tools.all().end(),
                                                  [](const Tool& t) { return t.shape != CutterShape::Flat; });
}

// Can the tool start at c: a plunge into solid (centre-cutting) or onto a
// hole its start-hole tool can drill there.
bool Grower::canStart(const Tool& tool, Vec2 c) const {
  if (tool.centerCutting) return true;
  const Tool& drill = in_.tools.startHoleFor(tool);
  return stopAt(c, drill) && region_.diskFits(c, 0.5 * drill.diameter + in_.radialAllowance);
}

void Grower::drillStart(const Tool& tool, Vec2 c) {
  if (tool.centerCutting) return;
  const Tool& drill = in_.tools.startHoleFor(tool);
  drillHole(drill, c, *stopAt(c, drill));
}

// A start hole at c, its tip at z (it comes before every plunge).
void Grower::drillHole(const Tool& drill, Vec2 c, double z) {
  Plunge hole = plungeOf(drill, c, z);
  hole.startHole = hole.start = true;
  holes_.push_back(hole);
  stock_.cut(c, cutterOf(drill), hole.z);
  cuts_.add(c, cutterOf(drill), hole.z);
}

// Pieces of the tool's planned cut narrower than the stock's cells, which the
// raster cannot see, measured exactly (polygons): for each, the planned
// plunge that covers most of it.
std::vector<size_t> Grower::sliverPlunges(const ToolRun& run) {
  const double r = run.cutter.radius;
  std::vector<Circle> want;
  for (const Plunge& p : run.planned) want.push_back({{p.x, p.y}, r});
  Polygons left = poly::subtract(poly::unionOfDisks(want), cleared_);
  if (in_.maxWallStock > 0)  // beyond the wall band, as the targets
    left = poly::intersect(left,
                           poly::offset(allowedRegion(region_, in_.radialAllowance), -kWallBand * in_.maxWallStock));
  std::vector<size_t> chosen;
  for (const Polygons& piece : poly::components(left)) {
    progress_.tick();
    if (poly::area(piece) < 0.01) continue;
    int best = -1;
    size_t inside = 0;
    for (size_t k = 0; k < run.planned.size(); ++k) {
      size_t n = 0;
      for (Vec2 v : piece.front()) n += dist(v, want[k].c) <= r + 1e-6;
      if (n > inside) {
        inside = n;
        best = static_cast<int>(k);
      }
    }
    if (best >= 0) chosen.push_back(static_cast<size_t>(best));
  }
  return chosen;
}

// The slivers (sliverPlunges), each cut by its planned plunge where that
// keeps the limits.
void Grower::finishSlivers(ToolRun& run) {
  settle();
  std::vector<size_t> chosen = sliverPlunges(run);
  const double e = run.limit + kExactSlack;
  placeNearestFirst(run, std::move(chosen), [&](const Plunge& s) {
    return stock_.contact({s.x, s.y}, run.cutter, s.z, run.coreR).coreClear &&
           cuts_.engagement({s.x, s.y}, run.cutter, s.z, e) <= e;
  });
  settle();
}

// Makes the planned plunges `left` (indices) nearest first from where the
// tool is, each only if `keeps` it when its turn comes (the ones before it
// may have cut what it would have). Returns how many it made.
template <class Keeps>
int Grower::placeNearestFirst(ToolRun& run, std::vector<size_t> left, Keeps keeps) {
  const std::vector<Plunge>& planned = run.planned;
  int placed = 0;
  while (!left.empty()) {
    progress_.tick();
    size_t best = 0;
    for (size_t i = 1; i < left.size(); ++i)
      if (dist(Vec2{planned[left[i]].x, planned[left[i]].y}, run.at) <
          dist(Vec2{planned[left[best]].x, planned[left[best]].y}, run.at) - 1e-9)
        best = i;
    const Plunge& s = planned[left[best]];
    left.erase(left.begin() + static_cast<long>(best));
    if (!keeps(s)) continue;
    place(run, {s.x, s.y}, s.z, false);
    ++placed;
  }
  return placed;
}

// A plunge of the tool at c, tip at z; the tool is there after it.
void Grower::place(ToolRun& run, Vec2 c, double z, bool start) {
  Plunge p = plungeOf(run.tool, c, z);
  p.start = start;
  order_.push_back(p);
  stock_.cut(c, run.cutter, z);
  cuts_.add(c, run.cutter, z);
  newDisks_.push_back({c, run.cutter.radius});
  run.targets.update(c, run.cutter.radius, stock_);
  run.targets.defer(c, run.cutter, z, stock_);  // what it left above its target, for the starts
  run.at = c;
}

// Material the rings cannot reach (slivers between their plunges, targets
// deeper than ring plunges stop over a sculptured floor): every planned
// plunge still cutting some (minGain cells, as everywhere in the growth)
// that keeps the limits is made as planned.
int Grower::finishPlanned(ToolRun& run) {
  auto keeps = [&](const Plunge& s) {
    const Vec2 c{s.x, s.y};
    if (run.targets.gain(c, run.cutter, s.z, stock_) < run.minGain) return false;
    return stock_.contact(c, run.cutter, s.z, run.coreR).coreClear &&
           cuts_.engagement(c, run.cutter, s.z, run.limit) <= run.limit;
  };
  // Those that keep the limits now, nearest first from where the tool is.
  std::vector<size_t> left;
  for (size_t k = 0; k < run.planned.size(); ++k) {
    progress_.tick();
    if (keeps(run.planned[k])) left.push_back(k);
  }
  return placeNearestFirst(run, std::move(left), keeps);
}

// The planned position not tried yet where the most target material is left,
// or none where no planned plunge would cut minGain cells: what is left is
// the raster's noise (and slivers, finishSlivers' work).
std::optional<size_t> Grower::richestStart(const ToolRun& run, const std::vector<bool>& tried) const {
  int best = -1, bestGain = 0;
  for (size_t k = 0; k < run.planned.size(); ++k) {
    progress_.tick();
    if (tried[k]) continue;
    const int g = run.targets.gain({run.planned[k].x, run.planned[k].y}, run.cutter, run.planned[k].z, stock_);
    if (g > bestGain) {
      bestGain = g;
      best = static_cast<int>(k);
    }
  }
  if (best < 0 || bestGain < run.minGain) return std::nullopt;
  return static_cast<size_t>(best);
}

// A start at richestStart: a plunge into solid (centre-cutting) or onto a
// start hole. False where there is none.
bool Grower::startAt(ToolRun& run, std::vector<bool>& tried) {
  const std::optional<size_t> best = richestStart(run, tried);
  if (!best) return false;
  tried[*best] = true;
  const Plunge& s = run.planned[*best];
  const Vec2 c{s.x, s.y};
  if (!run.tool.centerCutting) {
    const Tool& drill = in_.tools.startHoleFor(run.tool);
    const std::optional<double> z = stopAt(c, drill);
    // No hole possible here (a drill wider than the plunger may not fit): another start.
    if (!z || !region_.diskFits(c, 0.5 * drill.diameter + in_.radialAllowance)) return true;
    drillHole(drill, c, *z);
  }
  place(run, c, s.z, true);
  return true;
}

}  // namespace plunge
