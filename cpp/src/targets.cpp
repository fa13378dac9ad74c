#include "targets.hpp"

#include <algorithm>

namespace plunge {

Targets::Targets(const std::vector<Plunge>& planned, const Cutter& cutter, const HeightField& stock,
                 const Progress& progress)
    : bucket_(cutter.radius) {
  std::unordered_map<long long, size_t> cell;
  for (const Plunge& p : planned) {
    progress.tick();
    addDisk(p, cutter, stock, cell);
  }
  for (size_t k = 0; k < points_.size(); ++k) {
    if (k % 4096 == 0) progress.tick();
    grid_[detail::cellKeyOf(points_[k].p, bucket_)].push_back(k);
  }
  left_ = points_.size();
}

void Targets::addDisk(const Plunge& p, const Cutter& cutter, const HeightField& stock,
                      std::unordered_map<long long, size_t>& cell) {
  const double h = stock.spacing();
  const Vec2 origin = stock.cellCentre({0.0, 0.0});
  const Vec2 c{p.x, p.y};
  const long n = std::lround(std::ceil(2 * cutter.radius / h)) + 1;
  const Vec2 first = stock.cellCentre(c - Vec2{cutter.radius, cutter.radius});
  for (long j = 0; j <= n; ++j)
    for (long i = 0; i <= n; ++i) {
      const Vec2 q = first + Vec2{i * h, j * h};
      const double rho = dist(q, c);
      if (rho > cutter.radius) continue;
      const double z = p.z + cutterProfile(cutter, rho);
      auto [it, fresh] = cell.try_emplace(
          detail::cellKey(std::lround((q.x - origin.x) / h), std::lround((q.y - origin.y) / h)), points_.size());
      if (fresh) {
        points_.push_back({q, z, false, false});
      } else {
        points_[it->second].z = std::min(points_[it->second].z, z);
      }
    }
}

int Targets::gain(Vec2 c, const Cutter& cutter, double z, const HeightField& stock) const {
  int n = 0;
  forEachOpen(c, cutter.radius, [&](size_t k) {
    if (z + cutterProfile(cutter, dist(points_[k].p, c)) < stock.heightAt(points_[k].p) - kEngagementSkin) ++n;
  });
  return n;
}

int Targets::open(Vec2 c, double r) const {
  int n = 0;
  forEachOpen(c, r, [&](size_t) { ++n; }, false);
  return n;
}

void Targets::defer(Vec2 c, const Cutter& cutter, double z, const HeightField& stock) {
  forEachOpen(c, cutter.radius, [&](size_t k) {
    if (z + cutterProfile(cutter, dist(points_[k].p, c)) >= stock.heightAt(points_[k].p) - kEngagementSkin)
      points_[k].deferred = true;
  }, false);
}

void Targets::update(Vec2 c, double r, const HeightField& stock) {
  forEachOpen(c, r, [&](size_t k) {
    if (stock.heightAt(points_[k].p) <= std::max(points_[k].z + kEngagementSkin, points_[k].enough)) {
      points_[k].done = true;
      --left_;
    }
  });
}

}  // namespace plunge
