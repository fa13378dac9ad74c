#include "medial.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>

#include <boost/polygon/voronoi.hpp>

#include "polygon.hpp"

namespace {
struct IPoint {
  int x, y;
};
struct ISegment {
  IPoint a, b;
};
}  // namespace

namespace boost {
namespace polygon {
template <>
struct geometry_concept<IPoint> {
  typedef point_concept type;
};
template <>
struct point_traits<IPoint> {
  typedef int coordinate_type;
  static coordinate_type get(const IPoint& p, orientation_2d o) { return o == HORIZONTAL ? p.x : p.y; }
};
template <>
struct geometry_concept<ISegment> {
  typedef segment_concept type;
};
template <>
struct segment_traits<ISegment> {
  typedef int coordinate_type;
  typedef IPoint point_type;
  static point_type get(const ISegment& s, direction_1d d) { return d.to_int() ? s.b : s.a; }
};
}  // namespace polygon
}  // namespace boost

namespace plunge {

namespace {

bool insidePolygons(const Polygons& p, Vec2 q) {  // even-odd rule
  bool in = false;
  for (const Loop& l : p)
    for (size_t i = 0, j = l.size() - 1; i < l.size(); j = i++)
      if ((l[i].y > q.y) != (l[j].y > q.y) &&
          q.x < (l[j].x - l[i].x) * (q.y - l[i].y) / (l[j].y - l[i].y) + l[i].x)
        in = !in;
  return in;
}

}  // namespace

MedialAxis medialAxis(const Region& region) {
  // Boost.Polygon works on integers: coordinates in a fixed grid over the region.
  const Vec2 lo = region.minCorner(), hi = region.maxCorner();
  const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
  const double scale = std::min(1e4, 1e8 / std::max(extent, 1e-9));
  auto toInt = [&](Vec2 p) {
    return IPoint{static_cast<int>(std::lround((p.x - lo.x) * scale)), static_cast<int>(std::lround((p.y - lo.y) * scale))};
  };
  auto toMm = [&](double x, double y) { return Vec2{x / scale + lo.x, y / scale + lo.y}; };
  std::vector<ISegment> segments;
  for (const Segment& s : region.walls()) segments.push_back({toInt(s.a), toInt(s.b)});
  boost::polygon::voronoi_diagram<double> vd;
  std::vector<IPoint> noPoints;
  boost::polygon::construct_voronoi(noPoints.begin(), noPoints.end(), segments.begin(), segments.end(), &vd);

  MedialAxis axis;
  std::map<const void*, int> index;
  const double far = 2 * extent + 1;
  auto node = [&](const boost::polygon::voronoi_vertex<double>* v) {
    auto it = index.find(v);
    if (it != index.end()) return it->second;
    const Vec2 p = toMm(v->x(), v->y());
    const int id = static_cast<int>(axis.nodes.size());
    axis.nodes.push_back(p);
    axis.radius.push_back(region.wallDistance(p, far));
    index[v] = id;
    return id;
  };
  const double onWall = 2.0 / scale;
  for (const auto& e : vd.edges()) {
    if (!e.is_primary() || !e.is_finite() || &e > e.twin()) continue;
    const Vec2 p0 = toMm(e.vertex0()->x(), e.vertex0()->y()), p1 = toMm(e.vertex1()->x(), e.vertex1()->y());
    const Vec2 mid = 0.5 * (p0 + p1);
    if (!region.contains(mid) || region.wallDistance(mid, far) < onWall) continue;
    const int a = node(e.vertex0()), b = node(e.vertex1());
    if (e.is_curved()) {
      // Between a reflex vertex and a wall: the clearance is smallest at the
      // parabola's apex, half-way between the vertex and its foot on the wall.
      const auto* c1 = e.cell();
      const auto* c2 = e.twin()->cell();
      const auto* pointCell = c1->contains_point() ? c1 : c2;
      const auto* segCell = c1->contains_point() ? c2 : c1;
      const ISegment& ps = segments[pointCell->source_index()];
      const IPoint ip = pointCell->source_category() == boost::polygon::SOURCE_CATEGORY_SEGMENT_START_POINT ? ps.a : ps.b;
      const ISegment& ss = segments[segCell->source_index()];
      const Vec2 P = toMm(ip.x, ip.y);
      const Segment S{toMm(ss.a.x, ss.a.y), toMm(ss.b.x, ss.b.y)};
      const Vec2 apex = 0.5 * (P + closestPointOnSegment(S, P));
      const Vec2 d = p1 - p0;
      const double t = dot(apex - p0, d) / std::max(dot(d, d), 1e-300);
      if (t > 0.0 && t < 1.0 && dist(apex, P) > 0.5 * onWall) {
        const int m = static_cast<int>(axis.nodes.size());
        axis.nodes.push_back(apex);
        axis.radius.push_back(region.wallDistance(apex, far));
        axis.edges.push_back({a, m});
        axis.edges.push_back({m, b});
        continue;
      }
    }
    axis.edges.push_back({a, b});
  }
  return axis;
}

Circle largestInscribedCircle(const MedialAxis& axis) {
  Circle best{{0, 0}, 0.0};
  for (size_t i = 0; i < axis.nodes.size(); ++i)
    if (axis.radius[i] > best.r) best = {axis.nodes[i], axis.radius[i]};
  return best;
}

std::vector<Neck> findNecks(const Region& region, const MedialAxis& axis, double riseFactor) {
  const int n = static_cast<int>(axis.nodes.size());
  std::vector<std::vector<int>> adj(n);
  for (const auto& [a, b] : axis.edges) {
    adj[a].push_back(b);
    adj[b].push_back(a);
  }
  const Vec2 lo = region.minCorner(), hi = region.maxCorner();
  const double far = 2 * dist(lo, hi) + 1;
  // Local minima of the clearance where, on two sides, it climbs to riseFactor
  // times the minimum without first dropping below it.
  std::vector<int> candidates;
  for (int v = 0; v < n; ++v) {
    if (adj[v].size() < 2 || axis.radius[v] <= 0.0) continue;
    const double r = axis.radius[v];
    bool minimum = true;
    for (int w : adj[v])
      if (axis.radius[w] < r || (axis.radius[w] == r && w < v)) minimum = false;
    if (!minimum) continue;
    int rising = 0;
    for (int start : adj[v]) {
      std::vector<char> seen(n, 0);
      seen[v] = seen[start] = 1;
      std::vector<int> stack{start};
      bool climbs = false;
      while (!stack.empty() && !climbs) {
        const int u = stack.back();
        stack.pop_back();
        if (axis.radius[u] >= riseFactor * r) climbs = true;
        for (int w : adj[u])
          if (!seen[w] && axis.radius[w] >= r) {
            seen[w] = 1;
            stack.push_back(w);
          }
      }
      rising += climbs;
    }
    if (rising >= 2) candidates.push_back(v);
  }
  // One neck per narrow place: along a corridor every node is a minimum.
  std::sort(candidates.begin(), candidates.end(), [&](int a, int b) {
    return axis.radius[a] < axis.radius[b] || (axis.radius[a] == axis.radius[b] && a < b);
  });
  std::vector<Neck> necks;
  for (int v : candidates) {
    const Vec2 c = axis.nodes[v];
    const double r = axis.radius[v];
    bool duplicate = false;
    for (const Neck& k : necks)
      if (dist(k.center, c) < 1.5 * (r + 0.5 * k.width)) duplicate = true;
    if (duplicate) continue;
    // The neck line: the nearest wall point, and the nearest one on the other side.
    Vec2 a, b{};
    double d;
    int wa = -1;
    if (!region.nearestWallPoint(c, far, a, d, &wa)) continue;
    double best = std::numeric_limits<double>::infinity();
    int wb = -1;
    for (int w : region.wallsNear(c, 1.05 * r + 1e-9)) {
      const Vec2 f = closestPointOnSegment(region.walls()[w], c);
      if (dot(f - c, a - c) > 0.0) continue;  // same side as a
      const double dd = dist(f, c);
      if (dd < best) {
        best = dd;
        b = f;
        wb = w;
      }
    }
    if (wb < 0) continue;
    necks.push_back({c, dist(a, b), a, b, region.wallLoop(wa) != 0 || region.wallLoop(wb) != 0});
  }
  return necks;
}

std::vector<SubRegion> subdivide(const Region& region, const MedialAxis& axis, const std::vector<Neck>& necks) {
  const double cut = 0.01;  // mm: the width of the saw along each neck line
  Polygons cuts;
  for (const Neck& k : necks) {
    const Vec2 d = (k.b - k.a) * (1.0 / std::max(dist(k.a, k.b), 1e-12));
    const Vec2 a = k.a - d * (2 * cut), b = k.b + d * (2 * cut);
    const Vec2 n = leftNormal(d) * (0.5 * cut);
    cuts.push_back({a - n, b - n, b + n, a + n});
  }
  std::vector<SubRegion> parts;
  for (const Polygons& piece : poly::components(poly::subtract(region.polygons(), cuts))) {
    SubRegion s;
    s.area = poly::area(piece);
    if (s.area <= 1e-9) continue;
    s.shape = piece;
    for (size_t i = 0; i < axis.nodes.size(); ++i)
      if (axis.radius[i] > s.inscribed.r && insidePolygons(piece, axis.nodes[i])) s.inscribed = {axis.nodes[i], axis.radius[i]};
    if (s.inscribed.r <= 0.0) s.inscribed = {piece.front().front(), 0.0};
    for (size_t k = 0; k < necks.size(); ++k) {
      const Vec2 d = necks[k].b - necks[k].a;
      const Vec2 n = leftNormal(d) * (2 * cut / std::max(norm(d), 1e-12));
      const Vec2 m = 0.5 * (necks[k].a + necks[k].b);
      if (insidePolygons(piece, m + n) || insidePolygons(piece, m - n)) s.necks.push_back(static_cast<int>(k));
    }
    parts.push_back(std::move(s));
  }
  // Largest first, so that indices do not depend on Clipper's output order.
  std::sort(parts.begin(), parts.end(), [](const SubRegion& a, const SubRegion& b) {
    return a.area > b.area || (a.area == b.area && (a.inscribed.c.x < b.inscribed.c.x ||
                                                    (a.inscribed.c.x == b.inscribed.c.x && a.inscribed.c.y < b.inscribed.c.y)));
  });
  return parts;
}

std::vector<int> subRegionOrder(const std::vector<SubRegion>& parts, Vec2 start) {
  const int n = static_cast<int>(parts.size());
  if (n == 0) return {};
  int root = 0;
  for (int i = 1; i < n; ++i)
    if (dist(parts[i].inscribed.c, start) < dist(parts[root].inscribed.c, start)) root = i;
  // Prim's minimum spanning tree over the centres, then a depth-first walk.
  std::vector<double> key(n, std::numeric_limits<double>::infinity());
  std::vector<int> parent(n, -1);
  std::vector<char> done(n, 0);
  key[root] = 0.0;
  std::vector<std::vector<int>> children(n);
  for (int it = 0; it < n; ++it) {
    int u = -1;
    for (int i = 0; i < n; ++i)
      if (!done[i] && (u < 0 || key[i] < key[u])) u = i;
    done[u] = 1;
    if (parent[u] >= 0) children[parent[u]].push_back(u);
    for (int v = 0; v < n; ++v) {
      const double d = dist(parts[u].inscribed.c, parts[v].inscribed.c);
      if (!done[v] && d < key[v]) {
        key[v] = d;
        parent[v] = u;
      }
    }
  }
  std::vector<int> order;
  std::vector<int> stack{root};
  while (!stack.empty()) {
    const int u = stack.back();
    stack.pop_back();
    order.push_back(u);
    auto& ch = children[u];
    std::sort(ch.begin(), ch.end(), [&](int a, int b) {
      return dist(parts[a].inscribed.c, parts[u].inscribed.c) > dist(parts[b].inscribed.c, parts[u].inscribed.c);
    });
    for (int c : ch) stack.push_back(c);  // nearest child visited first
  }
  return order;
}

}  // namespace plunge
