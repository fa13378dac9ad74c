#include "plunge/engagement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <unordered_map>

#include "plunge/covering.hpp"
#include "plunge/error.hpp"
#include "plunge/polygon.hpp"

namespace plunge {

double engagementLimit(const Tool& t) {
  double e = t.maxEngagement > 0.0 ? t.maxEngagement : std::numeric_limits<double>::infinity();
  if (!t.centerCutting) e = std::min(e, 0.5 * (t.diameter - t.coreDiameter));
  return e;
}

const Tool& startHoleTool(const std::vector<Tool>& tools, const Tool& tool) {
  const Tool* best = nullptr;
  for (const Tool& t : tools)
    if (t.centerCutting && t.diameter >= tool.coreDiameter && (!best || t.diameter < best->diameter)) best = &t;
  if (!best) {
    std::ostringstream m;
    m << "tool " << tool.id << " (diameter " << tool.diameter << ") does not cut at its centre and the job has no "
      << "centre-cutting tool at least " << tool.coreDiameter
      << " mm wide to drill its start holes: add one (a drill or a centre-cutting end mill)";
    throw Error(m.str());
  }
  return *best;
}

namespace {

// The material a tool must clear: points sampled on the height field's raster
// inside its planned disks, each with the height the planned plunges cut it to.
class Targets {
 public:
  // The points are the stock's cell centres: a plunge covers a point exactly
  // when it cuts the point's cell.
  Targets(const std::vector<Plunge>& planned, const Cutter& cutter, const HeightField& stock)
      : bucket_(cutter.radius) {
    std::map<std::pair<long long, long long>, size_t> cell;
    const double h = stock.spacing();
    const Vec2 origin = stock.cellCentre({0.0, 0.0});
    for (const Plunge& p : planned) {
      const Vec2 c{p.x, p.y};
      const long n = std::lround(std::ceil(2 * cutter.radius / h)) + 1;
      const Vec2 first = stock.cellCentre(c - Vec2{cutter.radius, cutter.radius});
      for (long j = 0; j <= n; ++j)
        for (long i = 0; i <= n; ++i) {
          const Vec2 q = first + Vec2{i * h, j * h};
          const double rho = dist(q, c);
          if (rho > cutter.radius) continue;
          const double z = p.z + cutterProfile(cutter, rho);
          auto [it, fresh] = cell.try_emplace({std::llround((q.x - origin.x) / h), std::llround((q.y - origin.y) / h)},
                                              points_.size());
          if (fresh) {
            points_.push_back({q, z, false, false});
          } else {
            points_[it->second].z = std::min(points_[it->second].z, z);
          }
        }
    }
    for (size_t k = 0; k < points_.size(); ++k) grid_[key(points_[k].p)].push_back(k);
    left_ = points_.size();
  }

  // Target points a plunge at c (tip at z) would still cut, beyond the skin.
  template <class F>
  void forEachOpen(Vec2 c, double r, F f, bool withDeferred = true) const {
    const long bi = static_cast<long>(std::floor(c.x / bucket_)), bj = static_cast<long>(std::floor(c.y / bucket_));
    for (long j = bj - 1; j <= bj + 1; ++j)
      for (long i = bi - 1; i <= bi + 1; ++i) {
        auto it = grid_.find(pack(i, j));
        if (it == grid_.end()) continue;
        for (size_t k : it->second)
          if (!points_[k].done && (withDeferred || !points_[k].deferred) && dist(points_[k].p, c) <= r) f(k);
      }
  }
  int gain(Vec2 c, const Cutter& cutter, double z, const HeightField& stock) const {
    int n = 0;
    forEachOpen(c, cutter.radius, [&](size_t k) {
      if (z + cutterProfile(cutter, dist(points_[k].p, c)) < stock.heightAt(points_[k].p) - kEngagementSkin) ++n;
    });
    return n;
  }
  // Target points still to cut under a disk (whatever the plunge's depth),
  // not counting those the rings gave up on.
  int open(Vec2 c, double r) const {
    int n = 0;
    forEachOpen(c, r, [&](size_t) { ++n; }, false);
    return n;
  }
  // Over a sculptured floor a ring plunge may stop above a point its target
  // plunge reached: the rings leave such points to the starts at the planned
  // positions (startAt), instead of trying them again on every ring.
  void defer(Vec2 c, const Cutter& cutter, double z, const HeightField& stock) {
    forEachOpen(c, cutter.radius, [&](size_t k) {
      if (z + cutterProfile(cutter, dist(points_[k].p, c)) >= stock.heightAt(points_[k].p) - kEngagementSkin)
        points_[k].deferred = true;
    }, false);
  }
  // Marks the points cut (to their target height, within the skin) as done.
  void update(Vec2 c, double r, const HeightField& stock) {
    forEachOpen(c, r, [&](size_t k) {
      if (stock.heightAt(points_[k].p) <= points_[k].z + kEngagementSkin) {
        points_[k].done = true;
        --left_;
      }
    });
  }
  size_t left() const { return left_; }
  size_t size() const { return points_.size(); }

 private:
  struct Point {
    Vec2 p;
    double z;
    bool done;
    bool deferred = false;
  };
  // Unsigned: shifting a negative cell index left is undefined.
  static long long pack(long i, long j) {
    const unsigned long long hi = static_cast<unsigned long long>(i) << 32;
    return static_cast<long long>(hi ^ (static_cast<unsigned long long>(j) & 0xffffffffULL));
  }
  long long key(Vec2 p) const {
    return pack(static_cast<long>(std::floor(p.x / bucket_)), static_cast<long>(std::floor(p.y / bucket_)));
  }
  double bucket_;
  std::vector<Point> points_;
  std::unordered_map<long long, std::vector<size_t>> grid_;
  size_t left_ = 0;
};

// Points along every loop of `ring`, `step` apart, the loops visited nearest
// first from `at`, each walked from its vertex nearest to where the last ended.
std::vector<Vec2> walk(const Polygons& ring, Vec2 at, double step) {
  std::vector<Vec2> out;
  std::vector<bool> used(ring.size(), false);
  for (size_t n = 0; n < ring.size(); ++n) {
    size_t best = 0, bestVertex = 0;
    double bestD = std::numeric_limits<double>::infinity();
    for (size_t l = 0; l < ring.size(); ++l) {
      if (used[l]) continue;
      for (size_t v = 0; v < ring[l].size(); ++v)
        if (dist(ring[l][v], at) < bestD) {
          bestD = dist(ring[l][v], at);
          best = l;
          bestVertex = v;
        }
    }
    used[best] = true;
    const Loop& loop = ring[best];
    double carry = 0.0;  // distance walked since the last point
    out.push_back(loop[bestVertex]);
    for (size_t s = 0; s < loop.size(); ++s) {
      const Vec2 a = loop[(bestVertex + s) % loop.size()], b = loop[(bestVertex + s + 1) % loop.size()];
      const double len = dist(a, b);
      double t = step - carry;
      for (; t <= len; t += step) out.push_back(a + (b - a) * (t / len));
      carry = len - (t - step);
    }
    at = out.back();
  }
  return out;
}

class Grower {
 public:
  Grower(const PlanInput& in, const Region& region, const DepthSolver& depths, HeightField& stock,
         const Progress& progress)
      : in_(in), region_(region), depths_(depths), stock_(stock), progress_(progress) {}

  std::vector<Plunge> run(const std::vector<Plunge>& ordered) {
    size_t i = 0;
    while (i < ordered.size()) {
      size_t j = i;
      while (j < ordered.size() && ordered[j].toolId == ordered[i].toolId) ++j;
      const std::vector<Plunge> group(ordered.begin() + i, ordered.begin() + j);
      const Tool& tool = toolOf(ordered[i].toolId);
      if (std::isinf(engagementLimit(tool))) {
        for (const Plunge& p : group) add(p);
      } else {
        grow(tool, group);
      }
      i = j;
    }
    std::vector<Plunge> out = holes_;
    out.insert(out.end(), order_.begin(), order_.end());
    return out;
  }

 private:
  const Tool& toolOf(int id) const {
    for (const Tool& t : in_.tools)
      if (t.id == id) return t;
    throw Error("internal: a plunge of an unknown tool");
  }
  void add(const Plunge& p) {
    order_.push_back(p);
    stock_.cut({p.x, p.y}, cutterOf(toolOf(p.toolId)), p.z);
    newDisks_.push_back({{p.x, p.y}, 0.5 * p.diameter});
  }
  void settle() {
    if (newDisks_.empty()) return;
    cleared_ = poly::unite(cleared_, poly::unionOfDisks(newDisks_, 0.01));
    newDisks_.clear();
  }
  // The tip height of a plunge at c (its gouge-free depth, 4.4), or nothing above top_z.
  std::optional<double> stopAt(Vec2 c, const Tool& t) const {
    const double z = depths_.plungeHeight(c, cutterOf(t), in_.floorAllowance, in_.radialAllowance);
    if (z >= in_.topZ) return std::nullopt;
    return z;
  }

  // Grows the tool's cut over its targets (the plunges the plan gave it).
  void grow(const Tool& tool, const std::vector<Plunge>& planned) {
    settle();
    const Cutter cutter = cutterOf(tool);
    const double r = cutter.radius, e = std::min(engagementLimit(tool), 2 * r);
    const double coreR = tool.centerCutting ? 0.0 : 0.5 * tool.coreDiameter;
    const double h = stock_.spacing();
    Targets targets(planned, cutter, stock_);
    for (const Plunge& p : planned) targets.update({p.x, p.y}, r, stock_);
    const Polygons centres = poly::offset(allowedRegion(region_, in_.radialAllowance), -(r + 1e-3));
    // Along a ring, plunges a chord of the band apart: the next ring's offset
    // follows the scallops they leave.
    const double depthIn = r - 0.98 * e;
    const double step = std::clamp(0.9 * std::sqrt(std::max(0.0, r * r - depthIn * depthIn)),
                                   std::max(tool.minEngagement, 2 * h), r);
    const int minGain = std::max(3, static_cast<int>(0.003 * M_PI * r * r / (h * h)));
    std::vector<bool> triedStart(planned.size(), false);
    Vec2 at = order_.empty() ? (in_.start ? *in_.start : region_.loops()[0].front())
                             : Vec2{order_.back().x, order_.back().y};
    int stalls = 0;  // rounds that cut no target point (a guard: each round should)
    while (targets.left() > 0 && stalls < 3) {
      progress_.tick();
      const size_t before = targets.left();
      const Polygons ring = poly::intersect(poly::offset(cleared_, -depthIn, 0.01), centres);
      int accepted = 0;
      std::vector<std::pair<Vec2, double>> thin;
      for (const Vec2 c : walk(ring, at, step)) {
        // Cheap tests first: a stop height costs an optimization on sculptured floors.
        if (targets.open(c, r) < minGain || !region_.diskFits(c, r + in_.radialAllowance)) continue;
        const std::optional<double> z = stopAt(c, tool);
        if (!z) continue;
        if (targets.gain(c, cutter, *z, stock_) < minGain) {
          targets.defer(c, cutter, *z, stock_);
          continue;
        }
        const HeightField::Contact k = stock_.contact(c, cutter, *z, coreR);
        if (!k.coreClear || k.engagement > e + 2 * h) continue;
        if (k.engagement < tool.minEngagement) {
          thin.push_back({c, *z});
          continue;
        }
        place(tool, cutter, c, *z, targets, false);
        at = c;
        ++accepted;
      }
      // Where only thin cuts are left, make them (measured and reported).
      if (accepted == 0)
        for (const auto& [c, z] : thin)
          if (targets.gain(c, cutter, z, stock_) >= minGain && stock_.contact(c, cutter, z, coreR).coreClear) {
            place(tool, cutter, c, z, targets, false);
            at = c;
            ++accepted;
          }
      if (accepted == 0) accepted = finishPlanned(tool, cutter, planned, targets, at);
      if (accepted == 0 && !startAt(tool, cutter, planned, triedStart, targets, at)) break;
      settle();
      stalls = targets.left() < before ? 0 : stalls + 1;
    }
    finishSlivers(tool, cutter, planned, targets);
  }

  // Pieces of the tool's planned cut narrower than the stock's cells, which the
  // raster cannot see, measured exactly (polygons): each is cut by the planned
  // plunge that covers most of it, where that keeps the limits.
  void finishSlivers(const Tool& tool, const Cutter& cutter, const std::vector<Plunge>& planned, Targets& targets) {
    settle();
    std::vector<Circle> want;
    for (const Plunge& p : planned) want.push_back({{p.x, p.y}, cutter.radius});
    const double coreR = tool.centerCutting ? 0.0 : 0.5 * tool.coreDiameter;
    const double e = std::min(engagementLimit(tool), 2 * cutter.radius) + 2 * stock_.spacing();
    for (const Polygons& piece : poly::components(poly::subtract(poly::unionOfDisks(want), cleared_))) {
      if (poly::area(piece) < 0.01) continue;
      int best = -1;
      size_t inside = 0;
      for (size_t k = 0; k < planned.size(); ++k) {
        size_t n = 0;
        for (Vec2 v : piece.front()) n += dist(v, want[k].c) <= cutter.radius + 1e-6;
        if (n > inside) {
          inside = n;
          best = static_cast<int>(k);
        }
      }
      if (best < 0) continue;
      const Plunge& s = planned[best];
      const HeightField::Contact k = stock_.contact({s.x, s.y}, cutter, s.z, coreR);
      if (!k.coreClear || k.engagement > e) continue;
      place(tool, cutter, {s.x, s.y}, s.z, targets, false);
    }
    settle();
  }

  void place(const Tool& tool, const Cutter& cutter, Vec2 c, double z, Targets& targets, bool start) {
    Plunge p = plungeOf(tool, c, z);
    p.start = start;
    order_.push_back(p);
    stock_.cut(c, cutter, z);
    newDisks_.push_back({c, cutter.radius});
    targets.update(c, cutter.radius, stock_);
    targets.defer(c, cutter, z, stock_);  // what it left above its target, for the starts
  }

  // Material the rings cannot reach (slivers between their plunges, targets
  // deeper than ring plunges stop over a sculptured floor): every planned
  // plunge still cutting some that keeps the limits is made as planned.
  int finishPlanned(const Tool& tool, const Cutter& cutter, const std::vector<Plunge>& planned, Targets& targets,
                    Vec2& at) {
    const double coreR = tool.centerCutting ? 0.0 : 0.5 * tool.coreDiameter;
    const double e = std::min(engagementLimit(tool), 2 * cutter.radius);
    int placed = 0;
    for (const Plunge& s : planned) {
      const Vec2 c{s.x, s.y};
      if (targets.gain(c, cutter, s.z, stock_) < 1) continue;
      const HeightField::Contact k = stock_.contact(c, cutter, s.z, coreR);
      if (!k.coreClear || k.engagement > e) continue;
      place(tool, cutter, c, s.z, targets, false);
      at = c;
      ++placed;
    }
    return placed;
  }

  // A start where the most target material is left, among the planned
  // positions: a plunge into solid (centre-cutting) or onto a start hole.
  bool startAt(const Tool& tool, const Cutter& cutter, const std::vector<Plunge>& planned,
               std::vector<bool>& tried, Targets& targets, Vec2& at) {
    int best = -1, bestGain = 0;
    for (size_t k = 0; k < planned.size(); ++k) {
      if (tried[k]) continue;
      const int g = targets.gain({planned[k].x, planned[k].y}, cutter, planned[k].z, stock_);
      if (g > bestGain) {
        bestGain = g;
        best = static_cast<int>(k);
      }
    }
    if (best < 0) return false;
    tried[best] = true;
    const Plunge& s = planned[best];
    const Vec2 c{s.x, s.y};
    if (!tool.centerCutting) {
      const Tool& drill = startHoleTool(in_.tools, tool);
      const std::optional<double> z = stopAt(c, drill);
      // No hole possible here (a drill wider than the plunger may not fit): another start.
      if (!z || !region_.diskFits(c, 0.5 * drill.diameter + in_.radialAllowance)) return true;
      Plunge hole = plungeOf(drill, c, *z);
      hole.startHole = hole.start = true;
      holes_.push_back(hole);
      stock_.cut(c, cutterOf(drill), hole.z);
    }
    place(tool, cutter, c, s.z, targets, true);
    at = c;
    return true;
  }

  const PlanInput& in_;
  const Region& region_;
  const DepthSolver& depths_;
  HeightField& stock_;
  const Progress& progress_;
  Polygons cleared_;
  std::vector<Circle> newDisks_;
  std::vector<Plunge> order_, holes_;
};

}  // namespace

std::vector<Plunge> growWithinLimits(const PlanInput& in, const Region& region, const DepthSolver& depths,
                                     const std::vector<Plunge>& ordered, HeightField& stock,
                                     const Progress& progress) {
  return Grower(in, region, depths, stock, progress).run(ordered);
}

}  // namespace plunge
