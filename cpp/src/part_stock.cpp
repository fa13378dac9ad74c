#include "part_stock.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "depth.hpp"
#include "region.hpp"

namespace plunge {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Heights the stock is measured at: about this many from the floor to the top.
constexpr int kHeights = 48;
// Stock thinner than this (mm) over a sample is the raster's, not the plan's.
constexpr double kThin = 0.05;

// "No source" in the distance transform: far above any squared distance of
// a raster (at most a few thousand samples a side), and small enough that
// the differences it takes stay exact to well under a sample.
constexpr double kFar = 1e12;

// Squared Euclidean distance transform along one line (Felzenszwalb and
// Huttenlocher, "Distance transforms of sampled functions", 2012): the lower
// envelope of the parabolas (q - v)^2 + f(v). f: 0 at the sources, kFar elsewhere.
void transformLine(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v, std::vector<double>& z) {
  const int n = static_cast<int>(f.size());
  int k = 0;
  v[0] = 0;
  z[0] = -kInf;
  z[1] = kInf;
  for (int q = 1; q < n; ++q) {
    double s = ((f[q] + q * static_cast<double>(q)) - (f[v[k]] + v[k] * static_cast<double>(v[k]))) / (2.0 * (q - v[k]));
    while (s <= z[k]) {
      --k;
      s = ((f[q] + q * static_cast<double>(q)) - (f[v[k]] + v[k] * static_cast<double>(v[k]))) / (2.0 * (q - v[k]));
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInf;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    d[q] = (q - v[k]) * static_cast<double>(q - v[k]) + f[v[k]];
  }
}

// Squared distance, in samples, from every sample to the nearest one of
// `source` (kFar or more where there is none).
std::vector<double> distanceSquared(const std::vector<char>& source, size_t nx, size_t ny) {
  std::vector<double> grid(nx * ny);
  for (size_t k = 0; k < grid.size(); ++k) grid[k] = source[k] ? 0.0 : kFar;
  const size_t n = std::max(nx, ny);
  std::vector<double> f(n), d(n), z(n + 1);
  std::vector<int> v(n);
  f.resize(ny), d.resize(ny);
  for (size_t i = 0; i < nx; ++i) {  // columns
    for (size_t j = 0; j < ny; ++j) f[j] = grid[j * nx + i];
    transformLine(f, d, v, z);
    for (size_t j = 0; j < ny; ++j) grid[j * nx + i] = d[j];
  }
  f.resize(nx), d.resize(nx);
  for (size_t j = 0; j < ny; ++j) {  // rows
    std::copy(grid.begin() + static_cast<std::ptrdiff_t>(j * nx), grid.begin() + static_cast<std::ptrdiff_t>((j + 1) * nx),
              f.begin());
    transformLine(f, d, v, z);
    std::copy(d.begin(), d.end(), grid.begin() + static_cast<std::ptrdiff_t>(j * nx));
  }
  return grid;
}

}  // namespace

PartStock measurePartStock(const TriangleMesh& part, const FloorSurface& floor, const Loop& boundary,
                           const Material& material, const std::vector<Plunge>& plunges, const ToolTable& tools,
                           const PartStockOptions& o) {
  PartStock out;
  const Region outline(boundary, {});
  // One sample step of margin all round: the part's walls stand there.
  const double h = o.spacing;
  const Vec2 lo = outline.minCorner() - Vec2{2 * h, 2 * h}, hi = outline.maxCorner() + Vec2{2 * h, 2 * h};
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
  std::vector<char> inside(n, 0);
  std::vector<double> floorZ(n, -kInf);
  double lowest = kInf;
  for (size_t k = 0; k < n; ++k) {
    if (k % nx == 0) o.progress.tick();
    if (!outline.contains(at(k))) continue;
    inside[k] = 1;
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

  // At each height: the stock standing in the part's air there, above what
  // the floor stock may leave, and its distance to the part's material.
  // Up to the part's top: above it is the Job's stock over the whole part
  // (a facing pass's), not the pocket's.
  double highest = -kInf, partTop = -kInf;
  for (size_t k = 0; k < n; ++k) {
    if (inside[k]) highest = std::max(highest, stock[k]);
    if (std::isfinite(top[k])) partTop = std::max(partTop, top[k]);
  }
  const double from = lowest + o.floorAllowance, to = std::min(highest, partTop);
  if (!(to > from)) return out;
  const double step = std::max(0.25, (to - from) / kHeights);
  std::vector<char> solid(n);
  for (double z = from + 0.5 * step; z < to; z += step) {
    o.progress.tick();
    bool any = false;
    for (size_t k = 0; k < n; ++k) {
      // Material at this height seen from above; past the outline, what the
      // part does not show stands as the walls do.
      solid[k] = top[k] >= z || (!inside[k] && !std::isfinite(top[k]));
      any = any || (inside[k] && !solid[k] && stock[k] > z + kThin);
    }
    if (!any) continue;
    const std::vector<double> d2 = distanceSquared(solid, nx, ny);
    for (size_t k = 0; k < n; ++k) {
      if (!inside[k] || solid[k] || !(stock[k] > z + kThin) || d2[k] >= kFar) continue;
      // Over the floor, its stock up to the limit is the floor stock's.
      if (std::isfinite(floorZ[k]) && z <= floorZ[k] + o.floorAllowance + o.maxFloorStock + kThin) continue;
      const double left = std::sqrt(d2[k]) * h - o.radialAllowance;
      if (left > out.thickest) out = {left, at(k), z};
    }
  }
  return out;
}

}  // namespace plunge
