#include "part_stock.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "depth.hpp"
#include "polygon.hpp"
#include "region.hpp"

namespace plunge {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Heights the stock is measured at: about this many from the floor to the top.
constexpr int kHeights = 24;
// Stock thinner than this (mm) over a sample is the raster's, not the plan's.
constexpr double kThin = 0.05;

// "No source" in the distance transforms (mm^2): far above any squared
// distance in a pocket, and small enough that the differences taken of it
// stay exact to well under a micrometre.
constexpr double kFar = 1e12;

// Squared Euclidean distance transform along one line of samples at sorted
// positions p (Felzenszwalb and Huttenlocher, "Distance transforms of sampled
// functions", 2012): the lower envelope of the parabolas (x - p[v])^2 + f[v],
// read at each p[q]. f: 0 at the sources, kFar elsewhere (or an earlier
// pass's squared distances).
void transformLine(const std::vector<double>& p, const std::vector<double>& f, std::vector<double>& d,
                   std::vector<int>& v, std::vector<double>& z) {
  const int n = static_cast<int>(f.size());
  auto meet = [&](int q, int r) { return ((f[q] + p[q] * p[q]) - (f[r] + p[r] * p[r])) / (2.0 * (p[q] - p[r])); };
  int k = 0;
  v[0] = 0;
  z[0] = -kInf;
  z[1] = kInf;
  for (int q = 1; q < n; ++q) {
    double m = meet(q, v[k]);
    while (m <= z[k]) {
      --k;
      m = meet(q, v[k]);
    }
    ++k;
    v[k] = q;
    z[k] = m;
    z[k + 1] = kInf;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < p[q]) ++k;
    d[q] = (p[q] - p[v[k]]) * (p[q] - p[v[k]]) + f[v[k]];
  }
}

// Squared distance (mm^2) from every sample of an nx x ny raster of step h to
// the nearest one of `source`, into `out` (kFar or more where there is none).
void distanceSquared(const std::vector<char>& source, size_t nx, size_t ny, double h, float* out) {
  std::vector<double> grid(nx * ny);
  for (size_t k = 0; k < grid.size(); ++k) grid[k] = source[k] ? 0.0 : kFar;
  const size_t n = std::max(nx, ny);
  std::vector<double> p(n), f(n), d(n), z(n + 1);
  std::vector<int> v(n);
  for (size_t q = 0; q < n; ++q) p[q] = q * h;
  p.resize(ny), f.resize(ny), d.resize(ny);
  for (size_t i = 0; i < nx; ++i) {  // columns
    for (size_t j = 0; j < ny; ++j) f[j] = grid[j * nx + i];
    transformLine(p, f, d, v, z);
    for (size_t j = 0; j < ny; ++j) grid[j * nx + i] = d[j];
  }
  p.resize(nx), f.resize(nx), d.resize(nx);
  for (size_t q = 0; q < nx; ++q) p[q] = q * h;
  for (size_t j = 0; j < ny; ++j) {  // rows
    std::copy(grid.begin() + static_cast<std::ptrdiff_t>(j * nx), grid.begin() + static_cast<std::ptrdiff_t>((j + 1) * nx),
              f.begin());
    transformLine(p, f, d, v, z);
    for (size_t i = 0; i < nx; ++i) out[j * nx + i] = static_cast<float>(d[i]);
  }
}

}  // namespace

PartStock measurePartStock(const TriangleMesh& part, const FloorSurface& floor, const std::vector<Loop>& outlines,
                           const Material& material, const std::vector<Plunge>& plunges, const ToolTable& tools,
                           const PartStockOptions& o) {
  PartStock out;
  std::vector<Region> footprint;
  Vec2 lo{kInf, kInf}, hi{-kInf, -kInf};
  for (const Loop& L : outlines) {
    const Region& r = footprint.emplace_back(L, std::vector<Loop>{});
    lo = {std::min(lo.x, r.minCorner().x), std::min(lo.y, r.minCorner().y)};
    hi = {std::max(hi.x, r.maxCorner().x), std::max(hi.y, r.maxCorner().y)};
  }
  // Two sample steps of margin all round: the part's walls stand there.
  const double h = o.spacing;
  lo = lo - Vec2{2 * h, 2 * h};
  hi = hi + Vec2{2 * h, 2 * h};
  const size_t nx = static_cast<size_t>(std::ceil((hi.x - lo.x) / h)) + 1;
  const size_t ny = static_cast<size_t>(std::ceil((hi.y - lo.y) / h)) + 1;
  auto at = [&](size_t k) { return Vec2{lo.x + (k % nx) * h, lo.y + (k / nx) * h}; };
  const size_t n = nx * ny;

  // The part seen from above: its upper envelope, and the floor's heights.
  std::vector<double> top(n, -kInf);
  for (const auto& t : part.triangles) {
    const auto &a = part.vertices[t[0]], &b = part.vertices[t[1]], &c = part.vertices[t[2]];
    const double det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    const long i0 = std::max(0L, static_cast<long>(std::ceil((std::min({a[0], b[0], c[0]}) - lo.x) / h)));
    const long i1 = std::min(static_cast<long>(nx) - 1, static_cast<long>(std::floor((std::max({a[0], b[0], c[0]}) - lo.x) / h)));
    const long j0 = std::max(0L, static_cast<long>(std::ceil((std::min({a[1], b[1], c[1]}) - lo.y) / h)));
    const long j1 = std::min(static_cast<long>(ny) - 1, static_cast<long>(std::floor((std::max({a[1], b[1], c[1]}) - lo.y) / h)));
    if (std::fabs(det) < 1e-12) continue;  // standing: the faces at its top hold its height
    for (long j = j0; j <= j1; ++j) {
      o.progress.tick();
      for (long i = i0; i <= i1; ++i) {
        const double x = lo.x + i * h, y = lo.y + j * h;
        const double u = ((b[1] - c[1]) * (x - c[0]) + (c[0] - b[0]) * (y - c[1])) / ((b[1] - c[1]) * (a[0] - c[0]) + (c[0] - b[0]) * (a[1] - c[1]));
        const double v = ((c[1] - a[1]) * (x - c[0]) + (a[0] - c[0]) * (y - c[1])) / ((b[1] - c[1]) * (a[0] - c[0]) + (c[0] - b[0]) * (a[1] - c[1]));
        const double w = 1 - u - v;
        if (u < -1e-9 || v < -1e-9 || w < -1e-9) continue;
        double& cell = top[static_cast<size_t>(j) * nx + static_cast<size_t>(i)];
        cell = std::max(cell, u * a[2] + v * b[2] + w * c[2]);
      }
    }
  }
  // The footprint, row by row: where a row crosses the outlines' edges (their
  // union's, even-odd), the samples between two crossings are inside.
  std::vector<char> inside(n, 0);
  {
    Polygons all;
    for (const Region& r : footprint) all.push_back(r.loops()[0]);
    const Polygons merged = poly::unite(all);
    std::vector<double> xs;
    for (size_t j = 0; j < ny; ++j) {
      const double y = lo.y + j * h;
      xs.clear();
      for (const Loop& L : merged)
        for (size_t e = 0; e < L.size(); ++e) {
          const Vec2 a = L[e], b = L[(e + 1) % L.size()];
          if ((a.y <= y) != (b.y <= y)) xs.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
        }
      std::sort(xs.begin(), xs.end());
      for (size_t q = 0; q + 1 < xs.size(); q += 2) {
        const long i0 = std::max(0L, static_cast<long>(std::ceil((xs[q] - lo.x) / h)));
        const long i1 = std::min(static_cast<long>(nx) - 1, static_cast<long>(std::floor((xs[q + 1] - lo.x) / h)));
        for (long i = i0; i <= i1; ++i) inside[j * nx + static_cast<size_t>(i)] = 1;
      }
    }
  }
  std::vector<double> floorZ(n, -kInf);
  double lowest = kInf;
  for (size_t k = 0; k < n; ++k) {
    if (k % nx == 0) o.progress.tick();
    if (!inside[k]) continue;
    const double f = floor.height(at(k));
    if (std::isfinite(f)) {
      floorZ[k] = f;
      lowest = std::min(lowest, f);
      top[k] = std::max(top[k], f);
    }
  }
  if (!std::isfinite(lowest)) return out;

  // The stock's top after every plunge: each cutter's surface at its stop.
  std::vector<double> stock(n);
  for (size_t k = 0; k < n; ++k) stock[k] = material.at(at(k));
  for (const Plunge& p : plunges) {
    const Cutter c = cutterOf(tools.byId(p.toolId));
    const double r = c.radius;
    const long j0 = std::max(0L, static_cast<long>(std::ceil((p.y - r - lo.y) / h)));
    const long j1 = std::min(static_cast<long>(ny) - 1, static_cast<long>(std::floor((p.y + r - lo.y) / h)));
    for (long j = j0; j <= j1; ++j) {
      const double dy = lo.y + j * h - p.y, half = std::sqrt(std::max(0.0, r * r - dy * dy));
      const long i0 = std::max(0L, static_cast<long>(std::ceil((p.x - half - lo.x) / h)));
      const long i1 = std::min(static_cast<long>(nx) - 1, static_cast<long>(std::floor((p.x + half - lo.x) / h)));
      for (long i = i0; i <= i1; ++i) {
        const double dx = lo.x + i * h - p.x;
        double& s = stock[static_cast<size_t>(j) * nx + static_cast<size_t>(i)];
        s = std::min(s, p.z + cutterProfile(c, std::hypot(dx, dy)));
      }
    }
  }

  // Layers from the floor up to the part's top: above it is the Job's stock
  // over the whole part (a facing pass's), not the pocket's.
  double highest = -kInf, partTop = -kInf;
  for (size_t k = 0; k < n; ++k) {
    if (inside[k]) highest = std::max(highest, stock[k]);
    if (std::isfinite(top[k])) partTop = std::max(partTop, top[k]);
  }
  const double from = lowest + o.floorAllowance, to = std::min(highest, partTop);
  if (!(to > from)) return out;
  const double step = std::max(0.25, (to - from) / kHeights);
  std::vector<double> heights;
  for (double z = from + 0.5 * step; z < to; z += step) heights.push_back(z);
  for (double z : o.heights)
    if (z > from && z < to) heights.push_back(z);
  std::sort(heights.begin(), heights.end());
  heights.erase(std::unique(heights.begin(), heights.end()), heights.end());
  const size_t layers = heights.size();
  if (layers == 0 || layers > 4096) return out;  // (at most kHeights and the stops asked about)

  // The stock in each layer: in the part's air, above what the floor stock
  // may leave over the part below. Stock one sample wide (a sliver between
  // two plunges, the raster's own steps) is no band: only what lies in a
  // 3 x 3 block of stock or part counts (the raster opened by one sample).
  std::vector<char> solid(n), left(n), wide(n);
  std::vector<float> dist(n);
  for (size_t l = 0; l < layers; ++l) {
    const double z = heights[l];
    bool any = false;
    for (size_t k = 0; k < n; ++k) {
      solid[k] = top[k] >= z || !inside[k];
      // Over the floor (no part on it there) beyond its stock's limit, or over no part at all.
      const bool overFloor = std::isfinite(floorZ[k]) && top[k] <= floorZ[k] + kThin &&
                             z - floorZ[k] - o.floorAllowance > o.maxFloorStock + kThin;
      // Stock more than the floor's may leave under a cut above it: not the
      // ledge a plunge's floor allowance leaves where the part ends just under it.
      left[k] = !solid[k] && stock[k] > z + o.floorAllowance + o.maxFloorStock + kThin &&
                (overFloor || !std::isfinite(top[k]));
      any = any || left[k];
    }
    if (!any) continue;
    // The part's material there seen from above, and everything past the
    // pocket's outline (its walls, as the outline has them): the distance
    // across to it (the wall band is measured across, at each height).
    o.progress.tick();
    distanceSquared(solid, nx, ny, h, dist.data());
    for (size_t k = 0; k < n; ++k) {
      wide[k] = 0;
      const size_t i = k % nx, j = k / nx;
      if (!left[k] || i == 0 || j == 0 || i + 1 == nx || j + 1 == ny) continue;
      bool block = true;
      for (size_t b = j - 1; b <= j + 1 && block; ++b)
        for (size_t a = i - 1; a <= i + 1 && block; ++a) block = left[b * nx + a] || solid[b * nx + a];
      wide[k] = block;
    }
    for (size_t k = 0; k < n; ++k) {
      if (!left[k]) continue;
      bool counted = false;
      const size_t i = k % nx, j = k / nx;
      for (size_t b = j > 0 ? j - 1 : 0; b <= std::min(j + 1, ny - 1) && !counted; ++b)
        for (size_t a = i > 0 ? i - 1 : 0; a <= std::min(i + 1, nx - 1) && !counted; ++a) counted = wide[b * nx + a];
      if (!counted) continue;
      const double d2 = dist[k];
      const double across = (d2 < 0.5 * kFar ? std::sqrt(d2) : kInf) - o.radialAllowance;
      if (across > out.thickest) out = {across, at(k), z};
    }
  }
  return out;
}

}  // namespace plunge
