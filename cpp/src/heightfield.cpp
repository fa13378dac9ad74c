#include "heightfield.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace plunge {

HeightField::HeightField(Vec2 lo, Vec2 hi, double spacing, double topZ) : lo_(lo), h_(spacing), top_(topZ) {
  nx_ = std::max<long>(1, static_cast<long>(std::ceil((hi.x - lo.x) / h_)));
  ny_ = std::max<long>(1, static_cast<long>(std::ceil((hi.y - lo.y) / h_)));
  z_.assign(static_cast<size_t>(nx_ * ny_), static_cast<float>(topZ));
}

void HeightField::lowerTo(const Material& material) {
  if (!material.known()) return;
  for (long j = 0; j < ny_; ++j)
    for (long i = 0; i < nx_; ++i) {
      // Sampled at the centre, as the plunges cut it (the material's edges
      // are already taken in by its resolution, material.hpp).
      float& cell = z_[j * nx_ + i];
      cell = std::min(cell, static_cast<float>(material.at(centre(i, j))));
    }
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

bool HeightField::meetsMaterial(Vec2 c, const Cutter& cutter, double z, double margin) const {
  bool met = false;
  forEachMaterialCell(c, cutter, z, margin, [&](Vec2) { return !(met = true); });
  return met;
}

double HeightField::bite(Vec2 from, Vec2 c, const Cutter& cutter, double z, double margin) const {
  double deepest = -1.0;
  forEachMaterialCell(c, cutter, z, margin,
                      [&](Vec2 q) {
                        deepest = std::max(deepest, dist(q, from) - cutter.radius);
                        return true;
                      });
  return deepest;
}

HeightField::Contact HeightField::contact(Vec2 c, const Cutter& cutter, double z, double coreRadius) const {
  Contact out;
  const double r = cutter.radius;
  auto material = [&](Vec2 p, double rho) {
    const double above = heightAt(p) - (z + cutterProfile(cutter, rho));
    return above > kEngagementSkin ? above : -1.0;
  };
  // Cells of the disk: what is there, how deep, the core.
  const long i0 = static_cast<long>(std::floor((c.x - r - lo_.x) / h_));
  const long j0 = static_cast<long>(std::floor((c.y - r - lo_.y) / h_));
  const long m = static_cast<long>(std::ceil(2 * r / h_)) + 2;
  int freeCells = 0;
  for (long j = j0; j < j0 + m; ++j)
    for (long i = i0; i < i0 + m; ++i) {
      const Vec2 p = centre(i, j);
      const double rho = dist(p, c);
      if (rho > r) continue;
      const double above = material(p, rho);
      if (above < 0) {
        ++freeCells;
        continue;
      }
      ++out.materialCells;
      out.deepest = std::max(out.deepest, above);
      if (rho <= coreRadius) out.coreClear = false;
    }
  if (out.materialCells == 0) return out;
  out.solid = freeCells == 0;
  return out;
}

double heightFieldSpacing(Vec2 lo, Vec2 hi, double smallestRadius, double smallestLimit) {
  const double fine = std::min(smallestRadius / 6, smallestLimit / 4);
  const double area = std::max(1e-9, (hi.x - lo.x) * (hi.y - lo.y));
  return std::max(fine, std::sqrt(area / 4e6));
}

}  // namespace plunge
