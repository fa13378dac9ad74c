#include "covering.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <functional>
#include <cmath>
#include <iterator>
#include <map>
#include <numeric>
#include <queue>
#include <unordered_map>

#include "clip.hpp"
#include "polygon.hpp"
#include "detail.hpp"
#include "plunge/error.hpp"

namespace plunge {

using namespace detail;

namespace {

// Disks become polygons with this chord error. The coverage that is reported
// uses inscribed polygons (never overestimated); planning uses circumscribed
// ones, so that a disk touching a wall splits the material on either side
// instead of leaving a sliver that joins every cusp along the wall.
constexpr double kDiskChord = 0.005;
constexpr double kCoreOutlineTolerance = 0.01;  // mm, see coreRegion
constexpr double kBandMargin = 0.05;             // mm, see Coverer::run
// Corner placements pair the walls nearest a point, at most this many: with a
// tool as large as the pocket every wall is "in reach" and all pairs would take minutes.
constexpr size_t kCornerWalls = 64;
// A piece of material with more vertices than this, wider than a cell of
// 4 rMax, is kept cut into parts (Coverer::addSplit): Clipper's sweep costs the
// edges every scanline crosses, so each plunge cut from a long strip along a
// wall (thousands of vertices, all crossed by every scanline when it runs
// along x) would cost the whole strip squared.
constexpr size_t kSplitVertices = 1000;
// Pieces with more vertices are cut into cells once, for gainOf (long strips
// along the walls: each evaluation then clips only the cells in reach).
constexpr size_t kChunkVertices = 300;
// Pieces of material below the crumb are neither covered nor pins: with a
// wall band (a core covered whole) kCoreCrumb mm^2, the polygons' slivers;
// otherwise kCrumbShare of the smallest tool's r^2.
constexpr double kCoreCrumb = 0.004;
constexpr double kCrumbShare = 0.01;
// Halvings of a gap larger than the largest tool (encloseGap), and of a piece
// into the anchors of its candidates (anchorsOf).
constexpr int kGapSplits = 8;
constexpr int kAnchorSplits = 6;

// `area` minus the disks. Done tile by tile: Clipper's sweep slows down with
// the number of edges a scanline crosses, and the uncovered part is small, so
// merging the tiles' results again costs little.
clip::Paths subtractDisks(const clip::Paths& area, const std::vector<Circle>& disks, bool circumscribed) {
  if (area.empty()) return {};
  Vec2 lo, hi;
  clip::bounds(area, lo, hi);
  double rMax = 0.0;
  for (const Circle& c : disks) rMax = std::max(rMax, c.r);
  const double tile = std::max(10.0 * rMax, 1.0);
  const int nx = std::max(1, static_cast<int>(std::ceil((hi.x - lo.x) / tile)));
  const int ny = std::max(1, static_cast<int>(std::ceil((hi.y - lo.y) / tile)));
  std::vector<clip::Paths> bucket(static_cast<size_t>(nx) * ny);
  for (const Circle& c : disks) {
    const int x0 = std::clamp(static_cast<int>((c.c.x - c.r - lo.x) / tile), 0, nx - 1);
    const int x1 = std::clamp(static_cast<int>((c.c.x + c.r - lo.x) / tile), 0, nx - 1);
    const int y0 = std::clamp(static_cast<int>((c.c.y - c.r - lo.y) / tile), 0, ny - 1);
    const int y1 = std::clamp(static_cast<int>((c.c.y + c.r - lo.y) / tile), 0, ny - 1);
    const clip::Path p = clip::diskPath(c, kDiskChord, circumscribed);
    for (int j = y0; j <= y1; ++j)
      for (int i = x0; i <= x1; ++i) bucket[static_cast<size_t>(j) * nx + i].push_back(p);
  }
  clip::Paths left;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      // Tiles share their edges exactly, so the final union welds the pieces again.
      const Vec2 a{lo.x + i * tile, lo.y + j * tile};
      const Vec2 b{i == nx - 1 ? hi.x + 1.0 : a.x + tile, j == ny - 1 ? hi.y + 1.0 : a.y + tile};
      const clip::Path rect{clip::toInt(a), clip::toInt({b.x, a.y}), clip::toInt(b), clip::toInt({a.x, b.y})};
      const clip::Paths part = clip::boolean(area, {rect}, ClipperLib::ctIntersection);
      if (part.empty()) continue;
      for (clip::Path& q : clip::boolean(part, bucket[static_cast<size_t>(j) * nx + i], ClipperLib::ctDifference))
        left.push_back(std::move(q));
    }
  return clip::boolean(left, {}, ClipperLib::ctUnion);
}

std::vector<Vec2> verticesOf(const clip::Paths& p) {
  std::vector<Vec2> out;
  for (const clip::Path& q : p)
    for (const clip::IntPoint& v : q) out.push_back(clip::toMm(v));
  return out;
}

// A point inside a polygon set: the middle of the widest inside span of a
// horizontal line through the middle of its bounding box.
Vec2 interiorPoint(const clip::Paths& p) {
  Vec2 lo, hi;
  clip::bounds(p, lo, hi);
  const double y = lo.y + (hi.y - lo.y) * 0.5000123;  // off any vertex in practice
  std::vector<double> xs;
  for (const clip::Path& q : p)
    for (size_t i = 0, j = q.size() - 1; i < q.size(); j = i++) {
      if (const std::optional<double> x = crossingX(clip::toMm(q[j]), clip::toMm(q[i]), y)) xs.push_back(*x);
    }
  std::sort(xs.begin(), xs.end());
  Vec2 best{(lo.x + hi.x) * 0.5, y};
  double width = -1.0;
  for (size_t i = 0; i + 1 < xs.size(); i += 2)
    if (xs[i + 1] - xs[i] > width) {
      width = xs[i + 1] - xs[i];
      best = {(xs[i] + xs[i + 1]) * 0.5, y};
    }
  return best;
}

bool inTriangle(Vec2 p, Vec2 a, Vec2 b, Vec2 c) {
  const double d1 = cross(b - a, p - a), d2 = cross(c - b, p - b), d3 = cross(a - c, p - c);
  const bool neg = d1 < 0 || d2 < 0 || d3 < 0, pos = d1 > 0 || d2 > 0 || d3 > 0;
  return !(neg && pos);
}

// The components of p on either side of a cut through `at` across p's longer side.
std::vector<clip::Paths> splitInHalves(const clip::Paths& p, Vec2 at) {
  Vec2 lo, hi;
  clip::bounds(p, lo, hi);
  lo = lo - Vec2{1, 1};
  hi = hi + Vec2{1, 1};
  auto rect = [](Vec2 l, Vec2 h) {
    return clip::Path{clip::toInt(l), clip::toInt({h.x, l.y}), clip::toInt(h), clip::toInt({l.x, h.y})};
  };
  const bool cutX = (hi.x - lo.x) >= (hi.y - lo.y);
  const clip::Path h1 = cutX ? rect(lo, {at.x, hi.y}) : rect(lo, {hi.x, at.y});
  const clip::Path h2 = cutX ? rect({at.x, lo.y}, hi) : rect({lo.x, at.y}, hi);
  std::vector<clip::Paths> out;
  for (const clip::Path& h : {h1, h2})
    for (clip::Paths& part : clip::components(clip::boolean(p, {h}, ClipperLib::ctIntersection)))
      out.push_back(std::move(part));
  return out;
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

Polygons allowedRegion(const Region& region, double allowance) {
  if (allowance <= 0.0) return poly::unite(region.polygons());
  return poly::offset(region.polygons(), -allowance);
}

Polygons accessibleRegion(const Region& region, double minRadius, double allowance) {
  // Opening: erode by the tool (and allowance), dilate by the tool again.
  const clip::Paths eroded = clip::offset(clip::toPaths(region.polygons()), -(minRadius + allowance));
  if (eroded.empty()) return {};
  return clip::toPolygons(clip::offset(eroded, minRadius));
}

Polygons coreRegion(const Region& region, const Polygons& accessible, double allowance, double maxWallStock) {
  const clip::Paths inner = clip::offset(clip::toPaths(region.polygons()), -(allowance + maxWallStock));
  if (inner.empty()) return {};
  // Not the last hundredth of a millimetre of the accessible outline: there the
  // outline's polygon and the disks' polygons differ by their chord errors, in
  // corners the smallest tool just reaches.
  const clip::Paths reach = clip::offset(clip::toPaths(accessible), -kCoreOutlineTolerance);
  return clip::toPolygons(clip::boolean(reach, inner, ClipperLib::ctIntersection));
}

Polygons uncoveredRegion(const Polygons& area, const std::vector<Circle>& disks) {
  return clip::toPolygons(subtractDisks(clip::toPaths(area), disks, false));
}

DelaunayGaps delaunayGaps(const std::vector<PackedDisk>& packed) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
  using Tds = CGAL::Triangulation_data_structure_2<Vb>;
  using DT = CGAL::Delaunay_triangulation_2<K, Tds>;
  DelaunayGaps out;
  if (packed.size() < 3) return out;
  std::vector<std::pair<K::Point_2, int>> pts;
  for (size_t i = 0; i < packed.size(); ++i)
    pts.emplace_back(K::Point_2(packed[i].center.x, packed[i].center.y), static_cast<int>(i));
  DT dt(pts.begin(), pts.end());
  if (dt.dimension() < 2) return out;

  auto touching = [&](int a, int b) {
    return dist(packed[a].center, packed[b].center) <=
           packed[a].contactRadius + packed[b].contactRadius + 1e-6;
  };
  std::map<DT::Face_handle, int> id;
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    GapTriangle t;
    for (int i = 0; i < 3; ++i) t.v[i] = f->vertex(i)->info();
    // Thesis fig. 4.17: closed when L = R1 + R2 on every edge.
    t.closed = touching(t.v[0], t.v[1]) && touching(t.v[1], t.v[2]) && touching(t.v[2], t.v[0]);
    id[f] = static_cast<int>(out.triangles.size());
    out.triangles.push_back(t);
  }
  // Merge open triangles across their shared open edges (fig. 4.18).
  UnionFind uf(static_cast<int>(out.triangles.size()));
  for (const auto& [f, i] : id) {
    if (out.triangles[i].closed) continue;
    for (int e = 0; e < 3; ++e) {
      const auto g = f->neighbor(e);
      if (dt.is_infinite(g)) continue;
      const int j = id.at(g);
      if (out.triangles[j].closed) continue;
      if (!touching(f->vertex(DT::cw(e))->info(), f->vertex(DT::ccw(e))->info())) uf.unite(i, j);
    }
  }
  std::map<int, int> groupOf;
  for (size_t i = 0; i < out.triangles.size(); ++i) {
    const int root = uf.find(static_cast<int>(i));
    auto it = groupOf.find(root);
    if (it == groupOf.end()) {
      it = groupOf.emplace(root, static_cast<int>(out.groups.size())).first;
      out.groups.emplace_back();
    }
    out.groups[it->second].push_back(static_cast<int>(i));
  }
  return out;
}

namespace {

// The material the covering still has to cut: pieces of polygon (a large one
// halved until each part is small), an R-tree of their boxes, which are pins
// (touching no edge of the accessible region: free-standing material), and the
// area a disk would cut from them.
class MaterialPieces {
 public:
  struct Chunk {
    clip::Paths poly;
    Vec2 lo, hi;
    double area;
  };
  struct Piece {
    clip::Paths poly;
    Vec2 lo, hi;
    double area;
    bool pin;  // touches no edge of the accessible region: a free-standing core of material
    bool alive;
    mutable bool chunked = false;        // chunks computed (empty for small pieces)
    mutable std::vector<Chunk> chunks;  // a large piece cut into cells, for gainOf
  };
  // rMin, rMax: the tools' radii; core: covering a core whole (every piece a
  // pin); crumb: pieces below it count neither as pins nor for candidates.
  MaterialPieces(double rMin, double rMax, bool core, double crumb)
      : rMin_(rMin), rMax_(rMax), crumb_(crumb), core_(core) {}
  // The accessible region's outline: pieces touching it are no pins.
  void setOutline(const clip::Paths& accessible) {
    std::vector<BoxValue> boxes;
    for (const clip::Path& q : accessible)
      for (size_t i = 0, j = q.size() - 1; i < q.size(); j = i++) {
        const Vec2 a = clip::toMm(q[j]), b = clip::toMm(q[i]);
        boundary_.push_back({a, b});
        boxes.emplace_back(boxOf(boundary_.back()), static_cast<int>(boundary_.size() - 1));
      }
    boundaryIndex_ = decltype(boundaryIndex_)(boxes.begin(), boxes.end());
  }
  // Called with each piece added from now on.
  void onAdded(std::function<void(int)> f) { onAdded_ = std::move(f); }
  // Pins no plunge can reach (slivers of the polygon approximation) count no more.
  void givePinsUp() {
    for (Piece& p : pieces_)
      if (p.alive && p.pin && p.area >= crumb_) p.pin = false;
    pins_ = 0;
  }
  const Piece& operator[](int id) const { return pieces_[id]; }
  const std::vector<Piece>& all() const { return pieces_; }
  double uncovered() const { return uncovered_; }
  int pins() const { return pins_; }

  // A piece of material to cover (split when large).
  void add(clip::Paths poly) {
    const bool pin = core_ || !touchesBoundary(poly);
    addSplit(std::move(poly), pin);
  }

  void kill(int id) {
    Piece& p = pieces_[id];
    p.alive = false;
    uncovered_ -= p.area;
    if (p.pin && p.area >= crumb_) --pins_;
    pieceIndex_.remove({boxOf(p.lo, p.hi), id});
  }

  std::vector<int> near(Vec2 lo, Vec2 hi) const {
    std::vector<BoxValue> hits;
    pieceIndex_.query(bgi::intersects(boxOf(lo, hi)), std::back_inserter(hits));
    std::vector<int> out;
    for (const auto& h : hits) out.push_back(h.second);
    std::sort(out.begin(), out.end());
    return out;
  }

  // Cuts a disk (its polygon, within lo..hi) out of the pieces it touches.
  void cut(const clip::Paths& disk, Vec2 lo, Vec2 hi) {
    for (int id : near(lo, hi)) {
      clip::Paths rest = clip::boolean(pieces_[id].poly, disk, ClipperLib::ctDifference);
      if (clip::area(rest) >= pieces_[id].area) continue;  // untouched: keep it and its candidates
      kill(id);
      for (clip::Paths& part : clip::components(rest)) add(std::move(part));
    }
  }

  // Uncovered area a disk would cut. Large pieces (long strips along walls) are
  // cut once into cells, so that each evaluation clips only the cells in reach.
  double gainOf(Vec2 c, double r) const {
    // Coarse but inscribed: inside the polygon addDisk cuts with, so a disk is only
    // placed when it really removes what it was ranked by (no endless re-placing of
    // a disk whose gain was a polygon artefact).
    const clip::Paths disk{clip::diskPath({c, r}, 4 * kDiskChord, false)};
    const Vec2 lo{c.x - r, c.y - r}, hi{c.x + r, c.y + r};
    auto clipped = [&](const clip::Paths& poly, double area, Vec2 plo, Vec2 phi) {
      const bool within = dist(c, plo) <= r && dist(c, phi) <= r && dist(c, {plo.x, phi.y}) <= r &&
                          dist(c, {phi.x, plo.y}) <= r;
      return within ? area : clip::area(clip::boolean(poly, disk, ClipperLib::ctIntersection));
    };
    double g = 0.0;
    for (int id : near(lo, hi)) {
      const Piece& p = pieces_[id];
      if (!p.chunked) chunk(p);
      if (p.chunks.empty()) {
        g += clipped(p.poly, p.area, p.lo, p.hi);
        continue;
      }
      for (const Chunk& k : p.chunks)
        if (k.lo.x <= hi.x && k.hi.x >= lo.x && k.lo.y <= hi.y && k.hi.y >= lo.y) g += clipped(k.poly, k.area, k.lo, k.hi);
    }
    return g;
  }

 private:
  // (Queries collect their hits: GCC 16 warns falsely about Boost's
  // incremental query iterators inlined here, -Warray-bounds.)
  bool touchesBoundary(const clip::Paths& p) const {
    constexpr double tol = 3.0 / poly::kScale;
    std::vector<BoxValue> hits;
    for (const clip::Path& q : p)
      for (const clip::IntPoint& v : q) {
        const Vec2 m = clip::toMm(v);
        const BBox b = boxOf({m.x - tol, m.y - tol}, {m.x + tol, m.y + tol});
        hits.clear();
        boundaryIndex_.query(bgi::intersects(b), std::back_inserter(hits));
        for (const auto& h : hits)
          if (distanceToSegment(boundary_[h.second], m) <= tol) return true;
      }
    return false;
  }

  // A large piece (kSplitVertices) is cut in halves across its longer side
  // until each part has few vertices or fits in a cell of 4 rMax. The cuts
  // are no walls: the parts keep the piece's pin state.
  void addSplit(clip::Paths poly, bool pin) {
    size_t vertices = 0;
    for (const clip::Path& q : poly) vertices += q.size();
    Vec2 lo, hi;
    clip::bounds(poly, lo, hi);
    const double cell = 4 * rMax_;
    if (vertices <= kSplitVertices || (hi.x - lo.x <= cell && hi.y - lo.y <= cell)) {
      addPart(std::move(poly), lo, hi, pin);
      return;
    }
    for (clip::Paths& part : splitInHalves(poly, 0.5 * (lo + hi))) addSplit(std::move(part), pin);
  }

  void addPart(clip::Paths poly, Vec2 lo, Vec2 hi, bool pin) {
    Piece p;
    p.area = clip::area(poly);
    if (p.area <= 0.0) return;
    p.lo = lo;
    p.hi = hi;
    p.pin = pin;
    p.alive = true;
    p.poly = std::move(poly);
    uncovered_ += p.area;
    const int id = static_cast<int>(pieces_.size());
    pieceIndex_.insert({boxOf(p.lo, p.hi), id});
    pieces_.push_back(std::move(p));
    if (pieces_.back().pin && pieces_.back().area >= crumb_) ++pins_;
    if (onAdded_) onAdded_(id);
  }

  void chunk(const Piece& p) const {
    p.chunked = true;
    size_t vertices = 0;
    for (const clip::Path& q : p.poly) vertices += q.size();
    if (vertices <= kChunkVertices) return;
    const double cell = 4 * std::sqrt(rMin_ * rMax_);
    for (double y = p.lo.y; y < p.hi.y; y += cell)
      for (double x = p.lo.x; x < p.hi.x; x += cell) {
        const clip::Path rect{clip::toInt({x, y}), clip::toInt({x + cell, y}), clip::toInt({x + cell, y + cell}),
                              clip::toInt({x, y + cell})};
        Chunk k;
        k.poly = clip::boolean(p.poly, {rect}, ClipperLib::ctIntersection);
        if (k.poly.empty()) continue;
        k.area = clip::area(k.poly);
        clip::bounds(k.poly, k.lo, k.hi);
        p.chunks.push_back(std::move(k));
      }
  }

  double rMin_, rMax_, crumb_;
  bool core_;
  std::vector<Segment> boundary_;
  RStarTree<BoxValue> boundaryIndex_;
  std::vector<Piece> pieces_;
  RStarTree<BoxValue> pieceIndex_;
  double uncovered_ = 0.0;
  int pins_ = 0;
  std::function<void(int)> onAdded_;
};

class Coverer {
 public:
  Coverer(const Region& region, const std::vector<double>& radii, const CoveringOptions& opt)
      : region_(region), radii_(radii), opt_(opt) {
    sorted_.resize(radii.size());
    std::iota(sorted_.begin(), sorted_.end(), 0);
    std::stable_sort(sorted_.begin(), sorted_.end(), [&](int a, int b) { return radii[a] < radii[b]; });
    rMin_ = radii[sorted_.front()];
    rMax_ = radii[sorted_.back()];
    // With a band the core is covered whole: only slivers of the polygon
    // approximation (under 0.01 mm^2 measured) may stay.
    core_ = opt.maxWallStock > 0.0;
    crumb_ = core_ ? kCoreCrumb : kCrumbShare * rMin_ * rMin_;
    pieces_ = MaterialPieces(rMin_, rMax_, core_, crumb_);
  }

  // Phases: the material the packing leaves, its Delaunay gaps (4.2.2), every
  // piece's candidates, then the greedy covering (4.2.3) of the core or down
  // to min_coverage.
  CoverResult run(const std::vector<PackedDisk>& packed) {
    const Polygons acc = accessibleRegion(region_, rMin_, opt_.allowance);
    const Polygons core = materialLeft(acc, packed);
    coverDelaunayGaps(packed);
    generateAllCandidates();
    if (core_)
      coverCore(acc, core);
    else
      coverToMinCoverage(acc);
    return std::move(result_);
  }

 private:
  // The pieces of material the packed disks leave (of the core, with a band);
  // returns the core (empty without a band).
  Polygons materialLeft(const Polygons& acc, const std::vector<PackedDisk>& packed) {
    accessible_ = clip::toPaths(acc);
    result_.accessibleArea = clip::area(accessible_);
    pieces_.setOutline(accessible_);
    std::vector<Circle> circles;
    for (const PackedDisk& d : packed) {
      result_.disks.push_back({d.center, d.radius, d.tool, Stage::Packing});
      circles.push_back({d.center, d.radius});
    }
    Polygons core;
    clip::Paths toCover = accessible_;
    if (core_) {
      core = coreRegion(region_, acc, opt_.allowance, opt_.maxWallStock);
      result_.coreArea = poly::area(core);
      // Planned with a slightly wider core: the slivers the greedy leaves (under
      // its crumb) then lie inside the band, and so do the scallops' tips.
      const double margin = std::min(kBandMargin, 0.1 * opt_.maxWallStock);
      toCover = clip::toPaths(coreRegion(region_, acc, opt_.allowance, opt_.maxWallStock - margin));
    }
    // With a band, disks are inscribed polygons in planning too: what the
    // planner counts as cut is cut, so no sliver of the core survives the real disks.
    const clip::Paths left = core_ ? subtractDisks(toCover, circles, false) : subtractDisks(accessible_, circles, true);
    for (clip::Paths& c : clip::components(left)) pieces_.add(std::move(c));
    return core;
  }

  void generateAllCandidates() {
    pieces_.onAdded([this](int id) { generateCandidates(id); });
    for (size_t i = 0; i < pieces_.all().size(); ++i) {
      opt_.progress.tick();
      if (pieces_[static_cast<int>(i)].alive) generateCandidates(static_cast<int>(i));
    }
  }

  // With a band: the core whole (measured as planned, with inscribed disks).
  void coverCore(const Polygons& acc, const Polygons& core) {
    coverResidual(0.0);
    if (!opt_.measureCore) return;
    measure(acc);
    result_.coreUncovered = uncoveredRegion(core, diskCircles());
  }

  // The greedy counts with circumscribed disks; the measurement is conservative.
  // Where the two disagree about the target, cover a little more.
  void coverToMinCoverage(const Polygons& acc) {
    double target = opt_.minCoverage * result_.accessibleArea;
    for (int round = 0;; ++round) {
      coverResidual(target);
      measure(acc);
      const double shortBy = opt_.minCoverage * result_.accessibleArea - result_.coveredArea;
      if (shortBy <= 0.0 || round == 4) break;
      target += shortBy + 1e-4 * result_.accessibleArea;
    }
  }

  std::vector<Circle> diskCircles() const {
    std::vector<Circle> all;
    for (const CoverDisk& d : result_.disks) all.push_back({d.center, d.radius});
    return all;
  }

  // What the disks leave of the accessible region, with inscribed disks.
  void measure(const Polygons& accessible) {
    result_.uncovered = uncoveredRegion(accessible, diskCircles());
    result_.coveredArea = result_.accessibleArea - poly::area(result_.uncovered);
  }

 private:
  struct Candidate {
    double gain;
    int seq;
    Vec2 c;
    int tool;
    int piece;
    bool operator<(const Candidate& o) const { return gain < o.gain || (gain == o.gain && seq > o.seq); }
  };

  void addDisk(Vec2 c, int tool, Stage stage) {
    const double r = radii_[tool];
    result_.disks.push_back({c, r, tool, stage});
    pieces_.cut({clip::diskPath({c, r}, kDiskChord, !core_)}, {c.x - r, c.y - r}, {c.x + r, c.y + r});
  }

  // --- feasible centres ---------------------------------------------------

  // A centre near `a` where a plunge of radius r gouges nothing: pushed out of
  // the walls it is too close to; in a corner, the corner placement itself.
  bool feasibleNear(Vec2 a, double r, Vec2& out) const {
    const double c = r + opt_.allowance;
    Vec2 x = a;
    for (int iter = 0; iter < 12; ++iter) {
      Vec2 w;
      double d;
      int wall;
      const bool inside = region_.contains(x);
      if (!region_.nearestWallPoint(x, inside ? c : 4 * rMax_ + c, w, d, &wall) || (inside && d >= c - kTol)) {
        if (!inside || !region_.diskFits(x, c)) return false;
        out = x;
        return true;
      }
      // Away from the wall; on it or beyond it, along the wall's normal into the material.
      const Segment& s = region_.walls()[wall];
      const Vec2 away = inside && d > 1e-9 ? (x - w) * (1.0 / d) : leftNormal(s.b - s.a) * (1.0 / norm(s.b - s.a));
      x = w + away * (c + 1e-7);
    }
    // Still squeezed between walls: try the corner placements of the walls in reach.
    const std::vector<int> near = region_.nearestWallsNear(x, c, kCornerWalls);
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < near.size(); ++i)
      for (size_t j = i + 1; j < near.size(); ++j)
        for (const Vec2& p : cornerPlacementsWallWall(region_.walls()[near[i]], region_.walls()[near[j]], c))
          if (dist(p, a) < best && region_.diskFits(p, c)) {
            best = dist(p, a);
            out = p;
          }
    return std::isfinite(best);
  }

  // --- 4.2.3: Delaunay gap covering ---------------------------------------

  void coverDelaunayGaps(const std::vector<PackedDisk>& packed) {
    const DelaunayGaps gaps = delaunayGaps(packed);
    if (gaps.triangles.empty()) return;
    std::vector<int> groupOfTri(gaps.triangles.size());
    for (size_t g = 0; g < gaps.groups.size(); ++g)
      for (int t : gaps.groups[g]) groupOfTri[t] = static_cast<int>(g);
    std::vector<BoxValue> boxes;
    for (size_t t = 0; t < gaps.triangles.size(); ++t) {
      Bounds b;
      for (int v : gaps.triangles[t].v) b.add(packed[v].center);
      boxes.emplace_back(boxOf(b.lo, b.hi), static_cast<int>(t));
    }
    RStarTree<BoxValue> triIndex(boxes.begin(), boxes.end());

    // Gaps that hold uncovered material: locate a point of every uncovered piece.
    std::vector<int> groups;
    std::vector<BoxValue> hits;
    for (const MaterialPieces::Piece& p : pieces_.all()) {
      if (!p.alive || p.area < crumb_) continue;
      const Vec2 q = interiorPoint(p.poly);
      hits.clear();
      triIndex.query(bgi::intersects(toBPoint(q)), std::back_inserter(hits));
      for (const BoxValue& h : hits) {
        const GapTriangle& t = gaps.triangles[h.second];
        if (inTriangle(q, packed[t.v[0]].center, packed[t.v[1]].center, packed[t.v[2]].center)) {
          groups.push_back(groupOfTri[h.second]);
          break;
        }
      }
    }
    std::sort(groups.begin(), groups.end());
    groups.erase(std::unique(groups.begin(), groups.end()), groups.end());

    for (int g : groups) {
      clip::Paths tris;
      for (int t : gaps.groups[g]) {
        clip::Path tri;
        for (int v : gaps.triangles[t].v) tri.push_back(clip::toInt(packed[v].center));
        if (ClipperLib::Area(tri) < 0) std::reverse(tri.begin(), tri.end());
        tris.push_back(tri);
      }
      const clip::Paths gapPoly = clip::boolean(tris, {}, ClipperLib::ctUnion);
      Vec2 lo, hi;
      clip::bounds(gapPoly, lo, hi);
      clip::Paths material;
      for (int id : pieces_.near(lo, hi))
        for (const clip::Path& q : pieces_[id].poly) material.push_back(q);
      const clip::Paths gap = clip::boolean(material, gapPoly, ClipperLib::ctIntersection);
      for (clip::Paths& part : clip::components(gap)) encloseGap(part, 0);
    }
  }

  // Enclosing circle (4.2.3.2) readjusted to the next larger tool, split in two
  // when larger than the largest tool. Pieces whose enclosing plunge would gouge
  // are left to the residual covering.
  void encloseGap(const clip::Paths& gap, int depth) {
    if (clip::area(gap) < crumb_) return;
    const Circle mec = minEnclosingCircle(verticesOf(gap));
    if (mec.r <= rMax_) {
      for (int t : sorted_)
        if (radii_[t] >= mec.r && region_.diskFits(mec.c, radii_[t] + opt_.allowance)) {
          addDisk(mec.c, t, Stage::Gap);
          return;
        }
      return;
    }
    if (depth >= kGapSplits) return;
    for (const clip::Paths& part : splitInHalves(gap, mec.c)) encloseGap(part, depth + 1);
  }

  // --- residual covering ---------------------------------------------------

  void anchorsOf(const clip::Paths& p, int depth, std::vector<Vec2>& out) const {
    const Circle mec = minEnclosingCircle(verticesOf(p));
    out.push_back(mec.c);
    // Split until the smallest tool could take a part whole: a crescent left
    // beside a plunge has the same enclosing circle as the piece it came from,
    // whose centre that plunge already took.
    if (mec.r <= rMin_ || depth >= kAnchorSplits) return;
    for (const clip::Paths& part : splitInHalves(p, mec.c))
      if (clip::area(part) >= crumb_) anchorsOf(part, depth + 1, out);
  }

  void generateCandidates(int id) {
    const MaterialPieces::Piece& p = pieces_[id];
    if (p.area < crumb_) return;
    std::vector<Vec2> anchors;
    anchorsOf(p.poly, 0, anchors);

    for (const Vec2& a : anchors) {
      opt_.progress.tick();  // a long piece has many anchors, each its corner placements
      for (int t : sorted_) {
        std::vector<Vec2> centres;
        Vec2 c;
        if (feasibleNear(a, radii_[t], c)) centres.push_back(c);
        // A small piece of the core in a corner the tool only just reaches: the
        // corner placements themselves (the push off one wall lands beside them).
        if (core_ && p.area < radii_[t] * radii_[t]) cornerPlacementsNear(a, radii_[t], centres);
        for (const Vec2& x : centres) queueCandidate(x, t, id);
      }
    }
  }

  void cornerPlacementsNear(Vec2 a, double r, std::vector<Vec2>& out) const {
    const double c = r + opt_.allowance;
    const std::vector<int> near = region_.nearestWallsNear(a, c + r, kCornerWalls);
    const std::vector<int> reflex = region_.nearestReflexVerticesNear(a, c + r, kCornerWalls);
    std::vector<Vec2> pts;
    for (size_t i = 0; i < near.size(); ++i) {
      const Segment& w = region_.walls()[near[i]];
      for (size_t j = i + 1; j < near.size(); ++j)
        for (const Vec2& p : cornerPlacementsWallWall(w, region_.walls()[near[j]], c)) pts.push_back(p);
      for (int v : reflex)
        for (const Vec2& p : cornerPlacementsWallCircle(w, c, {region_.vertices()[v].p, c})) pts.push_back(p);
    }
    for (size_t i = 0; i < reflex.size(); ++i)
      for (size_t j = i + 1; j < reflex.size(); ++j)
        for (const Vec2& p : cornerPlacementsCircleCircle({region_.vertices()[reflex[i]].p, c},
                                                          {region_.vertices()[reflex[j]].p, c}))
          pts.push_back(p);
    for (const Vec2& p : pts)
      if (dist(p, a) <= r && fits(p, c)) out.push_back(p);
  }

  // region_.diskFits, remembered: neighbouring anchors meet the same corner
  // placements again (every one of them, for a tool nearly as large as the pocket).
  bool fits(Vec2 p, double c) const {
    auto [it, fresh] = fitsMemo_.try_emplace({p.x, p.y, c}, false);
    if (fresh) it->second = region_.diskFits(p, c);
    return it->second;
  }
  struct Placement {
    double x, y, c;
    bool operator==(const Placement& o) const { return x == o.x && y == o.y && c == o.c; }
  };
  struct PlacementHash {
    size_t operator()(const Placement& p) const {
      const std::hash<double> h;
      return h(p.x) * 0x9E3779B97F4A7C15ULL ^ h(p.y) * 0xC2B2AE3D27D4EB4FULL ^ h(p.c);
    }
  };

  // Lazy greedy: queue an upper bound of the gain, evaluated when it comes up.
  void queueCandidate(Vec2 c, int t, int id) {
    const double r = radii_[t];
    double bound = 0.0;
    for (int o : pieces_.near({c.x - r, c.y - r}, {c.x + r, c.y + r})) bound += pieces_[o].area;
    bound = std::min(bound, kPi * r * r);
    if (bound < 0.5 * crumb_) return;
    (pieces_[id].pin ? pinQueue_ : wallQueue_).push({bound, seq_++, c, t, id});
  }

  void coverResidual(double target) {
    for (int guard = 0; guard < 1000000; ++guard) {
      opt_.progress.tick();
      const bool pinMode = pieces_.pins() > 0;
      if (!pinMode && result_.accessibleArea - pieces_.uncovered() >= target) break;
      auto& q = pinMode ? pinQueue_ : wallQueue_;
      if (q.empty()) {
        if (!pinMode) break;
        // Pins no plunge can reach (slivers of the polygon approximation): give up on them.
        pieces_.givePinsUp();
        continue;
      }
      Candidate c = q.top();
      q.pop();
      if (!pieces_[c.piece].alive) continue;  // its piece changed: fresh candidates exist
      const double g = pieces_.gainOf(c.c, radii_[c.tool]);
      if (g < 0.5 * crumb_) continue;
      if (!q.empty() && g < q.top().gain) {  // stale: re-queue with its true gain (lazy greedy)
        c.gain = g;
        q.push(c);
        continue;
      }
      addDisk(c.c, c.tool, Stage::Residual);
    }
  }

  const Region& region_;
  std::vector<double> radii_;
  CoveringOptions opt_;
  std::vector<int> sorted_;  // tool indices by increasing radius
  mutable std::unordered_map<Placement, bool, PlacementHash> fitsMemo_;
  double rMin_ = 0, rMax_ = 0, crumb_ = 0;
  bool core_ = false;  // a wall band: cover the core whole (CoveringOptions::maxWallStock)
  clip::Paths accessible_;
  MaterialPieces pieces_{0.0, 0.0, false, 0.0};
  int seq_ = 0;
  std::priority_queue<Candidate> pinQueue_, wallQueue_;
  CoverResult result_;
};

}  // namespace

CoverResult coverRegion(const Region& region, const std::vector<double>& radii,
                        const std::vector<PackedDisk>& packed, const CoveringOptions& options) {
  if (radii.empty()) throw Error("no tools given");
  if (!(options.minCoverage > 0.0 && options.minCoverage <= 1.0))
    throw Error("minimum coverage must be in (0, 1]");
  if (!(options.maxWallStock >= 0.0) || !std::isfinite(options.maxWallStock)) throw Error("wall band must be >= 0");
  Coverer c(region, radii, options);
  return c.run(packed);
}

}  // namespace plunge
