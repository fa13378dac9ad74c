#include "material.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "depth.hpp"

namespace plunge {

Material::Material(const std::optional<MaterialGrid>& grid, double topZ)
    : grid_(grid ? std::make_shared<const MaterialGrid>(*grid) : nullptr), top_(topZ) {}

double Material::cell(long i, long j) const {
  const MaterialGrid& g = *grid_;
  if (i < 0 || j < 0 || i >= static_cast<long>(g.nx) || j >= static_cast<long>(g.ny)) return top_;
  return std::min(top_, g.top[static_cast<size_t>(j) * g.nx + static_cast<size_t>(i)]);
}

Vec2 Material::centre(long i, long j) const {
  const MaterialGrid& g = *grid_;
  return {g.origin.x + (static_cast<double>(i) + 0.5) * g.spacing, g.origin.y + (static_cast<double>(j) + 0.5) * g.spacing};
}

void Material::range(Vec2 lo, Vec2 hi, long& i0, long& i1, long& j0, long& j1) const {
  const MaterialGrid& g = *grid_;
  auto index = [&](double v, double o, size_t n) {
    return std::clamp(static_cast<long>(std::floor((v - o) / g.spacing)), -1L, static_cast<long>(n));
  };
  i0 = index(lo.x, g.origin.x, g.nx);
  i1 = index(hi.x, g.origin.x, g.nx);
  j0 = index(lo.y, g.origin.y, g.ny);
  j1 = index(hi.y, g.origin.y, g.ny);
}

double Material::at(Vec2 p) const {
  if (!grid_) return top_;
  long i0, i1, j0, j1;
  range(p, p, i0, i1, j0, j1);
  return cell(i0, j0);
}

double Material::highestAlong(Vec2 a, Vec2 b, double r) const {
  if (!grid_) return top_;
  const Segment path{a, b};
  const double reach = r - kRimTolerance;
  long i0, i1, j0, j1;
  range({std::min(a.x, b.x) - r, std::min(a.y, b.y) - r}, {std::max(a.x, b.x) + r, std::max(a.y, b.y) + r}, i0, i1,
        j0, j1);
  // Beyond the raster (index -1 or n) the material is top_z: the range
  // reaching there says so.
  double h = -std::numeric_limits<double>::infinity();
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i) {
      const double v = cell(i, j);
      if (v > h && distanceToSegment(path, centre(i, j)) <= reach) h = v;
    }
  return h;
}

bool Material::cutsAny(Vec2 c, const Cutter& cutter, double z, const std::function<bool(Vec2)>& counts) const {
  if (!grid_) return z < top_ - kAirTolerance;
  const double reach = cutter.radius + 0.5 * grid_->spacing;
  long i0, i1, j0, j1;
  range(c - Vec2{reach, reach}, c + Vec2{reach, reach}, i0, i1, j0, j1);
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i) {
      const double v = cell(i, j);
      if (v <= z + kAirTolerance) continue;  // the profile is never below the tip
      const Vec2 p = centre(i, j);
      const double rho = dist(p, c);
      if (rho <= reach && v > z + cutterProfile(cutter, std::min(rho, cutter.radius)) + kAirTolerance && counts(p))
        return true;
    }
  return false;
}

}  // namespace plunge
