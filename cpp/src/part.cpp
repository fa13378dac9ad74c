#include "part.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <boost/iterator/function_output_iterator.hpp>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <utility>

#include "depth.hpp"
#include "detail.hpp"
#include "plunge/error.hpp"
#include "polygon.hpp"
#include "region.hpp"

namespace plunge {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

namespace {

using Point = bg::model::point<double, 2, bg::cs::cartesian>;
using Box = bg::model::box<Point>;
using Entry = std::pair<Box, std::uint32_t>;

Vec2 xy(const std::array<double, 3>& v) { return {v[0], v[1]}; }

// Orientation of c from the line a-b: > 0 on its left.
double side(Vec2 a, Vec2 b, Vec2 c) { return cross(b - a, c - a); }

bool segmentsCross(Vec2 p, Vec2 q, Vec2 a, Vec2 b) {
  const double d1 = side(a, b, p), d2 = side(a, b, q), d3 = side(p, q, a), d4 = side(p, q, b);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

bool inTriangle(Vec2 p, Vec2 a, Vec2 b, Vec2 c) {
  const double d1 = side(a, b, p), d2 = side(b, c, p), d3 = side(c, a, p);
  return (d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0);
}

// Loops (non-zero winding: islands run the other way) with their edges in an
// R-tree: whether a point lies inside, and whether a triangle's shadow meets
// the inside, without walking every edge.
class LoopIndex {
 public:
  explicit LoopIndex(const Polygons& loops) {
    std::vector<Entry> entries;
    for (const Loop& L : loops)
      for (size_t i = 0; i < L.size(); ++i) {
        const Vec2 a = L[i], b = L[(i + 1) % L.size()];
        entries.push_back({Box(Point(std::min(a.x, b.x), std::min(a.y, b.y)), Point(std::max(a.x, b.x), std::max(a.y, b.y))),
                           static_cast<std::uint32_t>(edges_.size())});
        edges_.push_back({a, b});
      }
    index_ = Index(entries.begin(), entries.end());
  }

  bool empty() const { return edges_.empty(); }

  // Non-zero winding number of the loops around p (a ray to +x).
  bool contains(Vec2 p) const {
    int winding = 0;
    const Box ray(Point(p.x, p.y), Point(std::numeric_limits<double>::max(), p.y));
    index_.query(bgi::intersects(ray), boost::make_function_output_iterator([&](const Entry& e) {
                   const auto& [a, b] = edges_[e.second];
                   if (a.y <= p.y) {
                     if (b.y > p.y && side(a, b, p) > 0) ++winding;
                   } else if (b.y <= p.y && side(a, b, p) < 0) {
                     --winding;
                   }
                 }));
    return winding != 0;
  }

  // The triangle's shadow meets the loops' inside: a corner inside, a loop's
  // vertex inside it, or an edge crossing one of the loops'.
  bool meets(Vec2 a, Vec2 b, Vec2 c) const {
    if (contains(a) || contains(b) || contains(c)) return true;
    const Box box(Point(std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y})),
                  Point(std::max({a.x, b.x, c.x}), std::max({a.y, b.y, c.y})));
    bool hit = false;
    index_.query(bgi::intersects(box), boost::make_function_output_iterator([&](const Entry& e) {
                   if (hit) return;
                   const auto& [p, q] = edges_[e.second];
                   hit = inTriangle(p, a, b, c) || segmentsCross(p, q, a, b) || segmentsCross(p, q, b, c) ||
                         segmentsCross(p, q, c, a);
                 }));
    return hit;
  }

 private:
  using Index = bgi::rtree<Entry, bgi::rstar<16>>;
  std::vector<std::pair<Vec2, Vec2>> edges_;
  Index index_;
};

// A shadow this small (mm^2) is a wall seen edge-on, or rounding.
constexpr double kFlatShadow = 1e-9;

// The part of the triangle above height z, seen from above, counter-clockwise
// (empty where none of it is, or it stands vertical).
Loop shadowAbove(const std::array<double, 3>& a, const std::array<double, 3>& b, const std::array<double, 3>& c,
                 double z) {
  Loop out;
  const std::array<const std::array<double, 3>*, 3> v{&a, &b, &c};
  for (int i = 0; i < 3; ++i) {
    const auto& p = *v[i];
    const auto& q = *v[(i + 1) % 3];
    if (p[2] > z) out.push_back(xy(p));
    if ((p[2] > z) != (q[2] > z)) {  // the edge crosses the plane: where
      const double t = (z - p[2]) / (q[2] - p[2]);
      out.push_back({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])});
    }
  }
  double area = 0.0;
  for (size_t i = 0; i < out.size(); ++i) area += cross(out[i], out[(i + 1) % out.size()]);
  if (std::fabs(0.5 * area) <= kFlatShadow) return {};
  if (area < 0) std::reverse(out.begin(), out.end());
  return out;
}

}  // namespace

double partMargin(const TriangleMesh& part) {
  double dev = 0.0;
  for (double d : part.deviation) dev = std::max(dev, d);
  return std::max(kPartMargin, 2.0 * dev);
}

TriangleMesh partInReach(const TriangleMesh& part, const Polygons& region, double margin) {
  TriangleMesh out;
  const LoopIndex deep(poly::offset(region, -margin));
  if (deep.empty()) return out;
  std::vector<std::uint32_t> used(part.vertices.size(), UINT32_MAX);
  out.deviation.clear();
  for (size_t i = 0; i < part.triangles.size(); ++i) {
    const auto& t = part.triangles[i];
    if (!deep.meets(xy(part.vertices[t[0]]), xy(part.vertices[t[1]]), xy(part.vertices[t[2]]))) continue;
    std::array<std::uint32_t, 3> mine{};
    for (int k = 0; k < 3; ++k) {
      if (used[t[k]] == UINT32_MAX) {
        used[t[k]] = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(part.vertices[t[k]]);
      }
      mine[k] = used[t[k]];
    }
    out.triangles.push_back(mine);
    out.deviation.push_back(part.deviation.size() == 1 ? part.deviation[0] : part.deviation[i]);
  }
  return out;
}

Polygons overhangsOver(const TriangleMesh& part, double above, const Polygons& region, double margin) {
  const Polygons deep = poly::offset(region, -margin);
  const LoopIndex index(deep);
  if (index.empty()) return {};
  Polygons shadows;
  for (const auto& t : part.triangles) {
    const auto &a = part.vertices[t[0]], &b = part.vertices[t[1]], &c = part.vertices[t[2]];
    if (std::max({a[2], b[2], c[2]}) <= above || !index.meets(xy(a), xy(b), xy(c))) continue;
    Loop s = shadowAbove(a, b, c, above);
    if (!s.empty()) shadows.push_back(std::move(s));
  }
  if (shadows.empty()) return {};
  const Polygons over = poly::intersect(poly::unite(shadows), deep);
  if (poly::area(over) <= kFlatShadow) return {};
  return poly::offset(over, margin);
}

namespace {

// The highest the floor comes over the region: a flat floor's height, else
// the highest of its peaks (faces' peaks, ridges and corners; a mesh's
// vertices: floor.hpp) and of its heights along the region's loops.
double floorTop(const FloorSurface& floor, const Region& region) {
  if (floor.isFlat()) return floor.height(region.loops()[0][0]);
  const Vec2 lo = region.minCorner(), hi = region.maxCorner();
  double top = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : floor.peaks(lo, hi, 1e-3 * dist(lo, hi) + 0.1, Progress()).points) top = std::max(top, p.z);
  for (const Loop& L : region.loops())
    for (const Vec2& v : L)
      if (const double z = floor.height(v); std::isfinite(z)) top = std::max(top, z);
  return top;
}

}  // namespace

namespace {

// Pieces of floor smaller than this (mm^2) are the polygons' rounding.
constexpr double kCrumb = 0.01;

// The region less `over` grown by the margin more (so that where the part
// meets a wall it cuts into the wall, and no thread of the region is left
// between them), without crumbs: its pieces, largest first. Where Clipper
// still leaves loops touching, the region is opened by the margin instead
// (shrunk, then grown back), which rounds its corners that much.
std::vector<Polygons> piecesWithout(const Polygons& region, const Polygons& over, double margin) {
  auto pieces = [](const Polygons& p) {
    std::vector<Polygons> out;
    for (Polygons& c : poly::components(p))
      if (poly::area(c) > kCrumb) out.push_back(std::move(c));
    std::sort(out.begin(), out.end(), [](const Polygons& a, const Polygons& b) { return poly::area(a) > poly::area(b); });
    return out;
  };
  std::vector<Polygons> cut = pieces(poly::subtract(region, poly::offset(over, margin)));
  try {
    if (!cut.empty()) Region(cut[0][0], Polygons(cut[0].begin() + 1, cut[0].end()));
    return cut;
  } catch (const Error&) {
    return pieces(poly::offset(poly::offset(poly::subtract(region, over), -margin), margin));
  }
}

}  // namespace

std::optional<Region> pocketBelow(const TriangleMesh& part, const Region& region, double z) {
  const double margin = partMargin(part);
  const Polygons over = overhangsOver(part, z, region.polygons(), margin);
  if (over.empty()) return std::nullopt;
  const std::vector<Polygons> pieces = piecesWithout(region.polygons(), over, margin);
  if (pieces.empty() || poly::area(pieces[0]) <= kCrumb) return std::nullopt;
  try {
    return Region(pieces[0][0], Polygons(pieces[0].begin() + 1, pieces[0].end()));
  } catch (const Error&) {
    return std::nullopt;  // loops Clipper left touching: measured as the section
  }
}

PlanInput withoutOverhangs(PlanInput in, const FloorSurface& floor) {
  const Region given(in.boundary, in.islands);
  const Polygons region = given.polygons();
  const double margin = partMargin(*in.part);
  const Polygons over = overhangsOver(*in.part, floorTop(floor, given) + margin, region, margin);
  if (over.empty()) return in;
  const std::vector<Polygons> pieces = piecesWithout(region, over, margin);
  if (pieces.empty() || poly::area(pieces[0]) <= kCrumb)
    throw Error("the part hangs over the whole floor: no plunge reaches it (select the floor of a pocket open from"
                " above)");
  const Polygons under = poly::intersect(region, over);
  detail::Bounds b;
  for (const Loop& L : under) b.add(L);
  std::ostringstream m;
  m << std::fixed << std::setprecision(0) << "part material overhangs the pocket above its floor (a tab, or a top"
    << " wider than what holds it): no plunge goes under it, " << poly::area(under) << " mm2 of the floor around "
    << detail::formatPoint(0.5 * (b.lo + b.hi)) << " are left to another operation";
  double apart = 0.0;
  for (size_t k = 1; k < pieces.size(); ++k) apart += poly::area(pieces[k]);
  if (apart > kCrumb)
    m << "; it also parts the pocket: " << apart << " mm2 beyond it are not planned (select them in an operation of"
      << " their own)";
  in.notes.push_back(m.str());
  in.boundary = pieces[0][0];
  in.islands.assign(pieces[0].begin() + 1, pieces[0].end());
  return in;
}

}  // namespace plunge
