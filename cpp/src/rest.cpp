#include "plunge/rest.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "depth.hpp"
#include "material.hpp"
#include "plunge/error.hpp"
#include "plunge/geometry.hpp"

namespace plunge {

MaterialGrid materialGrid(Vec2 origin, double spacing, size_t nx, size_t ny, double top) {
  MaterialGrid g;
  g.origin = origin;
  g.spacing = spacing;
  g.nx = nx;
  g.ny = ny;
  g.top.assign(nx * ny, top);
  return g;
}

namespace {

// The lowest tip height along a move at which the cutter's surface passes
// over a cell's centre p: z(t) + profile(rho(t)) where the axis passes within
// the radius (plus kRimTolerance: the same edge cut by two paths at the same
// offset differs by their accuracy). A flat cutter is exact (z is linear in
// t: the lowest is at an end of the interval where p is under it); ball and
// bull noses are sampled finely along that interval.
class CellCut {
 public:
  explicit CellCut(const Cutter& cutter) : cutter_(cutter), reach_(cutter.radius + kRimTolerance) {}
  // Tip height to lower the cell to, or +inf where the move passes beside it.
  double lowest(const Move& m, Vec2 p, double step) const {
    const Vec2 a{m.x0, m.y0}, d{m.x1 - m.x0, m.y1 - m.y0};
    const double len2 = dot(d, d);
    double t0 = 0.0, t1 = 0.0;
    if (len2 < 1e-18) {
      if (dist(a, p) > reach_) return kNone;
    } else if (!interval(a, d, len2, p, t0, t1)) {
      return kNone;
    }
    auto z = [&](double t) { return m.z0 + t * (m.z1 - m.z0); };
    if (cutter_.shape == CutterShape::Flat) return std::min(z(t0), z(t1));
    const double length = std::sqrt(len2) * (t1 - t0);
    const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
    double best = kNone;
    for (int k = 0; k <= n; ++k) {
      const double t = t0 + (t1 - t0) * k / n;
      const double rho = std::min(dist(a + d * t, p), cutter_.radius);
      best = std::min(best, z(t) + cutterProfile(cutter_, rho));
    }
    return best;
  }

  static constexpr double kNone = std::numeric_limits<double>::infinity();

 private:
  // The t in [0, 1] where the axis passes within reach_ of p.
  bool interval(Vec2 a, Vec2 d, double len2, Vec2 p, double& t0, double& t1) const {
    const Vec2 w = p - a;
    const double tc = dot(w, d) / len2;
    const double off2 = std::max(0.0, dot(w, w) - tc * tc * len2);  // squared distance from the line
    const double r2 = reach_ * reach_ - off2;
    if (r2 < 0.0) return false;
    const double half = std::sqrt(r2 / len2);
    t0 = std::max(0.0, tc - half);
    t1 = std::min(1.0, tc + half);
    return t0 <= t1;
  }

  Cutter cutter_;
  double reach_;
};

void checkMove(const Move& m) {
  for (double v : {m.x0, m.y0, m.z0, m.x1, m.y1, m.z1})
    if (!std::isfinite(v)) throw Error("sweep: a move is not finite");
}

}  // namespace

void sweep(MaterialGrid& g, const Cutter& cutter, const std::vector<Move>& moves, const Progress& progress) {
  if (!(g.spacing > 0.0) || g.top.size() != g.nx * g.ny) throw Error("sweep: the grid is not nx * ny cells of a positive size");
  if (!(cutter.radius > 0.0)) throw Error("sweep: the cutter has no radius");
  const CellCut cut(cutter);
  const double step = 0.25 * g.spacing;
  auto index = [&](double v, double o, size_t n) {
    return std::clamp(static_cast<long>(std::floor((v - o) / g.spacing)), 0L, static_cast<long>(n) - 1);
  };
  for (size_t k = 0; k < moves.size(); ++k) {
    const Move& m = moves[k];
    checkMove(m);
    if ((k & 255) == 0) progress.tick(static_cast<double>(k) / static_cast<double>(moves.size()));
    const double r = cutter.radius;
    const double xlo = std::min(m.x0, m.x1) - r, xhi = std::max(m.x0, m.x1) + r;
    const double ylo = std::min(m.y0, m.y1) - r, yhi = std::max(m.y0, m.y1) + r;
    if (xhi < g.origin.x || yhi < g.origin.y || xlo > g.origin.x + g.spacing * g.nx ||
        ylo > g.origin.y + g.spacing * g.ny)
      continue;
    const long i0 = index(xlo, g.origin.x, g.nx), i1 = index(xhi, g.origin.x, g.nx);
    const long j0 = index(ylo, g.origin.y, g.ny), j1 = index(yhi, g.origin.y, g.ny);
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) {
        double& top = g.top[static_cast<size_t>(j) * g.nx + static_cast<size_t>(i)];
        if (top <= std::min(m.z0, m.z1)) continue;  // the tip never gets below it
        const Vec2 p{g.origin.x + (i + 0.5) * g.spacing, g.origin.y + (j + 0.5) * g.spacing};
        top = std::min(top, cut.lowest(m, p, step));
      }
  }
}

}  // namespace plunge
