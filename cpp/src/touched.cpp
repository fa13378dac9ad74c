#include "touched.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "detail.hpp"
#include "path_walk.hpp"
#include "polygon.hpp"

namespace plunge {

namespace {

// A rapid meeting more disks than this goes over top_z (Touched::highestAlong:
// the exact test of a gap among them would cost more than the height saves).
constexpr size_t kMaxDisksPerMove = 150;
// A point of the swept disk (radius rs) at least kWitness inside it and
// kWitness outside every near disk proves an uncovered piece of pi kWitness^2
// (more than the polygon test's 1e-4 mm^2): the common case (a move over
// uncut gaps, a plunge into fresh stock), found without polygon booleans.
constexpr double kWitness = 0.01;
// The cut disks' polygons in the exact tests: inscribed (they cover less than
// the disks), within half the 0.01 mm the moved disk is shrunk by.
constexpr double kCoverChord = 0.005;

}  // namespace

long Touched::cellOf(double v) const { return static_cast<long>(std::floor(v / bucket_)); }

void Touched::add(Vec2 c, double r, double bottom) {
  disks_.push_back({{c, r}, bottom});
  grid_[detail::cellKey(cellOf(c.x), cellOf(c.y))].push_back(disks_.size() - 1);
}

// Calls f(disk) for each disk in the grid cells within `reach` of c (and one
// cell beyond): the candidates a query then tests exactly.
template <class F>
void Touched::forEachDiskNear(Vec2 c, double reach, F f) const {
  for (long j = cellOf(c.y - reach) - 1; j <= cellOf(c.y + reach) + 1; ++j)
    for (long i = cellOf(c.x - reach) - 1; i <= cellOf(c.x + reach) + 1; ++i) {
      auto it = grid_.find(detail::cellKey(i, j));
      if (it == grid_.end()) continue;
      for (size_t k : it->second) f(disks_[k]);
    }
}

std::vector<Vec2> Touched::holesNear(Vec2 c, double r, double bottom, double from, double to, size_t count) const {
  std::vector<std::pair<double, Vec2>> found;
  forEachDiskNear(c, to, [&](const Disk& d) {
    const double l = dist(d.circle.c, c);
    if (l >= from && l <= to && d.circle.r >= r - 1e-9 && d.bottom <= bottom + 1e-9) found.push_back({l, d.circle.c});
  });
  std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Vec2> out;
  for (size_t k = 0; k < found.size() && k < count; ++k) out.push_back(found[k].second);
  return out;
}

bool Touched::grazes(Vec2 c, Vec2 end, double r, double bottom, double limit) const {
  // The inner disk's polygon (inscribed) grown by its chord error: it holds the whole circle.
  Polygons rest = poly::subtract({poly::disk({end, r - 0.01}, kCoverChord)},
                                 {poly::disk({c, r + limit + kCoverChord}, kCoverChord)});
  if (poly::area(rest) <= 1e-6) return false;
  std::vector<Circle> near;
  forEachDiskNear(end, 2 * r, [&](const Disk& d) {
    if (d.bottom <= bottom + 1e-9 && dist(d.circle.c, end) < d.circle.r + r) near.push_back(d.circle);
  });
  if (crescentWitness(c, end, r - 0.01, r + limit, near)) return true;
  return !coveredBy(std::move(rest), end, std::move(near), 1e-6);
}

double Touched::highestAlong(Vec2 a, Vec2 b, double r) const {
  const double cut = highestCut(a, b, r);
  return material_.known() ? std::min(cut, material_.highestAlong(a, b, r)) : cut;
}

bool Touched::standsAbove(Vec2 a, Vec2 b, double r, double z) const {
  if (material_.known() && !(material_.highestAlong(a, b, r) > z)) return false;
  return highestCut(a, b, r, z) > z;
}

double Touched::highestCut(Vec2 a, Vec2 b, double r, double above) const {
  const Segment path{a, b};
  const Vec2 lo{std::min(a.x, b.x) - r, std::min(a.y, b.y) - r}, hi{std::max(a.x, b.x) + r, std::max(a.y, b.y) + r};
  std::vector<Circle> near;
  double highest = -std::numeric_limits<double>::infinity();
  for (long j = cellOf(lo.y) - 1; j <= cellOf(hi.y) + 1; ++j)
    for (long i = cellOf(lo.x) - 1; i <= cellOf(hi.x) + 1; ++i) {
      auto it = grid_.find(detail::cellKey(i, j));
      if (it == grid_.end()) continue;
      for (size_t k : it->second) {
        const Disk& d = disks_[k];
        if (distanceToSegment(path, d.circle.c) >= d.circle.r + r) continue;
        near.push_back(d.circle);
        highest = std::max(highest, d.bottom);
      }
    }
  // Long moves over many disks go over the top of the stock: cheaper than the
  // exact test, and never lower than the truth.
  if (near.empty() || near.size() > kMaxDisksPerMove || highest > above || uncoveredWitness(a, b, r - 0.01, near))
    return top_;  // (either way, at least `highest`)
  const double rs = r - 0.01;
  Polygons swept{poly::disk({a, rs})};
  if (dist(a, b) > 1e-9) {
    const Vec2 n = leftNormal((b - a) * (1.0 / dist(a, b))) * rs;
    swept = poly::unite({poly::disk({a, rs}), poly::disk({b, rs}), Loop{a - n, b - n, b + n, a + n}});
  }
  if (!coveredBy(swept, a, near)) return top_;
  return std::min(top_, highest);
}

// Whether the disks leave less than `tiny` mm^2 of `rest` uncut. The disks
// nearest to `from` first, one at a time, each only if it reaches what is
// left: the rest shrinks fast, so the booleans stay small (the union of 150
// disks first, then one difference, cost 20 ms a move where plunges crowd).
bool Touched::coveredBy(Polygons rest, Vec2 from, std::vector<Circle> near, double tiny) {
  std::stable_sort(near.begin(), near.end(),
                   [&](const Circle& x, const Circle& y) { return dist(x.c, from) < dist(y.c, from); });
  detail::Bounds b;
  for (const Loop& l : rest) b.add(l);
  for (const Circle& d : near) {
    if (rest.empty()) break;
    if (d.c.x + d.r < b.lo.x || d.c.x - d.r > b.hi.x || d.c.y + d.r < b.lo.y || d.c.y - d.r > b.hi.y) continue;
    rest = poly::subtract(rest, {poly::disk(d, kCoverChord)});
    b = {};
    for (const Loop& l : rest) b.add(l);
  }
  return poly::area(rest) <= tiny;
}

// A point of the moved disk (radius rs at end) kWitness inside it, beyond
// `beyond` + kWitness from c and kWitness outside every near disk: proof of
// uncut material there without polygons (most directions that graze).
bool Touched::crescentWitness(Vec2 c, Vec2 end, double rs, double beyond, const std::vector<Circle>& near) {
  const double inner = rs - kWitness;
  if (inner <= 0.0) return false;
  const int n = std::clamp(static_cast<int>(std::ceil(2 * kPi * inner / 0.25)), 24, 512);
  for (double f : {1.0, 0.98, 0.95}) {
    for (int k = 0; k < n; ++k) {
      const double t = 2 * kPi * k / n;
      const Vec2 q = end + Vec2{std::cos(t), std::sin(t)} * (f * inner);
      if (dist(q, c) < beyond + kWitness) continue;
      if (clearOf(near, q)) return true;
    }
  }
  return false;
}

// q at least kWitness outside every disk.
bool Touched::clearOf(const std::vector<Circle>& near, Vec2 q) {
  for (const Circle& d : near)
    if (dist(q, d.c) < d.r + kWitness) return false;
  return true;
}

// A point of the disk (radius rs) swept from a to b that no near disk covers,
// sampled along the move (the witness of highestAlong).
bool Touched::uncoveredWitness(Vec2 a, Vec2 b, double rs, const std::vector<Circle>& near) {
  auto uncovered = [&](Vec2 q) { return clearOf(near, q); };
  const double inner = rs - kWitness;
  if (inner <= 0.0) return false;
  const int along = std::min(64, 1 + static_cast<int>(std::ceil(dist(a, b) / (0.5 * inner))));
  for (int s = 0; s <= along; ++s) {
    const Vec2 q = pointAlong(a, b, static_cast<double>(s) / along);
    if (uncovered(q)) return true;
    for (int k = 0; k < 24; ++k) {
      const double t = 2 * kPi * k / 24;
      for (double f : {0.5, 1.0})
        if (uncovered(q + Vec2{std::cos(t), std::sin(t)} * (f * inner))) return true;
    }
  }
  return false;
}

}  // namespace plunge
