#include "growth_paths.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "detail.hpp"
#include "path_walk.hpp"
#include "polygon.hpp"

namespace plunge {

namespace {

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

// The rows' direction: the long axis, or parallel to the longest wall where
// that is within 10 degrees of it (a machinist's rows run along the walls).
double rowAngle(const Polygons& centres) {
  const double axis = longAxis(centres);
  double th = axis, longest = 0;
  for (const Loop& l : centres)
    for (size_t i = 0; i < l.size(); ++i) {
      const Vec2 d = l[(i + 1) % l.size()] - l[i];
      const double a = std::atan2(d.y, d.x);
      if (norm(d) > longest && std::fabs(std::remainder(a - axis, kPi)) < kPi / 18) {
        longest = norm(d);
        th = a;
      }
    }
  return th;
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

// The loop's corners: turns of over 20 degrees (a corner's plunge reaches
// into the pocket's corner, none between would); its first vertex if none.
std::vector<size_t> cornersOf(const Loop& l) {
  const size_t m = l.size();
  std::vector<size_t> corners;
  for (size_t i = 0; i < m; ++i) {
    const Vec2 a = l[(i + m - 1) % m], b = l[i], c = l[(i + 1) % m];
    const double n1 = dist(a, b), n2 = dist(b, c);
    if (n1 > 0 && n2 > 0 && dot(b - a, c - b) < std::cos(kPi / 9) * n1 * n2) corners.push_back(i);
  }
  if (corners.empty()) corners.push_back(0);
  return corners;
}

// Positions along a loop at most `maxStep` apart, on every corner, evenly
// from one corner to the next.
std::vector<Vec2> alongLoop(const Loop& l, double maxStep) {
  const size_t m = l.size();
  const std::vector<size_t> corners = cornersOf(l);
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
        out.push_back(len > 0 ? pointAlong(a, b, (next - walked) / len) : a);
      walked += len;
    }
  }
  return out;
}

// One ring of offsets: each loop's positions (alongLoop), then a bridge from
// the nearest position of the ring outside (`outer`) to its first one: each
// loop is entered from cut material, like a row from the contour. `outer`
// becomes this ring's positions.
void addOffsetRing(const Polygons& loops, double step, std::vector<Vec2>& outer, std::vector<GrowthPath>& out) {
  std::vector<Vec2> next;
  for (const Loop& l : loops) {
    GrowthPath path;
    path.closed = true;
    path.at = alongLoop(l, step);
    Vec2 from = outer.front();
    for (Vec2 o : outer)
      if (dist(o, path.at.front()) < dist(from, path.at.front())) from = o;
    GrowthPath bridge;
    bridge.at = between(from, path.at.front(), step);
    next.insert(next.end(), path.at.begin(), path.at.end());
    out.push_back(std::move(path));
    if (!bridge.at.empty()) out.push_back(std::move(bridge));
  }
  outer = std::move(next);
}

// Offsets of the region's contour, `spacing` apart inwards, positions at most
// `step` apart along each loop (alongLoop); where the next offset is empty,
// one more halfway. `outer`: the contour's positions.
std::vector<GrowthPath> offsetsAt(const Polygons& centres, double step, double spacing, std::vector<Vec2> outer) {
  std::vector<GrowthPath> out;
  for (int k = 1; !outer.empty(); ++k) {
    const Polygons loops = poly::offset(centres, -k * spacing);
    if (loops.empty()) {  // one more halfway, or the middle stays out of reach
      addOffsetRing(poly::offset(centres, -(k - 0.5) * spacing), step, outer, out);
      break;
    }
    addOffsetRing(loops, step, outer, out);
  }
  return out;
}

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
  const double th = rowAngle(centres);
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
    walkLoop(ring[best], bestVertex, step, out);
    at = out.back();
  }
  return out;
}

void refineContour(GrowthPath& path, const Polygons& centres, const Region& region, const WallScallop& band) {
  const double r = band.r;
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
      if (cusps.size() == 2 && wall - band.allowance > band.scallop) {
        out.push_back(nearestOnLoops(centres, a + (b - a) * 0.5));
        added = true;
      }
    }
    path.at = std::move(out);
    if (!added) break;
  }
}

std::vector<std::vector<bool>> coveredByContour(const std::vector<GrowthPath>& paths, double r) {
  const double cell = 2 * r;
  std::unordered_map<long long, std::vector<Vec2>> contour;
  for (const GrowthPath& p : paths)
    if (p.contour)
      for (Vec2 c : p.at) contour[detail::cellKeyOf(c, cell)].push_back(c);
  auto cut = [&](Vec2 q) { return detail::anyNear(contour, q, cell, [&](Vec2 c) { return dist(c, q) <= r; }); };
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

}  // namespace plunge
