#include "region.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "detail.hpp"
#include "plunge/error.hpp"

namespace plunge {

using namespace detail;

// Distances asked about up to this (mm) query the walls in a box of that size.
constexpr double kBoxReach = 50.0;

struct Region::Index {
  RStarTree<BoxValue> walls;
  RStarTree<PointValue> reflex;
};

namespace {

std::string loopName(size_t i) {
  return i == 0 ? std::string("boundary") : "island " + std::to_string(i);
}

Loop cleanLoop(const Loop& in, const std::string& name) {
  Loop out;
  for (const Vec2& p : in) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y))
      throw Error(name + ": coordinate is not a finite number");
    if (out.empty() || out.back() != p) out.push_back(p);
  }
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  if (out.size() < 3)
    throw Error(name + ": needs at least 3 distinct points, got " + std::to_string(out.size()));
  return out;
}

// Ray-casting parity of one loop (half-open rule).
bool insideLoop(const Loop& loop, Vec2 p) {
  bool in = false;
  const size_t n = loop.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++)
    if (crossesRay(loop[j], loop[i], p)) in = !in;
  return in;
}

}  // namespace

Region::~Region() = default;
Region::Region(Region&&) noexcept = default;
Region& Region::operator=(Region&&) noexcept = default;

Region::Region(const Loop& boundary, const std::vector<Loop>& islands) : index_(new Index) {
  loops_.push_back(cleanLoop(boundary, "boundary"));
  for (size_t i = 0; i < islands.size(); ++i) loops_.push_back(cleanLoop(islands[i], loopName(i + 1)));
  orientLoops();
  buildWalls();
  checkCrossings();
  checkNesting();
  Bounds b;
  b.add(loops_[0]);
  lo_ = b.lo;
  hi_ = b.hi;
}

// Orientation: material to remove on the left of every wall.
void Region::orientLoops() {
  for (size_t i = 0; i < loops_.size(); ++i) {
    const double a = signedArea(loops_[i]);
    double scale = 0.0;
    for (const Vec2& p : loops_[i]) scale = std::max({scale, std::fabs(p.x), std::fabs(p.y), 1.0});
    if (std::fabs(a) <= 1e-12 * scale * scale) throw Error(loopName(i) + ": has zero area");
    if ((i == 0) != (a > 0)) std::reverse(loops_[i].begin(), loops_[i].end());
  }
}

// Walls and vertices, each loop's walls numbered consecutively from loopFirst_;
// the walls' and the reflex vertices' R-trees.
void Region::buildWalls() {
  for (size_t li = 0; li < loops_.size(); ++li) {
    const Loop& L = loops_[li];
    const int first = static_cast<int>(walls_.size());
    loopFirst_.push_back(walls_.size());
    const int n = static_cast<int>(L.size());
    for (int k = 0; k < n; ++k) {
      walls_.push_back({L[k], L[(k + 1) % n]});
      wallLoop_.push_back(static_cast<int>(li));
    }
    for (int k = 0; k < n; ++k) {
      const int prev = first + (k + n - 1) % n, next = first + k;
      const Vec2 din = walls_[prev].b - walls_[prev].a, dout = walls_[next].b - walls_[next].a;
      // Interior on the left: a right turn is a reflex (concave) corner of the region.
      vertices_.push_back({L[k], prev, next, cross(din, dout) < 0.0});
    }
  }
  std::vector<BoxValue> boxes;
  for (size_t i = 0; i < walls_.size(); ++i) boxes.emplace_back(boxOf(walls_[i]), static_cast<int>(i));
  index_->walls = decltype(index_->walls)(boxes.begin(), boxes.end());
  std::vector<PointValue> reflex;
  for (size_t v = 0; v < vertices_.size(); ++v)
    if (vertices_[v].reflex) reflex.emplace_back(toBPoint(vertices_[v].p), static_cast<int>(v));
  index_->reflex = decltype(index_->reflex)(reflex.begin(), reflex.end());
}

// Self-intersections and loops crossing each other: every pair of walls whose boxes meet.
void Region::checkCrossings() const {
  for (size_t i = 0; i < walls_.size(); ++i) {
    std::vector<BoxValue> hits;
    index_->walls.query(bgi::intersects(boxOf(walls_[i])), std::back_inserter(hits));
    for (const BoxValue& h : hits)
      if (static_cast<size_t>(h.second) > i) checkWallPair(i, static_cast<size_t>(h.second));
  }
}

void Region::checkWallPair(size_t i, size_t j) const {
  const Segment& s1 = walls_[i];
  const Segment& s2 = walls_[j];
  const int l1 = wallLoop_[i], l2 = wallLoop_[j];
  const size_t n = loops_[l1].size(), f = loopFirst_[l1];
  const bool adjacent = l1 == l2 && (j == i + 1 || (i == f && j == f + n - 1));
  if (adjacent) {
    // Adjacent walls share one end; they conflict only when they fold back on each other.
    const Vec2 d1 = s1.b - s1.a, d2 = s2.b - s2.a;
    const bool folds = std::fabs(cross(d1, d2)) <= 1e-12 * norm(d1) * norm(d2) && dot(d1, d2) < 0.0;
    if (folds)
      throw Error(loopName(l1) + ": self-intersecting (the loop folds back on itself near " +
                  formatPoint(j == i + 1 ? s1.b : s1.a) + ")");
    return;
  }
  if (!segmentsIntersect(s1, s2)) return;
  Vec2 where = s1.a;
  if (auto x = intersectLines(s1.a, s1.b - s1.a, s2.a, s2.b - s2.a)) where = *x;
  if (l1 == l2) throw Error(loopName(l1) + ": self-intersecting near " + formatPoint(where));
  if (l1 == 0 || l2 == 0)
    throw Error(loopName(std::max(l1, l2)) + ": crosses or touches the boundary near " + formatPoint(where));
  throw Error("islands " + std::to_string(l1) + " and " + std::to_string(l2) + " overlap near " +
              formatPoint(where));
}

// No crossings: each island is wholly inside or wholly outside every other loop.
void Region::checkNesting() const {
  for (size_t i = 1; i < loops_.size(); ++i) {
    if (!insideLoop(loops_[0], loops_[i][0])) throw Error(loopName(i) + ": lies outside the boundary");
    for (size_t j = 1; j < loops_.size(); ++j)
      if (i != j && insideLoop(loops_[j], loops_[i][0]))
        throw Error("islands " + std::to_string(j) + " and " + std::to_string(i) + " overlap (island " +
                    std::to_string(i) + " lies inside island " + std::to_string(j) + ")");
  }
}

double Region::area() const {
  double a = 0.0;
  for (const Loop& L : loops_) a += signedArea(L);
  return a;
}

bool Region::contains(Vec2 p) const {
  // Count crossings of the ray towards +x; the R-tree finds the walls that can cross it.
  const BBox ray(BPoint(p.x, p.y), BPoint(std::numeric_limits<double>::max(), p.y));
  bool in = false;
  for (auto it = index_->walls.qbegin(bgi::intersects(ray)); it != index_->walls.qend(); ++it) {
    const Segment& s = walls_[it->second];
    if (crossesRay(s.a, s.b, p)) in = !in;
  }
  return in;
}

double Region::wallDistance(Vec2 p, double within) const {
  double best = std::numeric_limits<double>::infinity();
  if (within > kBoxReach) {
    // Far reach (a tool as large as the pocket), where the box below would meet
    // every wall: the 16 walls with the nearest boxes (a box's distance is a
    // lower bound of its wall's). Enough when the 16th box lies beyond the
    // nearest wall found; else the box query.
    const BPoint q(p.x, p.y);
    const unsigned k = 16;
    unsigned seen = 0;
    double lastLower = 0.0;
    for (auto it = index_->walls.qbegin(bgi::nearest(q, k)); it != index_->walls.qend(); ++it, ++seen) {
      lastLower = std::max(lastLower, bg::distance(q, it->first));
      best = std::min(best, distanceToSegment(walls_[it->second], p));
    }
    if (seen < k || lastLower > best) return best;
    best = std::numeric_limits<double>::infinity();
  }
  const BBox q = boxAround(p, within);
  for (auto it = index_->walls.qbegin(bgi::intersects(q)); it != index_->walls.qend(); ++it)
    best = std::min(best, distanceToSegment(walls_[it->second], p));
  return best;
}

bool Region::nearestWallPoint(Vec2 p, double within, Vec2& point, double& distance, int* wall) const {
  const BBox q = boxAround(p, within);
  distance = std::numeric_limits<double>::infinity();
  for (auto it = index_->walls.qbegin(bgi::intersects(q)); it != index_->walls.qend(); ++it) {
    const Vec2 c = closestPointOnSegment(walls_[it->second], p);
    const double d = dist(c, p);
    if (d < distance) {
      distance = d;
      point = c;
      if (wall) *wall = it->second;
    }
  }
  return std::isfinite(distance);
}

bool Region::diskFits(Vec2 c, double clearance, double tol) const {
  return wallDistance(c, clearance) >= clearance - tol && contains(c);
}

std::vector<int> Region::wallsNear(Vec2 p, double radius) const {
  return wallsInBox({p.x - radius, p.y - radius}, {p.x + radius, p.y + radius});
}

namespace {

// The k of `items` nearest to p by `distance`, in their first order.
template <class Distance>
std::vector<int> keepNearest(std::vector<int> items, size_t k, Distance distance) {
  if (items.size() <= k) return items;
  std::vector<std::pair<double, int>> byDistance;
  for (int i : items) byDistance.emplace_back(distance(i), i);
  std::nth_element(byDistance.begin(), byDistance.begin() + static_cast<long>(k), byDistance.end());
  byDistance.resize(k);
  std::sort(byDistance.begin(), byDistance.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  items.clear();
  for (const auto& d : byDistance) items.push_back(d.second);
  return items;
}

}  // namespace

std::vector<int> Region::nearestWallsNear(Vec2 p, double radius, size_t k) const {
  return keepNearest(wallsNear(p, radius), k, [&](int w) { return distanceToSegment(walls_[w], p); });
}

std::vector<int> Region::nearestReflexVerticesNear(Vec2 p, double radius, size_t k) const {
  return keepNearest(reflexVerticesNear(p, radius), k, [&](int v) { return dist(vertices_[v].p, p); });
}

std::vector<int> Region::wallsInBox(Vec2 lo, Vec2 hi) const {
  std::vector<int> out;
  const BBox q = boxOf(lo, hi);
  for (auto it = index_->walls.qbegin(bgi::intersects(q)); it != index_->walls.qend(); ++it)
    out.push_back(it->second);
  return out;
}

std::vector<int> Region::reflexVerticesNear(Vec2 p, double radius) const {
  const BBox q = boxAround(p, radius);
  std::vector<int> out;
  for (auto it = index_->reflex.qbegin(bgi::intersects(q)); it != index_->reflex.qend(); ++it)
    out.push_back(it->second);
  return out;
}

std::optional<Region> simplifiedRegion(const Region& region, size_t maxVertices, double maxTolerance,
                                       double& tolerance) {
  tolerance = 0.0;
  if (region.vertices().size() <= maxVertices) return std::nullopt;
  using Line = bg::model::linestring<BPoint>;
  for (double t = 1e-3; t <= maxTolerance * (1 + 1e-9); t *= 2) {
    std::vector<Loop> loops;
    size_t count = 0;
    for (const Loop& loop : region.loops()) {
      // Open at the first vertex (kept, as both ends of a line are).
      Line line, out;
      for (const Vec2& p : loop) line.emplace_back(p.x, p.y);
      line.emplace_back(loop.front().x, loop.front().y);
      bg::simplify(line, out, t);
      Loop l;
      for (size_t k = 0; k + 1 < out.size(); ++k) l.push_back({bg::get<0>(out[k]), bg::get<1>(out[k])});
      if (l.size() < 3) l = loop;  // a loop smaller than the tolerance stays as it is
      count += l.size();
      loops.push_back(std::move(l));
    }
    if (count > maxVertices && t * 2 <= maxTolerance * (1 + 1e-9)) continue;
    try {
      Region out(loops.front(), std::vector<Loop>(loops.begin() + 1, loops.end()));
      tolerance = t;
      return out;
    } catch (const Error&) {
      return std::nullopt;  // walls simplified into each other: plan on the original ones
    }
  }
  return std::nullopt;
}

}  // namespace plunge
