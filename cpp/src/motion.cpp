#include "motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <iomanip>
#include <map>
#include <sstream>

#include "detail.hpp"
#include "covering.hpp"
#include "cuts.hpp"
#include "plunge/error.hpp"
#include "polygon.hpp"
#include "broken.hpp"

namespace plunge {

namespace {

// A rapid meeting more disks than this goes over top_z (Touched::highestAlong:
// the exact test of a gap among them would cost more than the height saves).
constexpr size_t kMaxDisksPerMove = 150;
// Lead-out directions tried around each plunge, and holes cut before that it may lead toward.
constexpr int kLeadOutDirections = 16;
constexpr size_t kHolesTried = 8;
// A raster cell's centre to its corner, in cells (sqrt(2) / 2, rounded up): how
// far a material cell's centre may lie from the material it stands for.
constexpr double kCellHalfDiagonal = 0.71;
// A raised lead-out: its height is searched on the first few directions that
// clear at the highest it may be, to this precision (mm); the lowest wins.
constexpr int kRaisedTried = 4;
constexpr double kRaisedPrecision = 0.002;

// Runs of consecutive plunges with the same tool and role.
template <class F>
void forEachGroup(const std::vector<Plunge>& order, F f) {
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j < order.size() && order[j].toolId == order[i].toolId && order[j].startHole == order[i].startHole) ++j;
    f(i, j);
    i = j;
  }
}

// Height of the tool's corner above its tip: the flutes above it cut walls.
double cornerHeight(const Tool& t) { return cutterProfile(cutterOf(t), 0.5 * t.diameter); }

// The plunges made so far, for the heights of rapids. Stock at a point is the
// lowest cut surface of the disks covering it, or top_z (stock or wall) where
// none does, so the highest stock under a rapid's swept disk is at most the
// highest bottom (tip + corner height) of the disks it meets, unless it meets
// untouched material. Exact where a raster could miss a feature narrower than
// a cell (a pin between three disks, the radial allowance). Pieces under
// 1e-4 mm^2, left by the disks' polygons (0.002 mm chords) and a 0.01 mm
// margin, do not count. A move meeting more than 150 disks goes over top_z.
class Touched {
 public:
  Touched(double bucket, double top) : bucket_(bucket), top_(top) {}
  void add(Vec2 c, double r, double bottom) {
    disks_.push_back({{c, r}, bottom});
    grid_[key(cellOf(c.x), cellOf(c.y))].push_back(disks_.size() - 1);
  }
  // Centres of the disks at least `r` wide, cut no higher than `bottom`,
  // between `from` and `to` away from c, nearest first (at most `count`).
  std::vector<Vec2> holesNear(Vec2 c, double r, double bottom, double from, double to, size_t count) const {
    std::vector<std::pair<double, Vec2>> found;
    forEachDiskNear(c, to, [&](const Disk& d) {
      const double l = dist(d.circle.c, c);
      if (l >= from && l <= to && d.circle.r >= r - 1e-9 && d.bottom <= bottom + 1e-9) found.push_back({l, d.circle.c});
    });
    std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<Vec2> out;
    for (size_t k = 0; k < found.size() && k < count; ++k) out.push_back(found[k].second);
    return out;
  }
  // Whether a disk of radius r moved from the hole at c to `end` reaches more
  // than `limit` beyond r from c into material: whether any of the crescent
  // of the moved disk farther than r + limit from c is left uncut by the
  // disks cut to `bottom` or deeper (polygons, nearest disks first; only the
  // crescent is clipped, so the booleans stay small).
  bool grazes(Vec2 c, Vec2 end, double r, double bottom, double limit) const {
    // The inner disk's polygon (inscribed) grown by its chord error: it holds the whole circle.
    Polygons rest =
        poly::subtract({poly::disk({end, r - 0.01}, kCoverChord)}, {poly::disk({c, r + limit + kCoverChord}, kCoverChord)});
    if (poly::area(rest) <= 1e-6) return false;
    std::vector<Circle> near;
    forEachDiskNear(end, 2 * r, [&](const Disk& d) {
      if (d.bottom <= bottom + 1e-9 && dist(d.circle.c, end) < d.circle.r + r) near.push_back(d.circle);
    });
    if (crescentWitness(c, end, r - 0.01, r + limit, near)) return true;
    return !coveredBy(std::move(rest), end, std::move(near), 1e-6);
  }
  // The highest stock a disk of radius r swept from a to b passes over (an upper bound).
  double highestAlong(Vec2 a, Vec2 b, double r) const {
    const Segment path{a, b};
    const Vec2 lo{std::min(a.x, b.x) - r, std::min(a.y, b.y) - r}, hi{std::max(a.x, b.x) + r, std::max(a.y, b.y) + r};
    std::vector<Circle> near;
    double highest = -std::numeric_limits<double>::infinity();
    for (long j = cellOf(lo.y) - 1; j <= cellOf(hi.y) + 1; ++j)
      for (long i = cellOf(lo.x) - 1; i <= cellOf(hi.x) + 1; ++i) {
        auto it = grid_.find(key(i, j));
        if (it == grid_.end()) continue;
        for (size_t k : it->second) {
          const Disk& d = disks_[k];
          if (distanceToSegment(path, d.circle.c) >= d.circle.r + r) continue;
          near.push_back(d.circle);
          highest = std::max(highest, d.bottom);
        }
      }
    // Long moves over many disks go over the top of the stock: cheaper than the
    // exact test, and never lower than the truth.
    if (near.empty() || near.size() > kMaxDisksPerMove || uncoveredWitness(a, b, r - 0.01, near)) return top_;
    const double rs = r - 0.01;
    Polygons swept{poly::disk({a, rs})};
    if (dist(a, b) > 1e-9) {
      const Vec2 n = leftNormal((b - a) * (1.0 / dist(a, b))) * rs;
      swept = poly::unite({poly::disk({a, rs}), poly::disk({b, rs}), Loop{a - n, b - n, b + n, a + n}});
    }
    if (!coveredBy(swept, a, near)) return top_;
    return std::min(top_, highest);
  }

 private:
  // Calls f(disk) for each disk in the grid cells within `reach` of c (and one
  // cell beyond): the candidates a query then tests exactly.
  template <class F>
  void forEachDiskNear(Vec2 c, double reach, F f) const {
    for (long j = cellOf(c.y - reach) - 1; j <= cellOf(c.y + reach) + 1; ++j)
      for (long i = cellOf(c.x - reach) - 1; i <= cellOf(c.x + reach) + 1; ++i) {
        auto it = grid_.find(key(i, j));
        if (it == grid_.end()) continue;
        for (size_t k : it->second) f(disks_[k]);
      }
  }
  // A point of the swept disk (radius rs) at least kWitness inside it and
  // kWitness outside every near disk proves an uncovered piece of pi kWitness^2
  // (more than the polygon test's 1e-4 mm^2): the common case (a move over
  // uncut gaps, a plunge into fresh stock), found without polygon booleans.
  static constexpr double kWitness = 0.01;
  // The cut disks' polygons in the exact tests: inscribed (they cover less than
  // the disks), within half the 0.01 mm the moved disk is shrunk by.
  static constexpr double kCoverChord = 0.005;
  // Whether the disks leave less than 1e-4 mm^2 of `swept` uncut. The disks
  // nearest to `from` first, one at a time, each only if it reaches what is
  // left: the rest shrinks fast, so the booleans stay small (the union of 150
  // disks first, then one difference, cost 20 ms a move where plunges crowd).
  static bool coveredBy(Polygons rest, Vec2 from, std::vector<Circle> near, double tiny = 1e-4) {
    std::stable_sort(near.begin(), near.end(),
                     [&](const Circle& x, const Circle& y) { return dist(x.c, from) < dist(y.c, from); });
    detail::Bounds b;
    for (const Loop& l : rest) b.add(l);
    for (const Circle& d : near) {
      if (rest.empty()) break;
      if (d.c.x + d.r < b.lo.x || d.c.x - d.r > b.hi.x || d.c.y + d.r < b.lo.y || d.c.y - d.r > b.hi.y) continue;
      rest = poly::subtract(rest, {poly::disk(d, kCoverChord)});
      b = {};
      for (const Loop& l : rest) b.add(l);
    }
    return poly::area(rest) <= tiny;
  }
  // A point of the moved disk (radius rs at end) kWitness inside it, beyond
  // `beyond` + kWitness from c and kWitness outside every near disk: proof of
  // uncut material there without polygons (most directions that graze).
  static bool crescentWitness(Vec2 c, Vec2 end, double rs, double beyond, const std::vector<Circle>& near) {
    const double inner = rs - kWitness;
    if (inner <= 0.0) return false;
    const int n = std::clamp(static_cast<int>(std::ceil(2 * kPi * inner / 0.25)), 24, 512);
    for (double f : {1.0, 0.98, 0.95}) {
      for (int k = 0; k < n; ++k) {
        const double t = 2 * kPi * k / n;
        const Vec2 q = end + Vec2{std::cos(t), std::sin(t)} * (f * inner);
        if (dist(q, c) < beyond + kWitness) continue;
        if (clearOf(near, q)) return true;
      }
    }
    return false;
  }
  // q at least kWitness outside every disk.
  static bool clearOf(const std::vector<Circle>& near, Vec2 q) {
    for (const Circle& d : near)
      if (dist(q, d.c) < d.r + kWitness) return false;
    return true;
  }
  static bool uncoveredWitness(Vec2 a, Vec2 b, double rs, const std::vector<Circle>& near) {
    auto uncovered = [&](Vec2 q) { return clearOf(near, q); };
    const double inner = rs - kWitness;
    if (inner <= 0.0) return false;
    const int along = std::min(64, 1 + static_cast<int>(std::ceil(dist(a, b) / (0.5 * inner))));
    for (int s = 0; s <= along; ++s) {
      const Vec2 q = a + (b - a) * (static_cast<double>(s) / along);
      if (uncovered(q)) return true;
      for (int k = 0; k < 24; ++k) {
        const double t = 2 * kPi * k / 24;
        for (double f : {0.5, 1.0})
          if (uncovered(q + Vec2{std::cos(t), std::sin(t)} * (f * inner))) return true;
      }
    }
    return false;
  }
  struct Disk {
    Circle circle;
    double bottom;
  };
  long cellOf(double v) const { return static_cast<long>(std::floor(v / bucket_)); }
  // Unsigned: shifting a negative cell index left is undefined.
  static long long key(long i, long j) {
    const unsigned long long hi = static_cast<unsigned long long>(i) << 32;
    return static_cast<long long>(hi ^ (static_cast<unsigned long long>(j) & 0xffffffffULL));
  }
  double bucket_, top_;
  std::vector<Disk> disks_;
  std::map<long long, std::vector<size_t>> grid_;
};

}  // namespace

HeightField stockOf(const std::vector<Tool>& tools, double topZ, const Region& region) {
  double rMin = 0.5 * tools.back().diameter, limit = rMin;
  for (const Tool& t : tools) {
    rMin = std::min(rMin, 0.5 * t.diameter);
    limit = std::min({limit, t.minEngagement.value_or(limit), t.maxEngagement.value_or(limit)});
  }
  const double rMax = 0.5 * tools.front().diameter;
  const Vec2 lo = region.minCorner() - Vec2{rMax, rMax}, hi = region.maxCorner() + Vec2{rMax, rMax};
  return HeightField(lo, hi, heightFieldSpacing(lo, hi, rMin, limit), topZ);
}

std::vector<Plunge> splitIntoLevels(const std::vector<Plunge>& ordered, const MotionOptions& in, PlanStats& stats) {
  Touched touched(in.tools.all().front().diameter, in.topZ);
  std::vector<Plunge> out;
  stats.levels = 1;
  forEachGroup(ordered, [&](size_t i, size_t j) {
    const Tool& t = in.tools.byId(ordered[i].toolId);
    const Cutter cutter = cutterOf(t);
    std::vector<double> top;
    int levels = 1;
    const double step = t.fluteLength.value_or(0.0) - cornerHeight(t);
    for (size_t k = i; k < j; ++k) {
      const Vec2 c{ordered[k].x, ordered[k].y};
      top.push_back(touched.highestAlong(c, c, cutter.radius));
      if (t.fluteLength)
        levels = std::max(levels, static_cast<int>(std::ceil((top.back() - ordered[k].z) / step - 1e-9)));
    }
    stats.levels = std::max(stats.levels, levels);
    for (int level = 1; level <= levels; ++level)
      for (size_t k = i; k < j; ++k) {
        Plunge p = ordered[k];
        p.z = level == levels ? p.z : std::max(p.z, top[k - i] - level * step);
        // Already at its depth on an earlier level.
        if (level > 1 && std::max(ordered[k].z, top[k - i] - (level - 1) * step) <= ordered[k].z) continue;
        p.level = level - 1;
        out.push_back(p);
        touched.add({p.x, p.y}, cutter.radius, p.z + cornerHeight(t));
      }
  });
  return out;
}

namespace {

// Why a plunge has no lead-out.
enum class NoLeadOut { None, Material, Walls };

// The lead-out end of a plunge just made (stock already cut by it), or none
// and why. Only directions that keep the allowance to the walls and do not
// cut the floor; of those, first one ending in cut space (no material under
// the moved disk, the most room from the walls first), then one toward a hole
// cut before (whose graze is bounded by geometry, below), then any that grazes
// material at its flanks by at most half the lead-out beyond the plunge's own
// hole, measured with the holes' polygons, then one raised out of the steps
// around (raisedTo: the height it feeds up to first). Cheap tests first, so
// the exact ones run on few directions.
std::optional<Vec2> leadOutOf(const MotionOptions& in, const Region& region, const DepthSolver& depths,
                              const HeightField& stock, const Touched& touched, const Plunge& p,
                              const Cutter& cutter, std::optional<Plunge> back, NoLeadOut& why,
                              std::optional<double>& raisedTo) {
  const Vec2 c{p.x, p.y};
  struct End {
    Vec2 at;
    double room;
    bool towardHole;
  };
  std::vector<End> ends;
  auto add = [&](Vec2 d, bool towardHole) {
    const Vec2 end = c + d * (in.leadOut / norm(d));
    ends.push_back({end, region.wallDistance(end, 4 * cutter.radius), towardHole});
  };
  // Toward holes cut before, as wide and as deep, d from this one (the
  // plunge before first): the moved disk lies in the two holes but where it
  // crosses between them, at most sqrt(r^2 + L^2 + L (d - L)) - r beyond this
  // hole, no more than half the lead-out L while d <= r + L / 4.
  std::vector<Vec2> holes;
  const double r = cutter.radius, L = in.leadOut, reach = r + 0.25 * L;
  if (L < r) {
    if (back && dist(Vec2{back->x, back->y}, c) >= L && dist(Vec2{back->x, back->y}, c) <= reach &&
        back->z <= p.z + 1e-9)
      holes.push_back({back->x, back->y});
    for (Vec2 h : touched.holesNear(c, r, p.z + cutterProfile(cutter, r), L, reach, kHolesTried)) holes.push_back(h);
  }
  for (Vec2 h : holes) add(h - c, true);
  for (int d = 0; d < kLeadOutDirections; ++d)
    add({std::cos(2 * kPi * d / kLeadOutDirections), std::sin(2 * kPi * d / kLeadOutDirections)}, false);
  // Beside the way to a hole (a contour along a wall that bulges in: the
  // straight way back comes too near the wall), measured with polygons below.
  for (Vec2 h : holes)
    for (double turn : {-20.0, 20.0, -40.0, 40.0}) {
      const double a = std::atan2(h.y - c.y, h.x - c.x) + turn * kPi / 180;
      add({std::cos(a), std::sin(a)}, false);
    }
  std::stable_sort(ends.begin(), ends.end(), [](const End& a, const End& b) { return a.room > b.room + 1e-9; });
  const int samples = std::max(2, static_cast<int>(std::ceil(in.leadOut / (0.25 * cutter.radius))));
  // Walls and islands (never nearer than the allowance), then the floor under
  // the moving tool (a depth optimization per sample on sculptured floors).
  auto wallsKept = [&](Vec2 end) {
    for (int s = 1; s <= samples; ++s)
      if (!region.diskFits(c + (end - c) * (static_cast<double>(s) / samples), cutter.radius + in.radialAllowance))
        return false;
    return true;
  };
  auto noGouge = [&](Vec2 end) {
    if (!wallsKept(end)) return false;
    for (int s = 1; s <= samples; ++s)
      if (depths.plungeHeight(c + (end - c) * (static_cast<double>(s) / samples), cutter, in.floorAllowance,
                              in.radialAllowance) > p.z + 1e-6)
        return false;
    return true;
  };
  const double margin = kCellHalfDiagonal * stock.spacing();
  std::vector<signed char> fits(ends.size(), -1);  // noGouge, computed once when needed
  auto fitsAt = [&](size_t k) {
    if (fits[k] < 0) fits[k] = noGouge(ends[k].at) ? 1 : 0;
    return fits[k] == 1;
  };
  for (size_t k = 0; k < ends.size(); ++k) {
    // Into no material (cells touching the moved disk: the crescent it adds is
    // narrower than a cell), then the exact bound of the stock left.
    const Vec2 end = ends[k].at;
    if (stock.meetsMaterial(end, cutter, p.z, margin) ||
        touched.highestAlong(c, end, cutter.radius) > p.z + cutterProfile(cutter, cutter.radius) + kEngagementSkin)
      continue;
    if (fitsAt(k)) return end;
  }
  for (size_t k = 0; k < ends.size(); ++k)
    if (ends[k].towardHole && fitsAt(k)) return ends[k].at;
  // Else any direction whose disk the holes cut so far (as deep) leave to
  // graze less than half the lead-out, measured exactly with their polygons.
  for (size_t k = 0; k < ends.size(); ++k)
    if (!ends[k].towardHole && stock.bite(c, ends[k].at, cutter, p.z) <= 0.5 * L &&
        !touched.grazes(c, ends[k].at, r, p.z + cutterProfile(cutter, r), 0.5 * L) && fitsAt(k))
      return ends[k].at;
  bool room = false;
  for (size_t k = 0; k < ends.size() && !room; ++k) room = fits[k] == 1 || wallsKept(ends[k].at);
  if (room) {
    // Raised: a plunge that went deeper than the plunges around it (a hollow
    // of a sculptured floor, uneven depths) sits in a ring of their steps.
    // It feeds up the ring's height, if that is no more than the lead-out is
    // long (the edges drag along at most that much of the wall just cut),
    // then out, grazing no more than half the lead-out at that height and
    // clear of the floor. The directions with the most room first.
    const double highest = p.z + L;
    auto grazes = [&](Vec2 end, double z) {
      return stock.bite(c, end, cutter, z) > 0.5 * L ||
             touched.grazes(c, end, r, z + cutterProfile(cutter, r), 0.5 * L);
    };
    // The height each of the first few clear directions needs to graze no
    // more (bisection), then the floor under the way out, lowest first.
    std::vector<std::pair<double, Vec2>> heights;
    for (size_t k = 0; k < ends.size() && heights.size() < kRaisedTried; ++k) {
      const Vec2 end = ends[k].at;
      if (grazes(end, highest) || !wallsKept(end)) continue;
      double lo = p.z, hi = highest;  // grazes at lo (the tests above), not at hi
      while (hi - lo > kRaisedPrecision) {
        const double mid = 0.5 * (lo + hi);
        (grazes(end, mid) ? lo : hi) = mid;
      }
      heights.push_back({hi, end});
    }
    std::stable_sort(heights.begin(), heights.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::optional<std::pair<double, Vec2>> best;
    for (auto [z, end] : heights) {
      if (best && z >= best->first) break;
      for (int s = 1; s <= samples && z <= highest; ++s)
        z = std::max(z, depths.plungeHeight(c + (end - c) * (static_cast<double>(s) / samples), cutter,
                                            in.floorAllowance, in.radialAllowance));
      if (z <= highest && (!best || z < best->first)) best = {{z, end}};
    }
    if (best) {
      if (best->first > p.z + 1e-6) raisedTo = best->first;
      return best->second;
    }
  }
  if (!room) {
    why = NoLeadOut::Walls;
    return std::nullopt;
  }
  why = NoLeadOut::Material;
  return std::nullopt;
}

}  // namespace

namespace {

// A plunge over its tool's max engagement by more than this is counted: the
// exact measure's rounding (cuts.hpp), as the tests' polygon replay allows.
constexpr double kEngagementTolerance = 0.01;

// A hole drilled into solid: material at the plunge's axis (a crescent beside
// removed material has its axis in the hole beside, and its chips room to go).
// Deeper than the tool's peck depth, from the material's top at the axis, it is
// pecked: a stop every peck depth, the last one short of z by at least a tenth
// of a peck (a stop closer to the bottom clears nothing).
std::vector<double> pecksOf(const Plunge& p, const Tool& t, const HeightField& stock, const MotionOptions& in) {
  std::vector<double> pecks;
  const double top = stock.heightAt({p.x, p.y});
  if (!in.peck || top <= p.z + kEngagementSkin) return pecks;
  const double peck = peckDepthOf(t);
  for (double z = top - peck; z > p.z + 0.1 * peck; z -= peck) pecks.push_back(z);
  return pecks;
}

}  // namespace

void planMotion(const Region& region, const DepthSolver& depths, Plan& plan, const MotionOptions& in) {
  HeightField stock = stockOf(in.tools.all(), in.topZ, region);
  Cuts cuts(kEngagementSkin);  // the plunges alone (not their lead-outs): the engagement as grown
  std::vector<Plunge>& ps = plan.plunges;
  Touched touched(in.tools.all().front().diameter, in.topZ);
  auto highestAlong = [&](Vec2 a, Vec2 b, double r) { return touched.highestAlong(a, b, r); };
  const double tol = 1.5 * stock.spacing();
  // Each limit a plunge breaks: how many, the worst (most beyond it) and where.
  struct Worst {
    BrokenLimit b;
    double excess = -1.0;
    bool start = false;  // the worst is a start
    void add(const Plunge& p, double value, double limit, double beyond) {
      ++b.count;
      if (beyond <= excess) return;
      excess = beyond;
      start = p.start;
      b.worst = value;
      b.asked = limit;
      b.at = {p.x, p.y};
    }
  };
  Worst over, thin, core, deep;
  over.b = {"max_engagement", 0, 0, {}, 0, ""};
  thin.b = {"min_engagement", 0, 0, {}, 0, ""};
  core.b = {"core_diameter", 0, 0, {}, 0, ""};
  deep.b = {"flute_length", 0, 0, {}, 0, ""};
  plan.stats.overEngaged = plan.stats.thinCuts = 0;
  plan.stats.leadOuts = plan.stats.raisedLeadOuts = plan.stats.noLeadOutMaterial = plan.stats.noLeadOutWalls = 0;
  plan.stats.travelLength = 0.0;
  plan.stats.peckedPlunges = 0;
  for (size_t i = 0; i < ps.size(); ++i) {
    in.progress.tick(static_cast<double>(i) / ps.size());
    Plunge& p = ps[i];
    const Tool& t = in.tools.byId(p.toolId);
    const Cutter cutter = cutterOf(t);
    const Vec2 c{p.x, p.y};
    const double r = cutter.radius;
    // What the plunge meets: its engagement measured exactly (cuts.hpp), as
    // the growth measured it, in the order posted.
    const HeightField::Contact k = stock.contact(c, cutter, p.z, coreRadius(t));
    p.engagement = k.materialCells > 0 ? cuts.engagement(c, cutter, p.z) : 0.0;
    const double top = highestAlong(c, c, r);
    // A start is exempt where it drills: into solid, or (a tool that does not
    // cut at its centre) onto its start hole. A start the growth had to make
    // beside cut material (its fallback) is measured as any plunge.
    const bool drills = p.start && (k.solid || !t.centerCutting);
    if (!drills && t.maxEngagement && p.engagement > *t.maxEngagement + kEngagementTolerance)
      over.add(p, p.engagement, *t.maxEngagement, p.engagement - *t.maxEngagement);
    if (!p.start && t.minEngagement && k.materialCells > 0 && p.engagement < *t.minEngagement - tol)
      thin.add(p, p.engagement, *t.minEngagement, *t.minEngagement - p.engagement);
    if (!t.centerCutting && !k.coreClear) core.add(p, k.deepest, t.coreDiameter, k.deepest);
    if (t.fluteLength && k.deepest + cornerHeight(t) > *t.fluteLength + 1e-6)
      deep.add(p, k.deepest + cornerHeight(t), *t.fluteLength, k.deepest + cornerHeight(t) - *t.fluteLength);
    p.approachZ = in.stockAwareHeights ? std::min(in.safeZ, std::max(top, p.z) + in.rapidClearance) : in.safeZ;
    // The retract of the plunge before: as high as the stock along the move.
    if (i > 0) {
      Plunge& q = ps[i - 1];
      const Vec2 from = q.leadOut ? *q.leadOut : Vec2{q.x, q.y};
      plan.stats.travelLength += dist(from, c);
      q.retractZ = in.safeZ;
      if (in.stockAwareHeights && q.toolId == p.toolId)
        q.retractZ = std::min(in.safeZ, std::max({highestAlong(from, c, 0.5 * q.diameter) + in.rapidClearance,
                                                  p.approachZ, q.z + in.rapidClearance}));
    }
    p.pecks = pecksOf(p, t, stock, in);
    if (!p.pecks.empty()) ++plan.stats.peckedPlunges;
    stock.cut(c, cutter, p.z);
    cuts.add(c, cutter, p.z);
    touched.add(c, r, p.z + cornerHeight(t));
    p.leadOut.reset();
    p.leadOutZ.reset();
    if (in.leadOut > 0.0) {
      // Back toward the plunge before, where the same tool just cut.
      std::optional<Plunge> back;
      if (i > 0 && ps[i - 1].toolId == p.toolId) back = ps[i - 1];
      NoLeadOut why = NoLeadOut::None;
      p.leadOut = leadOutOf(in, region, depths, stock, touched, p, cutter, back, why, p.leadOutZ);
      if (why == NoLeadOut::Material) ++plan.stats.noLeadOutMaterial;
      if (why == NoLeadOut::Walls) ++plan.stats.noLeadOutWalls;
      if (p.leadOut) ++plan.stats.leadOuts;
      if (p.leadOutZ) ++plan.stats.raisedLeadOuts;
    }
    if (p.leadOut) {
      touched.add(*p.leadOut, r, p.leadOutZ.value_or(p.z) + cornerHeight(t));
      stock.cut(*p.leadOut, cutter, p.leadOutZ.value_or(p.z));  // what the next plunges meet
    }
    p.retractZ = in.safeZ;
  }
  // What the limits could not keep, each said once with its count, the worst and why.
  plan.stats.overEngaged = over.b.count;
  plan.stats.thinCuts = thin.b.count;
  auto say = [&](Worst& w, const std::string& what, const char* why) {
    if (w.b.count == 0) return;
    std::ostringstream s;
    s << std::fixed << std::setprecision(2) << w.b.count << what << " (" << w.b.worst << " mm against "
      << w.b.asked << " mm)";
    w.b.why = why;
    sayBroken(plan, s.str(), w.b);
  };
  say(over, " plunges cut a wider band than their tool's max engagement",
      over.start ? "a start the growth had to make beside cut material, where no path reached within the limit;"
                   " a smaller plunger there, or a larger max engagement, avoids it"
                 : "uneven depths of a sculptured floor leave steps thicker than the limit there; a lower max floor"
                   " stock or a smaller plunger cuts them in thinner steps");
  say(thin, " plunges cut a narrower band than their tool's min engagement",
      "the last slivers of their region, where the walls leave no wider cut, and the tool may deflect there; a"
      " smaller min engagement, or a smaller plunger for the slivers, avoids them");
  say(core, " plunges of a non-centre-cutting tool have material under the core",
      "uneven floor depths leave material there that the core cannot cut; a centre-cutting plunger, or a lower max"
      " floor stock, clears it first");
  say(deep, " plunges cut deeper than their tool's flute length",
      "the material there stands higher above the stop than the flutes reach; a plunger with longer flutes would"
      " cut it");
  plan.stats.estimatedMinutes = motionMinutes(plan, in, false);
  plan.stats.minutesAtSafeHeight = motionMinutes(plan, in, true);
}

double motionMinutes(const Plan& plan, const MotionOptions& in, bool atSafeHeight) {
  const TimeModel& m = in.timeModel;
  double minutes = 0.0, z = in.safeZ;
  int changes = 0;
  for (size_t i = 0; i < plan.plunges.size(); ++i) {
    const Plunge& p = plan.plunges[i];
    const double feed = in.tools.byId(p.toolId).feed;
    if (i == 0 || plan.plunges[i - 1].toolId != p.toolId) ++changes;
    if (i > 0) {
      const Plunge& q = plan.plunges[i - 1];
      minutes += dist(q.leadOut ? *q.leadOut : Vec2{q.x, q.y}, {p.x, p.y}) / m.rapidRate;
    }
    const double approach = atSafeHeight ? in.safeZ : p.approachZ;
    const double retract = atSafeHeight ? in.safeZ : p.retractZ;
    minutes += std::max(0.0, z - approach) / m.retractRate + (approach - p.z) / feed;
    // Each peck: up out of the hole and back to just above its depth, at rapid.
    for (double at : p.pecks) minutes += (2 * (approach - at) - in.rapidClearance) / m.retractRate;
    if (!p.pecks.empty()) minutes += in.peckDwell / 60.0;
    if (p.leadOut) minutes += (dist(*p.leadOut, {p.x, p.y}) + p.leadOutZ.value_or(p.z) - p.z) / feed;
    minutes += (retract - p.z) / m.retractRate;
    z = retract;
  }
  return minutes + changes * m.toolChangeSeconds / 60.0;
}

}  // namespace plunge
