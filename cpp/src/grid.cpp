#include "grid.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "detail.hpp"
#include "plunge/error.hpp"
#include "polygon.hpp"

namespace plunge {

namespace {

struct Piece {
  Polygons poly;
  Vec2 lo, hi;
};

Piece pieceOf(Polygons p) {
  detail::Bounds b;
  for (const Loop& l : p) b.add(l);
  return {std::move(p), b.lo, b.hi};
}

// What is left, in pieces no larger than cells of `cell` mm (the band left along
// a long wall is one polygon: clipping every disk against all of it is slow).
std::vector<Piece> piecesOf(const Polygons& p, double cell) {
  std::vector<Piece> out;
  for (Polygons& c : poly::components(p)) {
    Piece k = pieceOf(std::move(c));
    size_t vertices = 0;
    for (const Loop& l : k.poly) vertices += l.size();
    if (vertices <= 200) {
      out.push_back(std::move(k));
      continue;
    }
    for (double y = k.lo.y; y < k.hi.y; y += cell)
      for (double x = k.lo.x; x < k.hi.x; x += cell) {
        Polygons part = poly::intersect(k.poly, {{{x, y}, {x + cell, y}, {x + cell, y + cell}, {x, y + cell}}});
        if (!part.empty()) out.push_back(pieceOf(std::move(part)));
      }
  }
  return out;
}

}  // namespace

void checkGridStep(double step) {
  if (!(step >= 0.0 && step <= 1.0))
    throw Error("grid.step must be 0 (the widest step that still covers) or in (0, 1] (a fraction of the diameter)");
}

CoverResult gridPlacements(const Region& region, const std::vector<double>& radii, const GridOptions& opt) {
  if (radii.empty()) throw Error("no tools given");
  checkGridStep(opt.step);
  std::vector<int> order(radii.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return radii[a] > radii[b]; });
  const double rMin = radii[order.back()];

  CoverResult res;
  const Polygons acc = accessibleRegion(region, rMin, opt.allowance);
  res.accessibleArea = poly::area(acc);
  const Vec2 lo = region.minCorner(), hi = region.maxCorner();
  std::vector<Circle> placed;
  for (size_t k = 0; k < order.size(); ++k) {
    const int t = order[k];
    const double r = radii[t];
    const double fraction = opt.step > 0.0 ? opt.step
                                           : (opt.pattern == GridPattern::Honeycomb ? std::sqrt(3.0) / 2 : std::sqrt(0.5));
    const double dx = fraction * 2 * r;
    const double dy = opt.pattern == GridPattern::Honeycomb ? dx * std::sqrt(3.0) / 2 : dx;
    // What the larger tools left, for the smaller ones.
    std::vector<Piece> left;
    if (k > 0) left = piecesOf(uncoveredRegion(acc, placed), 4 * r);
    const double need = opt.minGain * kPi * r * r;
    int row = 0;
    for (double y = lo.y + r + opt.allowance; y <= hi.y - r - opt.allowance + 1e-9; y += dy, ++row) {
      opt.progress.tick();
      const double shift = opt.pattern == GridPattern::Honeycomb && (row % 2) ? 0.5 * dx : 0.0;
      for (double x = lo.x + r + opt.allowance + shift; x <= hi.x - r - opt.allowance + 1e-9; x += dx) {
        const Vec2 c{x, y};
        if (!region.diskFits(c, r + opt.allowance)) continue;
        if (k > 0) {
          Polygons near;
          for (const Piece& p : left)
            if (p.lo.x <= x + r && p.hi.x >= x - r && p.lo.y <= y + r && p.hi.y >= y - r)
              near.insert(near.end(), p.poly.begin(), p.poly.end());
          if (near.empty() || poly::area(poly::intersect(near, {poly::disk({c, r})})) < need) continue;
        }
        res.disks.push_back({c, r, t, Stage::Packing});
      }
    }
    for (size_t i = placed.size(); i < res.disks.size(); ++i) placed.push_back({res.disks[i].center, res.disks[i].radius});
  }
  res.uncovered = uncoveredRegion(acc, placed);
  res.coveredArea = res.accessibleArea - poly::area(res.uncovered);
  return res;
}

}  // namespace plunge
