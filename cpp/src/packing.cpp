#include "packing.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <limits>
#include <tuple>

#include "detail.hpp"
#include "plunge/error.hpp"

namespace plunge {

using namespace detail;

namespace {

constexpr double kParamTol = 1e-9;  // tangent point may sit this far past a wall's end (relative)

Vec2 unitLeft(const Segment& s) {
  const Vec2 d = s.b - s.a;
  return leftNormal(d) * (1.0 / norm(d));
}

bool paramInside(double t) { return t >= -kParamTol && t <= 1.0 + kParamTol; }

}  // namespace

std::vector<Vec2> cornerPlacementsWallWall(const Segment& a, const Segment& b, double clearance) {
  // Both walls offset by the clearance towards the material (eqs. 4.18-4.26);
  // the corner placement is where the offset lines cross.
  const Vec2 da = a.b - a.a, db = b.b - b.a;
  const Vec2 pa = a.a + unitLeft(a) * clearance, pb = b.a + unitLeft(b) * clearance;
  const auto x = intersectLines(pa, da, pb, db);
  if (!x) return {};
  const double ta = dot(*x - pa, da) / dot(da, da), tb = dot(*x - pb, db) / dot(db, db);
  if (!paramInside(ta) || !paramInside(tb)) return {};
  return {*x};
}

std::vector<Vec2> cornerPlacementsWallCircle(const Segment& wall, double clearance, const Circle& locus) {
  // Offset wall line crossed with the offset circle (eqs. 4.27-4.38).
  const Vec2 d = wall.b - wall.a;
  const Vec2 p = wall.a + unitLeft(wall) * clearance;
  std::vector<Vec2> out;
  for (double t : intersectLineCircle(p, d, locus))
    if (paramInside(t)) out.push_back(p + d * t);
  return out;
}

std::vector<Vec2> cornerPlacementsCircleCircle(const Circle& locusA, const Circle& locusB) {
  return intersectCircles(locusA, locusB);  // eqs. 4.39-4.54
}

double contactDistance(const PackedDisk& a, const PackedDisk& b) {
  if (a.radius > b.radius) return a.radius + b.contactRadius;
  if (b.radius > a.radius) return b.radius + a.contactRadius;
  return a.contactRadius + b.contactRadius;
}

double wallRowSpacing(double r, double band) {
  if (!(band > 0.0)) return 0.0;
  const double h = std::min(band, r);
  // 5 % closer than on a straight wall: on walls curving round the material
  // (convex pockets, around islands) the scallops between row disks grow.
  return 0.95 * 2.0 * std::sqrt(2.0 * r * h - h * h);
}

double wallRowInset(double r, double rho, double band) {
  if (!(band > 0.0)) return 0.0;
  // Inner disks meet each other at 2 rho, so between two of them the cut reaches
  // sqrt(r^2 - rho^2) below their centres; the row cuts everything up to r - band
  // above its own centres. 2 % closer for curved walls and rounding.
  return 0.98 * std::max(0.0, r - band + std::sqrt(std::max(0.0, r * r - rho * rho)));
}

double holeDegree(double dMin, double r) { return 1.0 - std::clamp(dMin, 0.0, r) / r; }

namespace {

struct Site {
  enum Kind { Wall, Vertex, Disk } kind;
  int index;
  bool operator==(const Site& o) const { return kind == o.kind && index == o.index; }
};

class Packer {
 public:
  Packer(const Region& region, const PackingOptions& opt) : region_(region), opt_(opt) {}

  void packPhase(int tool, double radius) {
    tool_ = tool;
    r_ = radius;
    c_ = radius + opt_.allowance;
    rho_ = radius * opt_.contactRatio;
    // A wall-row pass (a band): disks of this phase meet at the band's chord,
    // or at the usual contact where that is closer (a band deep into the disk).
    row_ = opt_.maxWallStock > 0.0 ? std::min(wallRowSpacing(radius, opt_.maxWallStock), 2 * rho_) : 0.0;
    proto_ = {{}, r_, rho_, tool_};
    cands_.clear();
    candIndex_.clear();
    queue_.clear();
    seedCandidates();
    while (!queue_.empty()) {
      opt_.progress.tick();
      const int id = std::get<3>(*queue_.begin());
      if (opt_.order == PackingOrder::Lattice && !hasLattice_) anchorLattice(cands_[id]);
      place(cands_[id].p);
    }
  }

  std::vector<PackedDisk> disks;

 private:
  struct Candidate {
    Vec2 p;
    Site g1, g2;
    double dMin;
    bool alive;
  };

  bool touchesWall(Vec2 p) const { return region_.wallDistance(p, c_ + 1e-6) <= c_ + 1e-6; }

  // Centre distance at which a new disk meets disk k. In a wall-row pass every
  // disk touches a wall, and those of this phase meet at the row spacing.
  double need(int k) const {
    if (row_ > 0 && disks[k].tool == tool_) return row_;
    return contactDistance(disks[k], proto_);
  }
  // Max hole degree first; ties by lowest y then x, so equal-degree placements grow
  // row by row; then creation order.
  using Key = std::tuple<long long, double, double, int>;

  Key keyOf(int id) const {
    const Candidate& c = cands_[id];
    const long long lambda = std::llround(holeDegree(c.dMin, r_) * 1e9);
    if (opt_.order == PackingOrder::HoleDegree || !hasLattice_) return {-lambda * 1000, c.p.y, c.p.x, id};
    // Lattice order: placements on the lattice first, then by hole degree, then
    // by distance to the lattice (in steps of 0.5 % of the contact radius).
    const double steps = std::floor(latticeDistance(c.p) / (0.005 * rho_));
    const long long step = static_cast<long long>(std::min(steps, 999.0));
    return {(step > 0 ? (1LL << 50) : 0) - lambda * 1000 + step, c.p.y, c.p.x, id};
  }

  // Distance to the nearest point of the hexagonal lattice of spacing 2 rho
  // anchored at the first circle, rows along latDir_.
  double latticeDistance(Vec2 p) const {
    const Vec2 d = p - latOrigin_;
    const double x = dot(d, latDir_), y = dot(d, leftNormal(latDir_));
    const double h = std::sqrt(3.0) * rho_;
    const double row = std::round(y / h);
    double best = std::numeric_limits<double>::infinity();
    for (double j = row - 1; j <= row + 1; ++j) {
      const double shift = j * rho_;  // odd rows sit in the pockets of even ones
      const double col = std::round((x - shift) / (2 * rho_));
      for (double i = col - 1; i <= col + 1; ++i) best = std::min(best, std::hypot(x - shift - 2 * rho_ * i, y - j * h));
    }
    return best;
  }

  // The lattice follows the longer wall the first circle touches.
  void anchorLattice(const Candidate& first) {
    hasLattice_ = true;
    latOrigin_ = first.p;
    latDir_ = {1, 0};
    double longest = 0;
    for (const Site* g : {&first.g1, &first.g2})
      if (g->kind == Site::Wall) {
        const Segment& w = region_.walls()[g->index];
        if (dist(w.a, w.b) > longest) {
          longest = dist(w.a, w.b);
          latDir_ = (w.b - w.a) * (1.0 / longest);
        }
      }
    std::set<Key> rekeyed;
    for (const Key& k : queue_) rekeyed.insert(keyOf(std::get<3>(k)));
    queue_.swap(rekeyed);
  }

  Circle locus(const Site& s) const {
    if (s.kind == Site::Vertex) return {region_.vertices()[s.index].p, c_};
    return {disks[s.index].center, contactDistance(disks[s.index], proto_)};
  }

  // Cheap rejections before the full feasibility test: a disk touching a reflex
  // vertex must lie in the vertex's normal cone, or a neighbouring wall is closer.
  bool vertexConeOk(const Site& s, Vec2 p) const {
    if (s.kind != Site::Vertex) return true;
    const auto& v = region_.vertices()[s.index];
    const Segment& in = region_.walls()[v.prevWall];
    const Segment& out = region_.walls()[v.nextWall];
    const Vec2 u = p - v.p;
    const double nu = norm(u);
    return dot(u, in.b - in.a) >= -1e-9 * nu * norm(in.b - in.a) &&
           dot(u, out.b - out.a) <= 1e-9 * nu * norm(out.b - out.a);
  }

  bool disksClear(Vec2 p) const {
    for (auto it = diskIndex_.qbegin(bgi::intersects(boxAround(p, rho_ + maxReach_))); it != diskIndex_.qend(); ++it)
      if (dist(p, disks[it->second].center) < need(it->second) - kTol) return false;
    return true;
  }

  bool feasible(Vec2 p) const {
    return region_.wallDistance(p, c_) >= c_ - kTol && disksClear(p) && region_.contains(p);
  }

  Vec2 tangentPoint(const Site& s, Vec2 p) const {
    if (s.kind == Site::Wall) return closestPointOnSegment(region_.walls()[s.index], p);
    return region_.vertices()[s.index].p;
  }

  // d_min of eq. 4.68: gap to the nearest item other than the two tangent ones.
  double dMinOf(Vec2 p, const Site& g1, const Site& g2) const {
    double best = r_;
    std::vector<Vec2> touch;
    for (const Site* g : {&g1, &g2})
      if (g->kind != Site::Disk) touch.push_back(tangentPoint(*g, p));
    for (int w : region_.wallsNear(p, c_ + r_)) {
      if ((g1.kind == Site::Wall && g1.index == w) || (g2.kind == Site::Wall && g2.index == w)) continue;
      const Vec2 q = closestPointOnSegment(region_.walls()[w], p);
      // The same wall point reached through a neighbouring segment is not another item.
      bool same = false;
      for (const Vec2& t : touch) same = same || dist(q, t) <= 1e-7;
      if (same) continue;
      best = std::min(best, dist(p, q) - c_);
    }
    const double reach = rho_ + maxReach_ + r_;
    for (auto it = diskIndex_.qbegin(bgi::intersects(boxAround(p, reach))); it != diskIndex_.qend(); ++it) {
      const int k = it->second;
      if ((g1.kind == Site::Disk && g1.index == k) || (g2.kind == Site::Disk && g2.index == k)) continue;
      best = std::min(best, dist(p, disks[k].center) - need(k));
    }
    return std::max(best, 0.0);
  }

  void addCandidate(Vec2 p, const Site& a, const Site& b) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
    if (row_ > 0 && !touchesWall(p)) return;  // a wall-row pass places rows only
    if (!vertexConeOk(a, p) || !vertexConeOk(b, p) || !feasible(p)) return;
    const int id = static_cast<int>(cands_.size());
    cands_.push_back({p, a, b, dMinOf(p, a, b), true});
    candIndex_.insert({toBPoint(p), id});
    queue_.insert(keyOf(id));
  }

  void addPair(const Site& a, const Site& b) {
    const auto& walls = region_.walls();
    std::vector<Vec2> pts;
    const Site& w = a.kind == Site::Wall ? a : b;
    const Site& o = a.kind == Site::Wall ? b : a;
    if (a.kind == Site::Wall && b.kind == Site::Wall)
      pts = cornerPlacementsWallWall(walls[a.index], walls[b.index], c_);
    else if (w.kind == Site::Wall && o.kind == Site::Disk && row_ > 0 && disks[o.index].tool == tool_)
      // The next disk of a wall row: on the wall, at the row spacing from a row disk.
      pts = cornerPlacementsWallCircle(walls[w.index], c_, {disks[o.index].center, row_});
    else if (w.kind == Site::Wall)
      pts = cornerPlacementsWallCircle(walls[w.index], c_, locus(o));
    else
      pts = cornerPlacementsCircleCircle(locus(a), locus(b));
    for (const Vec2& p : pts) addCandidate(p, a, b);
  }

  bool isEndpointOf(int vertex, int wall) const {
    const auto& v = region_.vertices()[vertex];
    return v.prevWall == wall || v.nextWall == wall;
  }

  // Pairs of disk k with every wall, reflex vertex and disk in reach (with
  // `laterOnly`, only disks of higher index, so that seeding makes each pair once).
  void pairDisk(int k, bool laterOnly) {
    const Site s{Site::Disk, k};
    const Vec2 at = disks[k].center;
    const double siteReach = contactDistance(disks[k], proto_);  // the locus radius
    for (int w : region_.wallsNear(at, siteReach + c_)) addPair(s, {Site::Wall, w});
    for (int v : region_.reflexVerticesNear(at, siteReach + c_)) addPair(s, {Site::Vertex, v});
    std::vector<int> near;
    for (auto it = diskIndex_.qbegin(bgi::intersects(boxAround(at, siteReach + rho_ + maxReach_)));
         it != diskIndex_.qend(); ++it)
      if (it->second != k && (!laterOnly || it->second > k)) near.push_back(it->second);
    std::sort(near.begin(), near.end());
    for (int o : near) addPair(s, {Site::Disk, o});
  }

  void seedCandidates() {
    const auto& walls = region_.walls();
    for (size_t w = 0; w < walls.size(); ++w) {
      const Segment& s = walls[w];
      const Vec2 lo{std::min(s.a.x, s.b.x) - 2 * c_, std::min(s.a.y, s.b.y) - 2 * c_};
      const Vec2 hi{std::max(s.a.x, s.b.x) + 2 * c_, std::max(s.a.y, s.b.y) + 2 * c_};
      const Site site{Site::Wall, static_cast<int>(w)};
      for (int o : region_.wallsInBox(lo, hi))
        if (o > static_cast<int>(w)) addPair(site, {Site::Wall, o});
      const Vec2 mid = (s.a + s.b) * 0.5;
      for (int v : region_.reflexVerticesNear(mid, 0.5 * norm(s.b - s.a) + 2 * c_))
        if (!isEndpointOf(v, static_cast<int>(w))) addPair(site, {Site::Vertex, v});
    }
    for (size_t v = 0; v < region_.vertices().size(); ++v) {
      if (!region_.vertices()[v].reflex) continue;
      for (int u : region_.reflexVerticesNear(region_.vertices()[v].p, 2 * c_))
        if (u > static_cast<int>(v)) addPair({Site::Vertex, static_cast<int>(v)}, {Site::Vertex, u});
    }
    for (size_t k = 0; k < disks.size(); ++k) pairDisk(static_cast<int>(k), true);
  }

  void place(Vec2 p) {
    const int k = static_cast<int>(disks.size());
    PackedDisk d = proto_;
    d.center = p;
    disks.push_back(d);
    diskIndex_.insert({toBPoint(p), k});
    maxReach_ = std::max(maxReach_, r_);
    // Candidates now overlapping die; those nearby may see a smaller d_min.
    std::vector<PointValue> hits;
    candIndex_.query(bgi::intersects(boxAround(p, 2 * rho_ + r_)), std::back_inserter(hits));
    for (const PointValue& h : hits) {
      Candidate& c = cands_[h.second];
      if (!c.alive) continue;
      const double gap = dist(c.p, p) - need(k);
      if (gap < -kTol) {
        queue_.erase(keyOf(h.second));
        c.alive = false;
      } else if (gap < c.dMin) {
        queue_.erase(keyOf(h.second));
        c.dMin = std::max(gap, 0.0);
        queue_.insert(keyOf(h.second));
      }
    }
    pairDisk(k, false);
  }

  const Region& region_;
  PackingOptions opt_;
  PackedDisk proto_;  // the circle of this phase
  int tool_ = 0;
  double r_ = 0, c_ = 0, rho_ = 0, maxReach_ = 0;  // maxReach_: largest radius placed
  double row_ = 0;  // wall-row pass: the row spacing of this phase (0: a plain packing)
  bool hasLattice_ = false;  // anchored at the first circle of the largest tool
  Vec2 latOrigin_, latDir_;
  std::vector<Candidate> cands_;
  QuadraticTree<PointValue> candIndex_;
  QuadraticTree<PointValue> diskIndex_;
  std::set<Key> queue_;
};

}  // namespace

std::vector<PackedDisk> packWithWallBand(const Region& region, double radius, const PackingOptions& options) {
  if (!(options.maxWallStock > 0.0)) return packMaxHoleDegree(region, {radius}, options);
  // The rows: a pass that only places disks touching the walls, at the band's chord.
  std::vector<PackedDisk> disks = packMaxHoleDegree(region, {radius}, options);
  // Inside them, the plain packing kept off the walls by the inset.
  PackingOptions inner = options;
  inner.maxWallStock = 0.0;
  inner.allowance += wallRowInset(radius, radius * options.contactRatio, options.maxWallStock);
  for (const PackedDisk& d : packMaxHoleDegree(region, {radius}, inner)) disks.push_back(d);
  return disks;
}

std::vector<PackedDisk> packMaxHoleDegree(const Region& region, const std::vector<double>& radii,
                                          const PackingOptions& options) {
  if (!(options.contactRatio > 0.0 && options.contactRatio <= 1.0))
    throw Error("packing contact ratio must be in (0, 1]");
  if (!(options.allowance >= 0.0) || !std::isfinite(options.allowance))
    throw Error("radial allowance must be a finite number >= 0");
  if (options.order == PackingOrder::Auto)
    throw Error("packing order: auto is the plan's choice between hole_degree and lattice");
  std::vector<int> order(radii.size());
  std::iota(order.begin(), order.end(), 0);
  for (double r : radii)
    if (!(r > 0.0) || !std::isfinite(r)) throw Error("tool radius must be a finite number > 0");
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return radii[a] > radii[b]; });
  Packer packer(region, options);
  for (int t : order) packer.packPhase(t, radii[t]);
  return packer.disks;
}

}  // namespace plunge
