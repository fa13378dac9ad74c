#include "depth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "detail.hpp"
#include "plunge/error.hpp"
#include "plunge/optimizer.hpp"
#include "plunge/progress.hpp"

namespace plunge {

using namespace detail;

namespace {

// Compass search for a maximum of f: from x (where f is v), move by the first
// direction x + d step that rises, halve the step when none does, down to minStep.
template <class Point, class F>
double climb(Point x, double v, double step, double minStep, const std::vector<Point>& directions, const F& f) {
  while (step > minStep) {
    bool moved = false;
    for (const Point& d : directions) {
      const double w = f(x + d * step);
      if (w > v) {
        v = w;
        x = x + d * step;
        moved = true;
        break;
      }
    }
    if (!moved) step *= 0.5;
  }
  return v;
}

// The optimizer's budget for one plunge's search: far above what it needs
// (a few thousand evaluations); past it, the plunge's depth is sampled densely.
constexpr int kPlungeEvaluations = 60000;

// Maximum of g over the circle of radius r around c (eq. 4.84), by the global
// optimizer in one periodic variable, and the angle where it is; -inf if g is
// nowhere finite on it. converged: false when the optimizer ran out of budget.
struct RimMax {
  double value = -kInf;
  double angle = 0.0;
};
RimMax rimMaximum(const std::function<double(Vec2)>& g, Vec2 c, double r, double spacing, bool& converged) {
  OptimizeOptions opt;
  opt.periodic = true;
  opt.skipNonFinite = true;
  opt.samples = std::clamp(static_cast<int>(std::ceil(2 * kPi * r / spacing)), 48, 720);
  opt.maxEvaluations = kPlungeEvaluations;
  try {
    const OptimizeResult o = optimize(
        [&](const double* t) { return g({c.x + r * std::cos(t[0]), c.y + r * std::sin(t[0])}); }, {{0.0, 2 * kPi}},
        Goal::Maximize, opt);
    converged = converged && o.converged;
    return {o.value, o.x[0]};
  } catch (const Error&) {
    return {};  // no floor anywhere on the rim
  }
}

// A corner this thin (the flat cutter grown by the floor allowance) is searched
// on rings across it rather than by a search over the whole disk.
constexpr double kThinCorner = 0.5;
constexpr double kRingStep = 0.1;

// The highest contact of a thin-cornered bull nose in its corner's annulus:
// the maximum on rings across it (the flat's rim included), polished by a
// compass search in (angle, radius). The flat's inside touches at a floor peak
// or on that rim, so this and the peaks are the whole drop-cutter (4.4).
double cornerMaximum(const std::function<double(Vec2)>& lift, Vec2 c, const Cutter& cutter, double spacing,
                     bool& converged) {
  const double flat = cutter.radius - cutter.cornerRadius;
  const int n = std::max(2, static_cast<int>(std::ceil(cutter.cornerRadius / kRingStep)));
  RimMax best;
  double bestRho = flat;
  for (int k = 0; k <= n; ++k) {
    const double rho = flat + cutter.cornerRadius * k / n;
    const RimMax m = rimMaximum(lift, c, rho, spacing, converged);
    if (m.value > best.value) best = m, bestRho = rho;
  }
  if (!std::isfinite(best.value)) return best.value;
  auto polar = [&](Vec2 p) {  // p = (angle, radius)
    if (p.y < flat - 1e-12 || p.y > cutter.radius) return kNaN;
    return lift({c.x + p.y * std::cos(p.x), c.y + p.y * std::sin(p.x)});
  };
  const double step = cutter.cornerRadius / n;
  const std::vector<Vec2> compass{{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {0.7071, 0.7071}, {-0.7071, 0.7071},
                                  {0.7071, -0.7071}, {-0.7071, -0.7071}};
  // The angle moves by step / radius: about as far along the rim as the radius moves.
  const double scale = 1.0 / std::max(bestRho, step);
  auto scaled = [&](Vec2 p) { return polar({p.x * scale, p.y}); };
  return climb(Vec2{best.angle / scale, bestRho}, best.value, step, 1e-9, compass, scaled);
}

}  // namespace

DepthSolver::DepthSolver(const FloorSurface& floor, Vec2 lo, Vec2 hi, double spacing, const Progress& progress,
                         std::shared_ptr<const FloorSurface> part)
    : floor_(floor), part_(std::move(part)), spacing_(spacing) {
  if (floor.isFlat()) return;
  PeakSearch found = floor.peaks(lo, hi, spacing, progress);
  peaks_ = std::move(found.points);
  peakFallbacks_ = found.fallbacks;
}

double DepthSolver::stopHeight(Vec2 c, const Cutter& cutter) const {
  return std::max(floorStopHeight(c, cutter), partStopHeight(c, cutter));
}

double DepthSolver::partStopHeight(Vec2 c, const Cutter& cutter) const {
  if (!part_) return -kInf;
  const std::optional<double> z = part_->exactStopHeight(c, cutter);
  return z && std::isfinite(*z) ? *z : -kInf;
}

double DepthSolver::floorStopHeight(Vec2 c, const Cutter& cutter) const {
  if (floor_.isFlat()) return floor_.height(c);
  if (const std::optional<double> z = floor_.exactStopHeight(c, cutter)) {  // a mesh: drop-cutter
    if (!std::isfinite(*z)) throw Error("no floor under the plunge at " + formatPoint(c));
    return *z;
  }
  bool converged = true;
  const double z = searchedStopHeight(c, cutter, converged);
  if (converged) return z;
  // The optimizer ran out of budget: a dense drop-cutter sample, refined
  // locally, at a tenth of the solver's cells (never above the search's own).
  ++*depthFallbacks_;
  return std::max(z, stopHeightBruteForce(floor_, c, cutter, std::min(0.1 * spacing_, 0.05 * cutter.radius)));
}

double DepthSolver::searchedStopHeight(Vec2 c, const Cutter& cutter, bool& converged) const {
  const double R = cutter.radius;
  auto lift = [&](Vec2 q) {  // floor height minus the cutter's profile above its tip
    const double rho = dist(q, c);
    if (rho > R * (1 + 1e-12)) return kNaN;
    return floor_.height(q) - cutterProfile(cutter, rho);
  };
  double best = rimMaximum(lift, c, R, spacing_, converged).value;
  // Peaks of the floor inside the disk (eq. 4.83 and the thesis's local maxima).
  std::vector<std::vector<double>> inner;
  for (const Vec3& p : peaks_)
    if (dist({p.x, p.y}, c) < R) {
      best = std::max(best, p.z - cutterProfile(cutter, dist({p.x, p.y}, c)));
      inner.push_back({p.x, p.y});
    }
  if (cutter.shape == CutterShape::Bull && cutter.cornerRadius <= kThinCorner) {
    best = std::max(best, cornerMaximum(lift, c, cutter, spacing_, converged));
  } else if (cutter.shape != CutterShape::Flat) {
    // Drop-cutter: the touching point need not be a peak of the floor.
    OptimizeOptions opt;
    opt.skipNonFinite = true;
    opt.samples = std::clamp(static_cast<int>(std::ceil(2 * R / spacing_)) + 1, 17, 61);
    opt.starts = inner;
    opt.maxEvaluations = kPlungeEvaluations;
    try {
      const OptimizeResult o = optimize([&](const double* q) { return lift({q[0], q[1]}); },
                                        {{c.x - R, c.x + R}, {c.y - R, c.y + R}}, Goal::Maximize, opt);
      best = std::max(best, o.value);
      converged = converged && o.converged;
    } catch (const Error&) {
      // no floor under the disk: reported below unless the rim found some
    }
  }
  if (!std::isfinite(best)) throw Error("no floor under the plunge at " + formatPoint(c));
  return best;
}

double DepthSolver::plungeHeight(Vec2 c, const Cutter& cutter, double floorAllowance, double radialAllowance) const {
  // The floor allowance is a thickness normal to the floor, as a finishing
  // pass leaves it: the cutter offset by it in every direction (its tip that
  // much lower) touches the floor where the cutter keeps it. Added vertically
  // instead, a slope of angle t would keep only cos(t) of it.
  const Cutter around = floorAllowance > 0.0 ? grownAround(cutter, floorAllowance) : cutter;
  double z = -kInf;
  try {
    z = floor_.isFlat() ? floorStopHeight(c, cutter) + floorAllowance : floorStopHeight(c, around) + floorAllowance;
    // Beside the cutter the floor keeps the radial allowance: the cutter grown
    // sideways by it (a flat one wider, a ball or bull nose with a flat of the
    // allowance at its centre) must not touch the floor either. Where the floor
    // rises more than the floor allowance within the radial allowance beyond the
    // rim (a fillet rising into its wall) this holds the cutter up; a step
    // between two selected levels becomes a wall of the lower one.
    if (!floor_.isFlat() && radialAllowance > 0.0)
      z = std::max(z, floorStopHeight(c, grownSideways(cutter, radialAllowance)));
  } catch (const Error&) {
    if (!part_) throw;  // no floor under the cutter: the part may still be
  }
  // The part keeps both allowances too: a face of it over the pocket that no
  // outline shows (an overhang's underside beside the cutter, a neighbour's
  // floor) holds the cutter up before it enters.
  if (part_) {
    z = std::max(z, partStopHeight(c, around) + floorAllowance);
    if (radialAllowance > 0.0) z = std::max(z, partStopHeight(c, grownSideways(cutter, radialAllowance)));
    if (!std::isfinite(z)) throw Error("no floor under the plunge at " + formatPoint(c));
  }
  return z;
}

double DepthSolver::plungeHeightAtLeast(Vec2 c, const Cutter& cutter, double floorAllowance,
                                        double radialAllowance) const {
  // Offset by the floor allowance, the cutter's sag at the rim is no larger
  // (a larger ball or corner sags less), so the floor there plus the
  // allowance less the rim's profile bounds plungeHeight's first term; grown
  // sideways, its profile at r + allowance is the rim's, which bounds the second.
  double low = -std::numeric_limits<double>::infinity();
  auto ring = [&](double rho, double lift) {
    for (int a = 0; a < 16; ++a) {
      const double t = a * kPi / 8;
      const double z = floor_.height(c + Vec2{std::cos(t), std::sin(t)} * rho);
      if (!std::isnan(z)) low = std::max(low, z + lift);
    }
  };
  const double rimProfile = cutterProfile(cutter, cutter.radius);
  ring(cutter.radius, floorAllowance - rimProfile);
  if (!floor_.isFlat() && radialAllowance > 0.0) ring(cutter.radius + radialAllowance, -rimProfile);
  return low;
}

Cutter grownSideways(const Cutter& cutter, double by) {
  Cutter g = cutter;
  g.radius += by;
  if (cutter.shape == CutterShape::Ball) {
    g.shape = CutterShape::Bull;
    g.cornerRadius = cutter.radius;
  }
  return g;
}

Cutter grownAround(const Cutter& cutter, double by) {
  Cutter g = cutter;
  g.radius += by;
  if (cutter.shape == CutterShape::Flat) {
    g.shape = CutterShape::Bull;
    g.cornerRadius = by;
  } else if (cutter.shape == CutterShape::Bull) {
    g.cornerRadius += by;
  }
  return g;
}

double stopHeightBruteForce(const FloorSurface& floor, Vec2 c, const Cutter& cutter, double h) {
  const double R = cutter.radius;
  auto lift = [&](Vec2 q) {
    const double rho = dist(q, c);
    if (rho > R * (1 + 1e-12)) return kNaN;
    const double z = floor.height(q);
    return std::isfinite(z) ? z - cutterProfile(cutter, rho) : kNaN;
  };
  // Every sample inside the disk and along its rim.
  std::vector<std::pair<double, Vec2>> inner, rim;
  for (double y = c.y - R; y <= c.y + R; y += h)
    for (double x = c.x - R; x <= c.x + R; x += h) {
      const double v = lift({x, y});
      if (std::isfinite(v)) inner.push_back({v, {x, y}});
    }
  const int n = std::max(16, static_cast<int>(std::ceil(2 * kPi * R / h)));
  for (int k = 0; k < n; ++k) {
    const double t = 2 * kPi * k / n;
    const double v = lift({c.x + R * std::cos(t), c.y + R * std::sin(t)});
    if (std::isfinite(v)) rim.push_back({v, {t, 0}});
  }
  if (inner.empty() && rim.empty()) throw Error("no floor under the plunge at " + formatPoint(c));
  auto byValue = [](const auto& a, const auto& b) { return a.first > b.first; };
  std::sort(inner.begin(), inner.end(), byValue);
  std::sort(rim.begin(), rim.end(), byValue);
  double best = -kInf;
  // Compass search from the best samples: in the plane inside, along the rim on it.
  const std::vector<Vec2> compass{{1, 0},           {-1, 0},          {0, 1},           {0, -1},
                                  {0.7071, 0.7071}, {-0.7071, 0.7071}, {0.7071, -0.7071}, {-0.7071, -0.7071}};
  for (size_t k = 0; k < std::min<size_t>(6, inner.size()); ++k)
    best = std::max(best, climb(inner[k].second, inner[k].first, h, 1e-10, compass, lift));
  auto onRim = [&](double t) { return lift({c.x + R * std::cos(t), c.y + R * std::sin(t)}); };
  for (size_t k = 0; k < std::min<size_t>(6, rim.size()); ++k)
    best = std::max(best, climb(rim[k].second.x, rim[k].first, h / R, 1e-12, std::vector<double>{1.0, -1.0}, onRim));
  return best;
}

}  // namespace plunge
