#include "plunge/heightfield.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plunge {

HeightField::HeightField(Vec2 lo, Vec2 hi, double spacing, double topZ) : lo_(lo), h_(spacing), top_(topZ) {
  nx_ = std::max<long>(1, static_cast<long>(std::ceil((hi.x - lo.x) / h_)));
  ny_ = std::max<long>(1, static_cast<long>(std::ceil((hi.y - lo.y) / h_)));
  z_.assign(static_cast<size_t>(nx_ * ny_), static_cast<float>(topZ));
}

double HeightField::at(long i, long j) const {
  if (i < 0 || j < 0 || i >= nx_ || j >= ny_) return top_;
  return z_[j * nx_ + i];
}

void HeightField::cut(Vec2 c, const Cutter& cutter, double z) {
  const double r = cutter.radius;
  const long i0 = std::max(0L, static_cast<long>(std::floor((c.x - r - lo_.x) / h_)));
  const long i1 = std::min(nx_ - 1, static_cast<long>(std::floor((c.x + r - lo_.x) / h_)));
  const long j0 = std::max(0L, static_cast<long>(std::floor((c.y - r - lo_.y) / h_)));
  const long j1 = std::min(ny_ - 1, static_cast<long>(std::floor((c.y + r - lo_.y) / h_)));
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i) {
      const double rho = dist(centre(i, j), c);
      if (rho > r) continue;
      float& cell = z_[j * nx_ + i];
      cell = std::min(cell, static_cast<float>(z + cutterProfile(cutter, rho)));
    }
}

double HeightField::heightAt(Vec2 p) const {
  return at(static_cast<long>(std::floor((p.x - lo_.x) / h_)), static_cast<long>(std::floor((p.y - lo_.y) / h_)));
}

double HeightField::highest(Vec2 c, double r) const { return highestAlong(c, c, r); }

double HeightField::highestAlong(Vec2 a, Vec2 b, double r) const {
  // Cells whose centre lies within r + half a diagonal of the segment: the
  // swept disk touches them.
  const double reach = r + 0.71 * h_;
  const long i0 = static_cast<long>(std::floor((std::min(a.x, b.x) - reach - lo_.x) / h_));
  const long i1 = static_cast<long>(std::floor((std::max(a.x, b.x) + reach - lo_.x) / h_));
  const long j0 = static_cast<long>(std::floor((std::min(a.y, b.y) - reach - lo_.y) / h_));
  const long j1 = static_cast<long>(std::floor((std::max(a.y, b.y) + reach - lo_.y) / h_));
  double best = -std::numeric_limits<double>::infinity();
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i)
      if (distanceToSegment({a, b}, centre(i, j)) <= reach) best = std::max(best, at(i, j));
  return best;
}

int HeightField::materialCells(Vec2 c, const Cutter& cutter, double z, double margin) const {
  int n = 0;
  forEachMaterialCell(c, cutter, z, margin, [&](Vec2) { ++n; });
  return n;
}

double HeightField::bite(Vec2 from, Vec2 c, const Cutter& cutter, double z, double margin) const {
  double deepest = -1.0;
  forEachMaterialCell(c, cutter, z, margin,
                      [&](Vec2 q) { deepest = std::max(deepest, dist(q, from) - cutter.radius); });
  return deepest;
}

namespace {

// Squared Euclidean distance transform of one row or column (Felzenszwalb and
// Huttenlocher's lower envelope of parabolas): f holds 0 on sources, a large
// value elsewhere.
void distance1d(std::vector<double>& f, std::vector<double>& d, std::vector<int>& v, std::vector<double>& z) {
  const int n = static_cast<int>(f.size());
  const double inf = std::numeric_limits<double>::infinity();
  int k = 0;
  v[0] = 0;
  z[0] = -inf;
  z[1] = inf;
  for (int q = 1; q < n; ++q) {
    double s;
    while (true) {
      s = ((f[q] + q * q) - (f[v[k]] + v[k] * v[k])) / (2.0 * q - 2.0 * v[k]);
      if (s <= z[k] && k > 0) --k;
      else break;
    }
    if (s <= z[k]) {  // k == 0 and the new parabola wins everywhere
      v[0] = q;
      z[0] = -inf;
      z[1] = inf;
      continue;
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = inf;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    d[q] = (q - v[k]) * (q - v[k]) + f[v[k]];
  }
}

}  // namespace

HeightField::Contact HeightField::contact(Vec2 c, const Cutter& cutter, double z, double coreRadius) const {
  Contact out;
  const double r = cutter.radius;
  const long i0 = static_cast<long>(std::floor((c.x - r - lo_.x) / h_));
  const long j0 = static_cast<long>(std::floor((c.y - r - lo_.y) / h_));
  const long m = static_cast<long>(std::ceil(2 * r / h_)) + 2;
  // In the disk: material (1), free (0); outside the disk: -1.
  std::vector<signed char> kind(static_cast<size_t>(m * m), -1);
  int freeCells = 0;
  for (long j = 0; j < m; ++j)
    for (long i = 0; i < m; ++i) {
      const Vec2 p = centre(i0 + i, j0 + j);
      const double rho = dist(p, c);
      if (rho > r) continue;
      const double above = at(i0 + i, j0 + j) - (z + cutterProfile(cutter, rho));
      const bool material = above > kEngagementSkin;
      kind[j * m + i] = material ? 1 : 0;
      if (material) {
        ++out.materialCells;
        out.deepest = std::max(out.deepest, above);
        if (rho <= coreRadius) out.coreClear = false;
      } else {
        ++freeCells;
      }
    }
  if (out.materialCells == 0) return out;
  if (freeCells == 0) {
    out.solid = true;
    out.engagement = 2 * r;
    return out;
  }
  // Distance of each material cell to the nearest free cell of the disk.
  const double big = 1e12;  // far above any squared distance in cells, small enough to keep precision
  std::vector<double> g(static_cast<size_t>(m * m));
  for (size_t k = 0; k < g.size(); ++k) g[k] = kind[k] == 0 ? 0.0 : big;
  std::vector<double> f(m), d(m), zz(m + 1);
  std::vector<int> v(m);
  for (long j = 0; j < m; ++j) {
    for (long i = 0; i < m; ++i) f[i] = g[j * m + i];
    distance1d(f, d, v, zz);
    for (long i = 0; i < m; ++i) g[j * m + i] = d[i];
  }
  double worst = 0.0;
  for (long i = 0; i < m; ++i) {
    for (long j = 0; j < m; ++j) f[j] = g[j * m + i];
    distance1d(f, d, v, zz);
    for (long j = 0; j < m; ++j)
      if (kind[j * m + i] == 1) worst = std::max(worst, d[j]);
  }
  out.engagement = std::min(2 * r, std::sqrt(worst) * h_);
  return out;
}

double heightFieldSpacing(Vec2 lo, Vec2 hi, double smallestRadius, double smallestLimit) {
  const double fine = std::min(smallestRadius / 6, smallestLimit / 4);
  const double area = std::max(1e-9, (hi.x - lo.x) * (hi.y - lo.y));
  return std::max(fine, std::sqrt(area / 4e6));
}

}  // namespace plunge
