#include "cuts.hpp"

#include <algorithm>
#include <cmath>

#include "depth.hpp"

namespace plunge {

namespace {

// Radii of the first pass per full turn (0.25 degrees apart), and the steps
// each of the best few is refined in, either side.
constexpr int kDirections = 1440;
constexpr int kRefineSteps = 24;
constexpr int kRefined = 4;
// Pieces a cut's span along a radius is judged in where the two tools'
// profiles make the depth vary along it (ball and bull noses).
constexpr int kProfilePieces = 16;

struct Span {
  double t0, t1;
};

// The parts of the radius along u (t in [0, r]) where the material before
// stands no higher than the plunge's surface (+ skin), sampled every half cell.
void materialSpans(const Material& material, double skin, Vec2 c, Vec2 u, const Cutter& cutter, double z,
                   std::vector<Span>& spans) {
  const double r = cutter.radius, step = 0.5 * material.spacing();
  const int n = std::max(1, static_cast<int>(std::ceil(r / step)));
  double from = -1.0;
  for (int k = 0; k <= n; ++k) {
    const double t = r * k / n;
    const bool cleared = material.at(c + u * t) <= z + cutterProfile(cutter, t) + skin;
    if (cleared && from < 0.0) from = std::max(0.0, t - 0.5 * r / n);
    if (!cleared && from >= 0.0) {
      spans.push_back({from, t - 0.5 * r / n});
      from = -1.0;
    }
  }
  if (from >= 0.0) spans.push_back({from, r});
}

}  // namespace

Cuts::Cuts(double skin) : skin_(skin) {}
Cuts::Cuts(double skin, const Material& material) : skin_(skin), material_(material) {}

long long Cuts::key(long i, long j) const {
  return static_cast<long long>((static_cast<unsigned long long>(i) << 32) ^
                                (static_cast<unsigned long long>(j) & 0xffffffffULL));
}

void Cuts::add(Vec2 c, const Cutter& cutter, double z) {
  cuts_.push_back({c, cutter, z});
  if (2 * cutter.radius > cell_) {  // buckets as wide as the largest cut: rebuilt
    cell_ = 2 * cutter.radius;
    grid_.clear();
    for (size_t k = 0; k < cuts_.size(); ++k)
      grid_[key(static_cast<long>(std::floor(cuts_[k].c.x / cell_)), static_cast<long>(std::floor(cuts_[k].c.y / cell_)))]
          .push_back(k);
    return;
  }
  grid_[key(static_cast<long>(std::floor(c.x / cell_)), static_cast<long>(std::floor(c.y / cell_)))].push_back(
      cuts_.size() - 1);
}

std::vector<const Cuts::Cut*> Cuts::near(Vec2 c, double r) const {
  std::vector<const Cut*> out;
  if (cuts_.empty()) return out;
  const double reach = r + 0.5 * cell_;
  const long i0 = static_cast<long>(std::floor((c.x - reach) / cell_)), i1 = static_cast<long>(std::floor((c.x + reach) / cell_));
  const long j0 = static_cast<long>(std::floor((c.y - reach) / cell_)), j1 = static_cast<long>(std::floor((c.y + reach) / cell_));
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i) {
      const auto it = grid_.find(key(i, j));
      if (it == grid_.end()) continue;
      for (size_t k : it->second)
        if (dist(cuts_[k].c, c) < r + cuts_[k].cutter.radius) out.push_back(&cuts_[k]);
    }
  return out;
}

double Cuts::engagement(Vec2 c, const Cutter& cutter, double z, double enough) const {
  const double r = cutter.radius;
  const std::vector<const Cut*> cuts = near(c, r);
  if (cuts.empty() && !material_.known()) return r;
  // Whether a cut leaves no material (beyond the skin) at the point t along
  // the radius u: its cutting surface there no higher than this plunge's.
  auto clears = [&](const Cut& q, Vec2 u, double t) {
    const Vec2 p = c + u * t;
    const double rho = dist(p, q.c);
    if (rho > q.cutter.radius) return false;
    return q.z + cutterProfile(q.cutter, rho) <= z + cutterProfile(cutter, t) + skin_;
  };
  const bool flat = cutter.shape == CutterShape::Flat;
  std::vector<Span> spans;
  // The material along the radius at angle a: r less what the cuts clear of it.
  auto along = [&](double a) {
    const Vec2 u{std::cos(a), std::sin(a)};
    spans.clear();
    for (const Cut* q : cuts) {
      const Vec2 d = c - q->c;
      const double b = d.x * u.x + d.y * u.y, disc = b * b - (d.x * d.x + d.y * d.y - q->cutter.radius * q->cutter.radius);
      if (disc <= 0) continue;
      const double s = std::sqrt(disc);
      const double t0 = std::max(0.0, -b - s), t1 = std::min(r, -b + s);
      if (t1 <= t0) continue;
      if (flat && q->cutter.shape == CutterShape::Flat) {  // the same depth all along
        if (q->z <= z + skin_) spans.push_back({t0, t1});
        continue;
      }
      if (clears(*q, u, t0) && clears(*q, u, t1) && clears(*q, u, 0.5 * (t0 + t1))) {
        spans.push_back({t0, t1});
        continue;
      }
      const double piece = (t1 - t0) / kProfilePieces;
      for (int k = 0; k < kProfilePieces; ++k)
        if (clears(*q, u, t0 + (k + 0.5) * piece)) spans.push_back({t0 + k * piece, t0 + (k + 1) * piece});
    }
    if (material_.known()) materialSpans(material_, skin_, c, u, cutter, z, spans);
    std::sort(spans.begin(), spans.end(), [](const Span& x, const Span& y) { return x.t0 < y.t0; });
    double covered = 0.0, end = 0.0;
    for (const Span& s : spans) {
      const double from = std::max(s.t0, end);
      if (s.t1 > from) {
        covered += s.t1 - from;
        end = s.t1;
      }
    }
    return std::max(0.0, r - covered);
  };
  // The radii: evenly, and through every corner of the uncut material.
  std::vector<double> angles;
  for (int k = 0; k < kDirections; ++k) angles.push_back(2 * kPi * k / kDirections);
  auto corner = [&](Vec2 p) {
    if (dist(p, c) >= r || dist(p, c) < 1e-12) return;
    const double a = std::atan2(p.y - c.y, p.x - c.x);
    for (double e : {-1e-7, 0.0, 1e-7}) angles.push_back(a + e);
  };
  auto crossings = [&](Vec2 a, double ra, Vec2 b, double rb) {
    const double d = dist(a, b);
    if (d <= 1e-12 || d >= ra + rb || d <= std::fabs(ra - rb)) return;
    const double x = (d * d + ra * ra - rb * rb) / (2 * d), h = std::sqrt(std::max(0.0, ra * ra - x * x));
    const Vec2 u = (b - a) * (1.0 / d), n{-u.y, u.x};
    corner(a + u * x + n * h);
    corner(a + u * x - n * h);
  };
  for (size_t i = 0; i < cuts.size(); ++i) {
    crossings(cuts[i]->c, cuts[i]->cutter.radius, c, r - 1e-9);
    for (size_t j = i + 1; j < cuts.size(); ++j)
      crossings(cuts[i]->c, cuts[i]->cutter.radius, cuts[j]->c, cuts[j]->cutter.radius);
  }
  std::vector<std::pair<double, double>> best;  // (material, angle), the few largest
  for (double a : angles) {
    const double m = along(a);
    if (m > enough) return m;
    best.push_back({m, a});
  }
  std::partial_sort(best.begin(), best.begin() + std::min<size_t>(kRefined, best.size()), best.end(),
                    [](const auto& x, const auto& y) { return x.first > y.first; });
  double most = best.front().first;
  const double step = 2 * kPi / kDirections;
  for (size_t k = 0; k < std::min<size_t>(kRefined, best.size()); ++k)
    for (int s = -kRefineSteps; s <= kRefineSteps; ++s) {
      most = std::max(most, along(best[k].second + s * step / kRefineSteps));
      if (most > enough) return most;
    }
  return most;
}

}  // namespace plunge
