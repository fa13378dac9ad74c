#include "engagement.hpp"

#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <tuple>
#include <unordered_map>

#include "covering.hpp"
#include "cuts.hpp"
#include "plunge/error.hpp"
#include "polygon.hpp"
#include "plunge/sequencing.hpp"

namespace plunge {

namespace {

// Centres this much farther from the allowed region than the radius: the
// offset's arcs are chords whose midpoints lie up to kArcTolerance inside, and
// a plunge there must still fit (Region::diskFits); and a lead-out along a
// wall that bulges in (a chord to the plunge before) keeps the allowance.
constexpr double kCentreMargin = 0.05;
// The wall band a limited tool leaves to its contour, as a share of
// max_wall_stock: the contour is spaced for 0.8 of it on straight walls and
// refined where curved walls leave more than this.
constexpr double kWallBand = 0.9;
// The floor stock a limited tool leaves to the finishing pass, as a share of
// max_floor_stock (the raster's heights and the stock samples' differ a little).
constexpr double kFloorBand = 0.9;
// The contour along the walls is spaced for this share of max_wall_stock on
// straight walls (the raster measures to a cell; refineContour adds plunges
// where curved walls leave up to kWallBand).
constexpr double kContourScallop = 0.8;
// Rings (the fallback after the paths): a ring lies this share of the band
// inside what is cut, and its plunges a chord of that band apart times
// kRingChord, so that every plunge measures a little under the band.
constexpr double kRingBand = 0.98;
constexpr double kRingChord = 0.9;
// A plunge is worth making when it cuts this share of its disk's raster cells,
// and at least kMinGainCells of them (fewer is the raster's noise).
constexpr double kMinGainShare = 0.003;
constexpr int kMinGainCells = 3;
// A plunge is within its limit when its exact engagement (cuts.hpp) is at
// most this over it: the measure's own rounding (its circles are exact, its
// radii 0.25 degrees apart, refined).
constexpr double kExactSlack = 0.002;
// Entries to the paths: a row entered before the contour beside it is cut
// cuts its ends, which the contour covers (on sculptured floors, where walks
// stop at deeper neighbours, that costs plunges); so the contour's positions
// come first unless a row is this many tool radii nearer (the tour's length).
constexpr double kRowDetour = 1.0;
// Rounds of rings that cut nothing before a tool gives up on its targets.
constexpr int kStallRounds = 3;

// A grid cell's key. Unsigned: shifting a negative cell index left is undefined.
long long pack(long i, long j) {
  const unsigned long long hi = static_cast<unsigned long long>(i) << 32;
  return static_cast<long long>(hi ^ (static_cast<unsigned long long>(j) & 0xffffffffULL));
}

// Items of a grid keyed by pack(cell indices), cells `cell` wide: whether f
// holds for any in the 3 x 3 cells around c (each visited until one does).
template <class T, class F>
bool anyNear(const std::unordered_map<long long, std::vector<T>>& grid, Vec2 c, double cell, F f) {
  const long ci = static_cast<long>(std::floor(c.x / cell)), cj = static_cast<long>(std::floor(c.y / cell));
  for (long j = cj - 1; j <= cj + 1; ++j)
    for (long i = ci - 1; i <= ci + 1; ++i) {
      const auto it = grid.find(pack(i, j));
      if (it != grid.end())
        for (const T& item : it->second)
          if (f(item)) return true;
    }
  return false;
}

// The material a tool must clear: points sampled on the height field's raster
// inside its planned disks, each with the height the planned plunges cut it to.
class Targets {
 public:
  // The points are the stock's cell centres: a plunge covers a point exactly
  // when it cuts the point's cell.
  Targets(const std::vector<Plunge>& planned, const Cutter& cutter, const HeightField& stock, const Progress& progress)
      : bucket_(cutter.radius) {
    std::unordered_map<long long, size_t> cell;
    const double h = stock.spacing();
    const Vec2 origin = stock.cellCentre({0.0, 0.0});
    for (const Plunge& p : planned) {
      progress.tick();
      const Vec2 c{p.x, p.y};
      const long n = std::lround(std::ceil(2 * cutter.radius / h)) + 1;
      const Vec2 first = stock.cellCentre(c - Vec2{cutter.radius, cutter.radius});
      for (long j = 0; j <= n; ++j)
        for (long i = 0; i <= n; ++i) {
          const Vec2 q = first + Vec2{i * h, j * h};
          const double rho = dist(q, c);
          if (rho > cutter.radius) continue;
          const double z = p.z + cutterProfile(cutter, rho);
          auto [it, fresh] = cell.try_emplace(pack(std::lround((q.x - origin.x) / h), std::lround((q.y - origin.y) / h)),
                                              points_.size());
          if (fresh) {
            points_.push_back({q, z, false, false});
          } else {
            points_[it->second].z = std::min(points_[it->second].z, z);
          }
        }
    }
    for (size_t k = 0; k < points_.size(); ++k) {
      if (k % 4096 == 0) progress.tick();
      grid_[key(points_[k].p)].push_back(k);
    }
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
        for (size_t k : it->second) {
          if (points_[k].done || (!withDeferred && points_[k].deferred)) continue;
          const Vec2 d = points_[k].p - c;
          if (d.x * d.x + d.y * d.y <= r * r) f(k);
        }
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
  // Marks the points cut to their target height (within the skin), or to
  // within the floor stock they may keep, as done.
  void update(Vec2 c, double r, const HeightField& stock) {
    forEachOpen(c, r, [&](size_t k) {
      if (stock.heightAt(points_[k].p) <= std::max(points_[k].z + kEngagementSkin, points_[k].enough)) {
        points_[k].done = true;
        --left_;
      }
    });
  }
  // Over a sculptured floor a point cut to `enough(p)` needs no more: what is
  // left there is the floor's stock, the finisher's.
  template <class F>
  void keepAbove(F enough) {
    for (Point& q : points_) q.enough = enough(q.p);
  }
  // Gives up the points `skip` says need no cutting.
  template <class F>
  void forget(F skip) {
    for (Point& q : points_)
      if (!q.done && skip(q.p)) {
        q.done = true;
        --left_;
      }
  }
  size_t left() const { return left_; }
  size_t size() const { return points_.size(); }

 private:
  struct Point {
    Vec2 p;
    double z;
    bool done;
    bool deferred = false;
    double enough = -std::numeric_limits<double>::infinity();
  };
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

// The long axis of a region: the direction of its largest second moment of
// area about its centroid (the principal axis; rows run along it).
double longAxis(const Polygons& region) {
  if (region.empty() || region.front().empty()) return 0.0;
  const Vec2 o = region.front().front();  // moments about a nearby point keep precision
  double a = 0, sx = 0, sy = 0, xx = 0, yy = 0, xy = 0;
  for (const Loop& l : region)
    for (size_t i = 0; i < l.size(); ++i) {
      const Vec2 p = l[i] - o, q = l[(i + 1) % l.size()] - o;
      const double w = cross(p, q);
      a += w / 2;
      sx += (p.x + q.x) * w / 6;
      sy += (p.y + q.y) * w / 6;
      xx += (p.x * p.x + p.x * q.x + q.x * q.x) * w / 12;
      yy += (p.y * p.y + p.y * q.y + q.y * q.y) * w / 12;
      xy += (p.x * q.y + 2 * p.x * p.y + 2 * q.x * q.y + q.x * p.y) * w / 24;
    }
  if (std::fabs(a) < 1e-12) return 0.0;
  const double cxx = xx - sx * sx / a, cyy = yy - sy * sy / a, cxy = xy - sx * sy / a;
  return 0.5 * std::atan2(2 * cxy, cxx - cyy);
}

// Rows at angle th across the region, evenly spaced at most rowSpacing apart
// between its extremes, each piece inside the region `step` apart.
std::vector<GrowthPath> rowsAt(const Polygons& centres, double th, double step, double rowSpacing) {
  std::vector<GrowthPath> out;
  const double c = std::cos(th), s = std::sin(th);
  auto toRow = [&](Vec2 p) { return Vec2{p.x * c + p.y * s, -p.x * s + p.y * c}; };
  auto fromRow = [&](Vec2 p) { return Vec2{p.x * c - p.y * s, p.x * s + p.y * c}; };
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Loop& l : centres)
    for (Vec2 p : l) {
      lo = std::min(lo, toRow(p).y);
      hi = std::max(hi, toRow(p).y);
    }
  const int gaps = static_cast<int>(std::ceil((hi - lo) / rowSpacing - 1e-9));
  for (int k = 1; k < gaps; ++k) {
    const double y = lo + (hi - lo) * k / gaps;
    std::vector<double> xs;  // where the row crosses the region's loops
    for (const Loop& l : centres)
      for (size_t i = 0; i < l.size(); ++i) {
        const Vec2 a = toRow(l[i]), b = toRow(l[(i + 1) % l.size()]);
        if ((a.y <= y) != (b.y <= y)) xs.push_back(a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y));
      }
    std::sort(xs.begin(), xs.end());
    for (size_t i = 0; i + 1 < xs.size(); i += 2) {
      // On a lattice `step` apart, shifted half a step on every other row,
      // from just inside one end to the other end.
      const double shift = (k % 2) * 0.5 * step, a = xs[i], b = xs[i + 1];
      GrowthPath path;
      path.at.push_back(fromRow({a, y}));
      for (double x = (std::floor((a - shift) / step) + 1) * step + shift; x < b - 1e-6; x += step)
        if (x > a + 1e-6) path.at.push_back(fromRow({x, y}));
      path.at.push_back(fromRow({b, y}));
      out.push_back(std::move(path));
    }
  }
  return out;
}

// Positions along a loop at most `maxStep` apart, on every corner (a turn of
// over 20 degrees: a corner's plunge reaches into the pocket's corner, none
// between would), evenly from one corner to the next.
std::vector<Vec2> alongLoop(const Loop& l, double maxStep) {
  const size_t m = l.size();
  std::vector<size_t> corners;
  for (size_t i = 0; i < m; ++i) {
    const Vec2 a = l[(i + m - 1) % m], b = l[i], c = l[(i + 1) % m];
    const double n1 = dist(a, b), n2 = dist(b, c);
    if (n1 > 0 && n2 > 0 && dot(b - a, c - b) < std::cos(kPi / 9) * n1 * n2) corners.push_back(i);
  }
  if (corners.empty()) corners.push_back(0);
  std::vector<Vec2> out;
  for (size_t k = 0; k < corners.size(); ++k) {
    // From this corner up to the next one, evenly.
    const size_t from = corners[k], to = corners[(k + 1) % corners.size()];
    const size_t span = (to + m - from) % m == 0 ? m : (to + m - from) % m;
    double length = 0;
    for (size_t s = 0; s < span; ++s) length += dist(l[(from + s) % m], l[(from + s + 1) % m]);
    const int n = std::max(1, static_cast<int>(std::ceil(length / maxStep - 1e-9)));
    double walked = 0;
    int placed = 0;
    for (size_t s = 0; s < span && placed < n; ++s) {
      const Vec2 a = l[(from + s) % m], b = l[(from + s + 1) % m];
      const double len = dist(a, b);
      for (double next = length * placed / n; next <= walked + len && placed < n; next = length * ++placed / n)
        out.push_back(len > 0 ? a + (b - a) * ((next - walked) / len) : a);
      walked += len;
    }
  }
  return out;
}

// Offsets of the region's contour, `spacing` apart inwards, positions at most
// `step` apart along each loop (alongLoop); where the next offset is empty,
// one more halfway. `outer`: the contour's positions.
std::vector<GrowthPath> offsetsAt(const Polygons& centres, double step, double spacing, std::vector<Vec2> outer) {
  std::vector<GrowthPath> out;
  auto add = [&](const Polygons& loops) {
    std::vector<Vec2> next;
    for (const Loop& l : loops) {
      GrowthPath path;
      path.closed = true;
      path.at = alongLoop(l, step);
      // A bridge from the loop outside to this loop's first position: each
      // loop is entered from cut material, like a row from the contour.
      Vec2 from = outer.front();
      for (Vec2 o : outer)
        if (dist(o, path.at.front()) < dist(from, path.at.front())) from = o;
      GrowthPath bridge;
      const Vec2 to = path.at.front();
      const int n = static_cast<int>(std::ceil(dist(from, to) / step - 1e-9));
      for (int i = 1; i < n; ++i) bridge.at.push_back(from + (to - from) * (static_cast<double>(i) / n));
      next.insert(next.end(), path.at.begin(), path.at.end());
      out.push_back(std::move(path));
      if (!bridge.at.empty()) out.push_back(std::move(bridge));
    }
    outer = std::move(next);
  };
  for (int k = 1; !outer.empty(); ++k) {
    const Polygons loops = poly::offset(centres, -k * spacing);
    if (loops.empty()) {  // one more halfway, or the middle stays out of reach
      add(poly::offset(centres, -(k - 0.5) * spacing));
      break;
    }
    add(loops);
  }
  return out;
}

}  // namespace

double loopSpacing(double r, double step) {
  // Side by side, not staggered: the closest the scallops come is midway
  // between two plunges of a loop.
  const double h = std::min(step, 2 * r);
  return 2 * std::sqrt(r * r - 0.25 * h * h);
}

double rowSpacing(double r, double step) {
  // Staggered rows (each row's plunges between the last row's): the scallops
  // of neighbouring rows interleave; the closest they come is either a plunge
  // opposite a gap or a quarter step from both.
  const double h = std::min(step, 2 * r);
  return std::min(r + std::sqrt(r * r - 0.25 * h * h), 2 * std::sqrt(r * r - h * h / 16));
}

std::vector<GrowthPath> growthPaths(const Polygons& centres, double step, double wallStep, double spacing,
                                    GrowthPattern pattern) {
  std::vector<GrowthPath> out;
  if (centres.empty() || !(step > 0) || !(spacing > 0)) return out;
  // Rows along the long axis; parallel to the longest wall instead where that
  // is within 10 degrees of it (a machinist's rows run along the walls).
  double th = longAxis(centres), longest = 0;
  for (const Loop& l : centres)
    for (size_t i = 0; i < l.size(); ++i) {
      const Vec2 d = l[(i + 1) % l.size()] - l[i];
      const double a = std::atan2(d.y, d.x);
      if (norm(d) > longest && std::fabs(std::remainder(a - longAxis(centres), kPi)) < kPi / 18) {
        longest = norm(d);
        th = a;
      }
    }
  // Each connected piece of the region on its own (the tool finishes one
  // before it moves to another): its contour, then its rows.
  const std::vector<Polygons> pieces = poly::components(centres);
  for (size_t piece = 0; piece < pieces.size(); ++piece) {
    const size_t first = out.size();
    const Polygons& region = pieces[piece];
    // The contour: every loop of the centre region, at most wallStep apart.
    for (const Loop& l : region) {
      GrowthPath path;
      path.closed = path.contour = true;
      path.at = alongLoop(l, wallStep);
      out.push_back(std::move(path));
    }
    std::vector<Vec2> contour;
    for (size_t k = first; k < out.size(); ++k) contour.insert(contour.end(), out[k].at.begin(), out[k].at.end());
    for (GrowthPath& p : pattern == GrowthPattern::Offsets ? offsetsAt(region, step, spacing, contour)
                                                            : rowsAt(region, th, step, spacing))
      out.push_back(std::move(p));
    for (size_t k = first; k < out.size(); ++k) out[k].piece = piece;
  }
  return out;
}


namespace {

// The nearest point on the region's loops to p.
Vec2 nearestOnLoops(const Polygons& loops, Vec2 p) {
  Vec2 best = p;
  double bestD = std::numeric_limits<double>::infinity();
  for (const Loop& l : loops)
    for (size_t i = 0; i < l.size(); ++i) {
      const Vec2 q = closestPointOnSegment({l[i], l[(i + 1) % l.size()]}, p);
      if (dist(q, p) < bestD) {
        bestD = dist(q, p);
        best = q;
      }
    }
  return best;
}

// Where a wall curves away from the contour, neighbours a wall step apart
// leave a deeper scallop at the wall than on a straight one: a position is
// added between two whose scallop (the circles' crossing on the wall side)
// stands more than `scallop` beyond the allowance.
void refineContour(GrowthPath& path, const Polygons& centres, const Region& region, double r, double allowance,
                   double scallop) {
  for (int pass = 0; pass < 4; ++pass) {
    std::vector<Vec2> out;
    bool added = false;
    const size_t n = path.at.size();
    for (size_t i = 0; i < n; ++i) {
      const Vec2 a = path.at[i], b = path.at[(i + 1) % n];
      out.push_back(a);
      if (n < 2 || dist(a, b) < 1e-3) continue;
      const std::vector<Vec2> cusps = intersectCircles({a, r}, {b, r});
      double wall = std::numeric_limits<double>::infinity();  // the cusp on the wall side
      for (Vec2 q : cusps) wall = std::min(wall, region.wallDistance(q, 2 * r));
      if (cusps.size() == 2 && wall - allowance > scallop) {
        out.push_back(nearestOnLoops(centres, a + (b - a) * 0.5));
        added = true;
      }
    }
    path.at = std::move(out);
    if (!added) break;
  }
}

// Row positions the contour cuts anyway: every sample of the disk (rings a
// quarter radius apart) lies within r of a contour position. Between the
// wall's contour and an island's less than two swaths apart, a row would cut
// only what the contours cut; the growth enters such a position only where
// nothing else can be entered or started (a connector to a contour).
std::vector<std::vector<bool>> coveredByContour(const std::vector<GrowthPath>& paths, double r) {
  const double cell = 2 * r;
  auto key = [&](Vec2 p) {
    return pack(static_cast<long>(std::floor(p.x / cell)), static_cast<long>(std::floor(p.y / cell)));
  };
  std::unordered_map<long long, std::vector<Vec2>> contour;
  for (const GrowthPath& p : paths)
    if (p.contour)
      for (Vec2 c : p.at) contour[key(c)].push_back(c);
  auto cut = [&](Vec2 q) { return anyNear(contour, q, cell, [&](Vec2 c) { return dist(c, q) <= r; }); };
  auto covered = [&](Vec2 c) {
    if (!cut(c)) return false;
    for (int ring = 1; ring <= 4; ++ring)
      for (int a = 0; a < 6 * ring; ++a) {
        const double t = 2 * kPi * a / (6 * ring) + 0.3 * ring;
        if (!cut(c + Vec2{std::cos(t), std::sin(t)} * (r * ring / 4))) return false;
      }
    return true;
  };
  std::vector<std::vector<bool>> out;
  for (const GrowthPath& p : paths) {
    out.emplace_back(p.at.size(), false);
    if (!p.contour)
      for (size_t i = 0; i < p.at.size(); ++i) out.back()[i] = covered(p.at[i]);
  }
  return out;
}

class Grower {
 public:
  Grower(const EngagementOptions& in, const Region& region, const DepthSolver& depths, HeightField& stock)
      : in_(in), region_(region), depths_(depths), stock_(stock), progress_(in.progress) {}

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
  const Tool& toolOf(int id) const { return in_.tools.byId(id); }
  void add(const Plunge& p) {
    order_.push_back(p);
    stock_.cut({p.x, p.y}, cutterOf(toolOf(p.toolId)), p.z);
    cuts_.add({p.x, p.y}, cutterOf(toolOf(p.toolId)), p.z);
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

  // Grows the tool's cut over its targets along the pattern asked for; with
  // Auto twice, along rows and along offsets of the contour, keeping the one
  // with fewer plunges, a start into solid counted twice (it drills the whole
  // disk and cannot lead out), rows on a tie. Rows suit long straight
  // pockets, offsets rings and narrow necks. The two run at once, one per
  // core, the second on its own copies of the stock and of the floor (whose
  // evaluation is not thread-safe, floor.hpp).
  void grow(const Tool& tool, const std::vector<Plunge>& planned) {
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
    if (cost(other) < cost(*this)) {
      stock_ = std::move(otherStock);
      cleared_ = std::move(other.cleared_);
      newDisks_ = std::move(other.newDisks_);
      order_ = std::move(other.order_);
      holes_ = std::move(other.holes_);
      cuts_ = std::move(other.cuts_);
    }
  }

  // Grows the tool's cut over its targets (the plunges the plan gave it).
  void grow(const Tool& tool, const std::vector<Plunge>& planned, GrowthPattern pattern) {
    settle();
    const size_t begin = order_.size();
    const Cutter cutter = cutterOf(tool);
    const double r = cutter.radius, e = std::min(engagementLimit(tool), 2 * r);
    const double coreR = coreRadius(tool);
    const double h = stock_.spacing();
    Targets targets(planned, cutter, stock_, progress_);
    keepFloorStock(targets);
    for (const Plunge& p : planned) targets.update({p.x, p.y}, r, stock_);
    // Material in the wall band is the walls' stock (kept within max_wall_stock
    // by the contour's spacing), not a target: chasing the scallops the planned
    // disks would have left elsewhere costs plunges and leaves no less stock.
    if (in_.maxWallStock > 0) {
      const double band = in_.radialAllowance + kWallBand * in_.maxWallStock;
      targets.forget([&](Vec2 q) {
        progress_.tick();
        return region_.wallDistance(q, band + 1.0) < band;
      });
    }
    const Polygons centres = poly::offset(allowedRegion(region_, in_.radialAllowance), -(r + kCentreMargin));
    // Along a ring, plunges a chord of the band apart: the next ring's offset
    // follows the scallops they leave.
    const double depthIn = r - kRingBand * e;
    const double step = std::clamp(kRingChord * std::sqrt(std::max(0.0, r * r - depthIn * depthIn)),
                                   std::max(tool.minEngagement.value_or(0.0), 2 * h), r);
    const int minGain = std::max(kMinGainCells, static_cast<int>(kMinGainShare * kPi * r * r / (h * h)));
    std::vector<bool> triedStart(planned.size(), false);
    Vec2 at = order_.empty() ? (in_.start ? *in_.start : region_.loops()[0].front())
                             : Vec2{order_.back().x, order_.back().y};
    growAlongPaths(tool, cutter, centres, pattern, targets, minGain, at);
    int stalls = 0;  // rounds that cut no target point (a guard: each round should)
    while (targets.left() > 0 && stalls < kStallRounds) {
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
        if (!stock_.contact(c, cutter, *z, coreR).coreClear) continue;
        const double engaged = cuts_.engagement(c, cutter, *z, e + kExactSlack);
        if (engaged > e + kExactSlack) continue;
        if (engaged < tool.minEngagement.value_or(0.0)) {
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
      if (accepted == 0) accepted = finishPlanned(tool, cutter, planned, targets, minGain, at);
      if (accepted == 0 && !startAt(tool, cutter, planned, triedStart, targets, minGain, at)) break;
      settle();
      stalls = targets.left() < before ? 0 : stalls + 1;
    }
    finishSlivers(tool, cutter, planned, targets, at);
    shortenTour(begin);
  }

  // The tour within the order the growth allows: a plunge measured against
  // the stock the plunges before it left meets the same stock in any order
  // that keeps it after every plunge whose disk reaches its own (the raster's
  // cells, a margin of two, included), so depths, engagement, cores and starts
  // stay as measured while the tour shortens (sequencing.hpp).
  void shortenTour(size_t begin) {
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
  // stock, as in the rest step (stock.hpp), not a target: a plunge for it
  // would cut a sliver of a few tenths (the planned rest plunges, where it is
  // thicker, stay targets). A target point is done as soon as it is cut that
  // low, so a path position that would only deepen such points is not made.
  void keepFloorStock(Targets& targets) const {
    if (!(in_.maxFloorStock > 0) || !sculptured()) return;
    const FloorSurface& floor = depths_.floor();
    const double keep = in_.floorAllowance + kFloorBand * in_.maxFloorStock;
    targets.keepAbove([&](Vec2 q) {
      const double f = floor.height(q);
      return std::isfinite(f) ? f + keep : -std::numeric_limits<double>::infinity();
    });
  }
  bool sculptured() const {
    return !depths_.floor().isFlat() ||
           std::any_of(in_.tools.all().begin(), in_.tools.all().end(), [](const Tool& t) { return t.shape != CutterShape::Flat; });
  }

  // Grows along the contour and rows (growthPaths): each path is entered next
  // to cut material, nearest first, and walked while its plunges keep the
  // limit; where nothing can be entered, a start. Leaves to the rings what the
  // paths cannot reach.
  void growAlongPaths(const Tool& tool, const Cutter& cutter, const Polygons& centres, GrowthPattern pattern,
                      Targets& targets, int minGain, Vec2& at) {
    const double r = cutter.radius, e = std::min(engagementLimit(tool), 2 * r);
    const double coreR = coreRadius(tool);
    const double h = stock_.spacing();
    // A step a little under the band (the raster measures to a cell); rows as
    // far apart as the scallops along them allow, a cell of overlap.
    // A core is checked three quarters of a cell wider (a cell's centre may lie
    // that far from a point it stands for), so steps keep that much inside.
    const double coreMargin = 0.75 * h;
    const double step = std::max(std::min(e - 0.25 * h, coreR > 0 ? r - coreR - coreMargin - 0.05 * h : e),
                                 std::max(tool.minEngagement.value_or(0.0), 2 * h));
    // Along the walls, plunges close enough that their scallops keep the wall
    // stock limit (with a margin for the raster).
    double wallStep = step;
    const double scallop = kContourScallop * in_.maxWallStock;
    if (scallop > 0 && scallop < r) wallStep = std::min(step, 2 * std::sqrt(r * r - (r - scallop) * (r - scallop)));
    const double spacing = (pattern == GrowthPattern::Offsets ? loopSpacing(r, step) : rowSpacing(r, step)) - h;
    std::vector<GrowthPath> paths = growthPaths(centres, step, wallStep, spacing, pattern);
    if (scallop > 0)
      for (GrowthPath& p : paths)
        if (p.contour) refineContour(p, centres, region_, r, in_.radialAllowance, kWallBand * in_.maxWallStock);
    const std::vector<std::vector<bool>> covered = coveredByContour(paths, r);
    enum class Verdict { Skip, Blocked, Solid, Thin, Ok };
    struct Pos {
      Vec2 c;
      size_t path, index;
      bool covered = false;  // a row position the contour cuts anyway (coveredByContour)
      bool open = true;
      // What a plunge here would meet, measured until a plunge lands nearby.
      bool known = false, skip = false, solid = false, coreClear = true;
      double engagement = 0.0;
      std::optional<double> z;
      bool zKnown = false;
    };
    std::vector<Pos> pos;
    std::vector<size_t> first;  // each path's first position in pos
    for (size_t k = 0; k < paths.size(); ++k) {
      first.push_back(pos.size());
      for (size_t i = 0; i < paths[k].at.size(); ++i) pos.push_back({paths[k].at[i], k, i, covered[k][i], true, false, false, false, true, 0.0, std::nullopt, false});
    }
    if (pos.empty()) return;
    // Positions by cell, to forget the verdicts a new plunge may change.
    const double cell = 2 * r + e + 2 * h;
    std::unordered_map<long long, std::vector<size_t>> near;
    for (size_t k = 0; k < pos.size(); ++k)
      near[pack(static_cast<long>(std::floor(pos[k].c.x / cell)), static_cast<long>(std::floor(pos[k].c.y / cell)))]
          .push_back(k);
    auto zOf = [&](Pos& p) {
      if (!p.zKnown) {
        p.zKnown = true;
        if (region_.diskFits(p.c, r + in_.radialAllowance)) p.z = stopAt(p.c, tool);
      }
      return p.z;
    };
    // Every plunge, entered anywhere or a step on along its path, is measured
    // exactly (cuts.hpp) against the plunges before it.
    auto judge = [&](size_t k) {
      Pos& p = pos[k];
      if (!p.known) {
        progress_.tick();
        p.known = true;
        if (targets.open(p.c, r) < minGain || !zOf(p)) {
          p.skip = true;
        } else if (targets.gain(p.c, cutter, *p.z, stock_) < minGain) {
          targets.defer(p.c, cutter, *p.z, stock_);
          p.skip = true;
        } else {
          const HeightField::Contact m = stock_.contact(p.c, cutter, *p.z, coreR > 0 ? coreR + coreMargin : 0.0);
          p.solid = m.solid;
          p.coreClear = m.coreClear;
          if (!p.solid && p.coreClear) p.engagement = cuts_.engagement(p.c, cutter, *p.z, e + kExactSlack);
        }
      }
      if (p.skip) return Verdict::Skip;
      if (p.solid) return Verdict::Solid;  // a drill into solid: a start, whatever the limit
      if (!p.coreClear || p.engagement > e + kExactSlack) return Verdict::Blocked;
      return p.engagement < tool.minEngagement.value_or(0.0) ? Verdict::Thin : Verdict::Ok;
    };
    auto cut = [&](size_t k, bool start) {
      pos[k].open = false;
      place(tool, cutter, pos[k].c, *pos[k].z, targets, start);
      at = pos[k].c;
      anyNear(near, at, cell, [&](size_t q) {
        if (pos[q].open && !pos[q].skip) pos[q].known = false;
        return false;  // every one
      });
    };
    // The next position along a path (dir +1 or -1), or none.
    auto along = [&](size_t k, int dir) -> std::optional<size_t> {
      const GrowthPath& path = paths[pos[k].path];
      const long n = static_cast<long>(path.at.size()), i = static_cast<long>(pos[k].index) + dir;
      if (!path.closed && (i < 0 || i >= n)) return std::nullopt;
      return first[pos[k].path] + static_cast<size_t>((i + n) % n);
    };
    // Can a contour's position near c be entered now?
    auto contourOpens = [&](Vec2 c) {
      return anyNear(near, c, cell, [&](size_t q) {
        return pos[q].open && paths[pos[q].path].contour && dist(pos[q].c, c) <= 2 * r &&
               judge(q) == Verdict::Ok;
      });
    };
    // From a plunge just made, on along its path while the plunges keep the
    // limit; a thin plunge only where the next one needs it. A walk stops
    // before a position the contour cuts anyway (until the contour is cut
    // there, when it is skipped); a connector (a walk entered at such a
    // position) stops as soon as a contour beside it can be entered.
    auto walkOn = [&](size_t k) {
      std::optional<size_t> ahead = along(k, +1);
      const int dir = ahead && pos[*ahead].open ? +1 : -1;
      const bool connector = pos[k].covered;
      size_t last = k;
      for (std::optional<size_t> q = along(k, dir); q && pos[*q].open; q = along(*q, dir)) {
        progress_.tick();
        if (connector && contourOpens(pos[last].c)) break;
        if (!connector && pos[*q].covered && judge(*q) != Verdict::Skip) break;
        zOf(pos[*q]);
        const Verdict v = judge(*q);
        if (v == Verdict::Skip) {
          pos[*q].open = false;
        } else if (v == Verdict::Ok) {
          cut(*q, false);
          last = *q;
        } else if (v == Verdict::Thin) {
          const std::optional<size_t> next = along(*q, dir);
          if (next && pos[*next].open && judge(*next) == Verdict::Ok) {
            pos[*q].open = false;  // the next one cuts wider without it
          } else {
            cut(*q, false);
            last = *q;
          }
        } else {
          break;
        }
      }
    };
    std::vector<size_t> open(pos.size());
    for (size_t k = 0; k < pos.size(); ++k) open[k] = k;
    std::vector<std::pair<std::tuple<bool, bool, double>, size_t>> order;
    std::optional<size_t> piece;  // where the last plunge was
    while (targets.left() > 0) {
      progress_.tick();
      // The piece of the region the tool is in first, then nearest first (ties
      // by index, so deterministic), the contour's positions kRowDetour radii
      // nearer than the rows'. Row positions the contour cuts anyway come
      // last, after a start: a start is one plunge, a row between two
      // contours a dozen.
      open.erase(std::remove_if(open.begin(), open.end(), [&](size_t k) { return !pos[k].open; }), open.end());
      if (open.empty()) break;
      order.clear();
      for (size_t k : open) {
        const Vec2 d = pos[k].c - at;
        const double detour = paths[pos[k].path].contour ? 0.0 : kRowDetour * r;
        order.push_back({{pos[k].covered, piece && paths[pos[k].path].piece != *piece, norm(d) + detour}, k});
      }
      std::sort(order.begin(), order.end());
      std::optional<size_t> entry, thin, start;
      for (const auto& [unused, k] : order) {
        if (pos[k].covered && (thin || start)) break;
        const Verdict v = judge(k);
        if (v == Verdict::Skip) {
          pos[k].open = false;
        } else if (v == Verdict::Ok) {
          entry = k;
          break;
        } else if (v == Verdict::Thin && !thin) {
          thin = k;
        } else if (v == Verdict::Solid && !start && canStart(tool, pos[k].c)) {
          start = k;
        }
      }
      if (!entry) entry = thin;
      if (entry) {
        cut(*entry, false);
      } else if (start) {
        drillStart(tool, pos[*start].c);
        cut(*start, true);
      } else {
        break;
      }
      walkOn(entry ? *entry : *start);
      piece = paths[pos[entry ? *entry : *start].path].piece;
    }
  }

  // Can the tool start at c: a plunge into solid (centre-cutting) or onto a
  // hole its start-hole tool can drill there.
  bool canStart(const Tool& tool, Vec2 c) const {
    if (tool.centerCutting) return true;
    const Tool& drill = in_.tools.startHoleFor(tool);
    return stopAt(c, drill) && region_.diskFits(c, 0.5 * drill.diameter + in_.radialAllowance);
  }
  void drillStart(const Tool& tool, Vec2 c) {
    if (tool.centerCutting) return;
    const Tool& drill = in_.tools.startHoleFor(tool);
    Plunge hole = plungeOf(drill, c, *stopAt(c, drill));
    hole.startHole = hole.start = true;
    holes_.push_back(hole);
    stock_.cut(c, cutterOf(drill), hole.z);
    cuts_.add(c, cutterOf(drill), hole.z);
  }

  // Pieces of the tool's planned cut narrower than the stock's cells, which the
  // raster cannot see, measured exactly (polygons): each is cut by the planned
  // plunge that covers most of it, where that keeps the limits.
  void finishSlivers(const Tool& tool, const Cutter& cutter, const std::vector<Plunge>& planned, Targets& targets,
                     Vec2 at) {
    settle();
    std::vector<Circle> want;
    for (const Plunge& p : planned) want.push_back({{p.x, p.y}, cutter.radius});
    const double coreR = coreRadius(tool);
    const double e = std::min(engagementLimit(tool), 2 * cutter.radius) + kExactSlack;
    Polygons left = poly::subtract(poly::unionOfDisks(want), cleared_);
    if (in_.maxWallStock > 0)  // beyond the wall band, as the targets
      left = poly::intersect(left,
                             poly::offset(allowedRegion(region_, in_.radialAllowance), -kWallBand * in_.maxWallStock));
    std::vector<size_t> chosen;  // for each piece, the planned plunge covering most of it
    for (const Polygons& piece : poly::components(left)) {
      progress_.tick();
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
      if (best >= 0) chosen.push_back(static_cast<size_t>(best));
    }
    placeNearestFirst(tool, cutter, planned, std::move(chosen), targets, at, [&](const Plunge& s) {
      return stock_.contact({s.x, s.y}, cutter, s.z, coreR).coreClear &&
             cuts_.engagement({s.x, s.y}, cutter, s.z, e) <= e;
    });
    settle();
  }

  // Makes the planned plunges `left` (indices) nearest first from where the
  // tool is, each only if `keeps` it when its turn comes (the ones before it
  // may have cut what it would have). Returns how many it made.
  template <class Keeps>
  int placeNearestFirst(const Tool& tool, const Cutter& cutter, const std::vector<Plunge>& planned,
                        std::vector<size_t> left, Targets& targets, Vec2& at, Keeps keeps) {
    int placed = 0;
    while (!left.empty()) {
      progress_.tick();
      size_t best = 0;
      for (size_t i = 1; i < left.size(); ++i)
        if (dist(Vec2{planned[left[i]].x, planned[left[i]].y}, at) <
            dist(Vec2{planned[left[best]].x, planned[left[best]].y}, at) - 1e-9)
          best = i;
      const Plunge& s = planned[left[best]];
      left.erase(left.begin() + static_cast<long>(best));
      if (!keeps(s)) continue;
      place(tool, cutter, {s.x, s.y}, s.z, targets, false);
      at = {s.x, s.y};
      ++placed;
    }
    return placed;
  }

  void place(const Tool& tool, const Cutter& cutter, Vec2 c, double z, Targets& targets, bool start) {
    Plunge p = plungeOf(tool, c, z);
    p.start = start;
    order_.push_back(p);
    stock_.cut(c, cutter, z);
    cuts_.add(c, cutter, z);
    newDisks_.push_back({c, cutter.radius});
    targets.update(c, cutter.radius, stock_);
    targets.defer(c, cutter, z, stock_);  // what it left above its target, for the starts
  }

  // Material the rings cannot reach (slivers between their plunges, targets
  // deeper than ring plunges stop over a sculptured floor): every planned
  // plunge still cutting some (minGain cells, as everywhere in the growth)
  // that keeps the limits is made as planned.
  int finishPlanned(const Tool& tool, const Cutter& cutter, const std::vector<Plunge>& planned, Targets& targets,
                    int minGain, Vec2& at) {
    const double coreR = coreRadius(tool);
    const double e = std::min(engagementLimit(tool), 2 * cutter.radius);
    auto keeps = [&](const Plunge& s) {
      const Vec2 c{s.x, s.y};
      if (targets.gain(c, cutter, s.z, stock_) < minGain) return false;
      return stock_.contact(c, cutter, s.z, coreR).coreClear && cuts_.engagement(c, cutter, s.z, e) <= e;
    };
    // Those that keep the limits now, nearest first from where the tool is.
    std::vector<size_t> left;
    for (size_t k = 0; k < planned.size(); ++k) {
      progress_.tick();
      if (keeps(planned[k])) left.push_back(k);
    }
    return placeNearestFirst(tool, cutter, planned, std::move(left), targets, at, keeps);
  }

  // A start where the most target material is left, among the planned
  // positions: a plunge into solid (centre-cutting) or onto a start hole.
  // None where no planned plunge would cut minGain cells: what is left is the
  // raster's noise (and slivers, finishSlivers' work).
  bool startAt(const Tool& tool, const Cutter& cutter, const std::vector<Plunge>& planned,
               std::vector<bool>& tried, Targets& targets, int minGain, Vec2& at) {
    int best = -1, bestGain = 0;
    for (size_t k = 0; k < planned.size(); ++k) {
      progress_.tick();
      if (tried[k]) continue;
      const int g = targets.gain({planned[k].x, planned[k].y}, cutter, planned[k].z, stock_);
      if (g > bestGain) {
        bestGain = g;
        best = static_cast<int>(k);
      }
    }
    if (best < 0 || bestGain < minGain) return false;
    tried[best] = true;
    const Plunge& s = planned[best];
    const Vec2 c{s.x, s.y};
    if (!tool.centerCutting) {
      const Tool& drill = in_.tools.startHoleFor(tool);
      const std::optional<double> z = stopAt(c, drill);
      // No hole possible here (a drill wider than the plunger may not fit): another start.
      if (!z || !region_.diskFits(c, 0.5 * drill.diameter + in_.radialAllowance)) return true;
      Plunge hole = plungeOf(drill, c, *z);
      hole.startHole = hole.start = true;
      holes_.push_back(hole);
      stock_.cut(c, cutterOf(drill), hole.z);
      cuts_.add(c, cutterOf(drill), hole.z);
    }
    place(tool, cutter, c, s.z, targets, true);
    at = c;
    return true;
  }

  const EngagementOptions& in_;
  const Region& region_;
  const DepthSolver& depths_;
  HeightField& stock_;
  Cuts cuts_{kEngagementSkin};  // the same plunges as circles: the exact engagement
  const Progress& progress_;
  Polygons cleared_;
  std::vector<Circle> newDisks_;
  std::vector<Plunge> order_, holes_;
};

}  // namespace

std::vector<Plunge> growWithinLimits(const Region& region, const DepthSolver& depths,
                                     const std::vector<Plunge>& ordered, HeightField& stock,
                                     const EngagementOptions& options) {
  return Grower(options, region, depths, stock).run(ordered);
}

}  // namespace plunge
