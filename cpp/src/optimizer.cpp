#include "plunge/optimizer.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "detail.hpp"
#include "plunge/error.hpp"

namespace plunge {

namespace {

using detail::kInf;
using detail::kNaN;

// Evaluations between calls of OptimizeOptions::poll.
constexpr int kPollEvery = 32;
// A finite-difference step nearer the box's face than this is one-sided: a
// step of 1e-17 would make the gradient, and then BFGS's update, blow up.
constexpr double kMinStep = 1e-9;


// The function to minimise in normalised coordinates u in [0, 1]^d.
class Problem {
 public:
  Problem(const Objective& f, const std::vector<std::pair<double, double>>& bounds, Goal goal,
          const OptimizeOptions& opt)
      : f_(f), d_(static_cast<int>(bounds.size())), sign_(goal == Goal::Maximize ? -1.0 : 1.0), opt_(opt) {
    for (const auto& b : bounds) {
      lo_.push_back(b.first);
      span_.push_back(b.second - b.first);
    }
  }

  int dims() const { return d_; }
  double sign() const { return sign_; }
  int evaluations() const { return evaluations_; }

  std::vector<double> toX(const Eigen::VectorXd& u) const {
    std::vector<double> x(d_);
    for (int i = 0; i < d_; ++i) x[i] = lo_[i] + span_[i] * u[i];
    return x;
  }

  bool exhausted() const { return evaluations_ >= opt_.maxEvaluations; }

  // Objective to minimise; +inf outside the domain when allowed, and at a
  // point the arithmetic made non-finite (never passed on to f).
  double g(const Eigen::VectorXd& u) {
    if (!u.allFinite()) return kInf;
    const std::vector<double> x = toX(u);
    if (++evaluations_ % kPollEvery == 0 && opt_.poll) opt_.poll();
    const double v = f_(x.data());
    if (!std::isfinite(v)) {
      if (opt_.skipNonFinite) return kInf;
      throw Error("the function returned a non-finite value at " + detail::formatPoint(x.data(), d_, 10));
    }
    return sign_ * v;
  }

  // Keeps u in the box (or wraps a periodic variable).
  Eigen::VectorXd project(Eigen::VectorXd u) const {
    for (int i = 0; i < d_; ++i) u[i] = opt_.periodic ? u[i] - std::floor(u[i]) : std::clamp(u[i], 0.0, 1.0);
    return u;
  }

  Eigen::VectorXd gradient(const Eigen::VectorXd& u, double gu) {
    Eigen::VectorXd grad(d_);
    const double h = 1e-6;
    for (int i = 0; i < d_; ++i) {
      Eigen::VectorXd a = u, b = u;
      double ha = h, hb = h;
      if (!opt_.periodic) {  // one-sided at the box's faces
        ha = std::min(h, u[i]);
        hb = std::min(h, 1.0 - u[i]);
        if (ha < kMinStep) ha = 0;
        if (hb < kMinStep) hb = 0;
      }
      a[i] -= ha;
      b[i] += hb;
      const double ga = ha > 0 ? g(project(a)) : gu, gb = hb > 0 ? g(project(b)) : gu;
      if (!std::isfinite(ga) || !std::isfinite(gb))
        grad[i] = std::isfinite(gb) ? (gb - gu) / hb : std::isfinite(ga) ? (gu - ga) / ha : 0.0;
      else
        grad[i] = (gb - ga) / (ha + hb);
    }
    return grad;
  }

  // Projected BFGS (3.4.3) from u; returns the local minimiser.
  Eigen::VectorXd bfgs(Eigen::VectorXd u, double& gu) {
    gu = g(u);
    if (!std::isfinite(gu)) return u;
    Eigen::MatrixXd H = Eigen::MatrixXd::Identity(d_, d_);
    Eigen::VectorXd grad = gradient(u, gu);
    for (int iter = 0; iter < 100 && !exhausted(); ++iter) {
      // Variables held at a face by a gradient pointing out of the box are fixed.
      std::vector<bool> fixedVar(d_, false);
      if (!opt_.periodic)
        for (int i = 0; i < d_; ++i)
          fixedVar[i] = (u[i] <= 0.0 && grad[i] > 0) || (u[i] >= 1.0 && grad[i] < 0);
      Eigen::VectorXd gfree = grad;
      for (int i = 0; i < d_; ++i)
        if (fixedVar[i]) gfree[i] = 0;
      if (gfree.norm() < 1e-12) break;
      Eigen::VectorXd p = -H * gfree;
      for (int i = 0; i < d_; ++i)
        if (fixedVar[i]) p[i] = 0;
      if (!p.allFinite() || p.dot(gfree) >= 0) {
        H.setIdentity();
        p = -gfree;
      }
      if (!p.allFinite()) break;
      // Armijo backtracking along the projected path.
      double alpha = std::min(1.0, 0.25 / std::max(p.lpNorm<Eigen::Infinity>(), 1e-300));
      Eigen::VectorXd un = u;
      double gn = gu;
      bool moved = false;
      for (int k = 0; k < 50 && !exhausted(); ++k) {
        un = project(u + alpha * p);
        gn = g(un);
        if (std::isfinite(gn) && gn <= gu + 1e-4 * grad.dot(un - u)) {
          moved = true;
          break;
        }
        alpha *= 0.5;
      }
      if (!moved) break;
      Eigen::VectorXd s = un - u;
      if (opt_.periodic)
        for (int i = 0; i < d_; ++i) s[i] -= std::round(s[i]);
      const Eigen::VectorXd gradn = gradient(un, gn);
      const Eigen::VectorXd y = gradn - grad;
      u = un;
      const double improvement = gu - gn;
      gu = gn;
      grad = gradn;
      if (s.lpNorm<Eigen::Infinity>() < opt_.tolerance) break;
      const double sy = s.dot(y);
      if (sy > 1e-16 && y.allFinite()) {
        const double rho = 1.0 / sy;
        const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(d_, d_);
        H = (I - rho * s * y.transpose()) * H * (I - rho * y * s.transpose()) + rho * s * s.transpose();
        if (!H.allFinite()) H.setIdentity();
      }
      if (improvement <= 1e-15 * (1.0 + std::fabs(gu)) && s.lpNorm<Eigen::Infinity>() < 1e-8) break;
    }
    return u;
  }

  // Derivative-free compass search: settles optima on ridges and corners where
  // finite-difference gradients mislead.
  Eigen::VectorXd polish(Eigen::VectorXd u, double& gu) {
    std::vector<Eigen::VectorXd> dirs;
    for (int i = 0; i < d_; ++i) {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(d_);
      e[i] = 1;
      dirs.push_back(e);
      dirs.push_back(-e);
    }
    if (d_ == 2)
      for (double sx : {-1.0, 1.0})
        for (double sy : {-1.0, 1.0}) dirs.push_back(Eigen::Vector2d(sx, sy) / std::sqrt(2.0));
    double step = 1e-4;
    for (int iter = 0; iter < 400 && step > opt_.tolerance && !exhausted(); ++iter) {
      bool better = false;
      for (const Eigen::VectorXd& e : dirs) {
        const Eigen::VectorXd v = project(u + step * e);
        const double gv = g(v);
        if (gv < gu) {
          u = v;
          gu = gv;
          better = true;
          break;
        }
      }
      if (!better) step *= 0.5;
    }
    return u;
  }

 private:
  const Objective& f_;
  int d_;
  double sign_;
  OptimizeOptions opt_;
  std::vector<double> lo_, span_;
  int evaluations_ = 0;
};

}  // namespace

std::vector<int> subtractiveClustering(const std::vector<std::vector<double>>& points, double ra, double rb,
                                       double acceptRatio, double rejectRatio) {
  const int n = static_cast<int>(points.size());
  std::vector<int> centres;
  if (n == 0) return centres;
  const double alpha = 4.0 / (ra * ra), beta = 4.0 / (rb * rb);  // eqs. 3.11b, 3.14b
  auto d2 = [&](int i, int j) {
    double s = 0;
    for (size_t k = 0; k < points[i].size(); ++k) s += (points[i][k] - points[j][k]) * (points[i][k] - points[j][k]);
    return s;
  };
  // Eq. 3.11a; terms beyond 3 r_a (below e^-36) are left out, via a bucket grid.
  const double cutoff = 3.0 * std::max(ra, rb);
  const int dims = static_cast<int>(points[0].size());
  const int cells = std::max(1, std::min(512, static_cast<int>(1.0 / cutoff)));
  auto cellOf = [&](const std::vector<double>& p, int k) {
    return std::clamp(static_cast<int>(p[k] * cells), 0, cells - 1);
  };
  std::vector<std::vector<int>> bucket(dims == 1 ? cells : cells * cells);
  for (int i = 0; i < n; ++i) bucket[dims == 1 ? cellOf(points[i], 0) : cellOf(points[i], 0) * cells + cellOf(points[i], 1)].push_back(i);
  auto near = [&](int i, const std::function<void(int)>& visit) {
    const int cx = cellOf(points[i], 0), cy = dims == 1 ? 0 : cellOf(points[i], 1);
    for (int x = std::max(0, cx - 1); x <= std::min(cells - 1, cx + 1); ++x)
      for (int y = dims == 1 ? 0 : std::max(0, cy - 1); y <= (dims == 1 ? 0 : std::min(cells - 1, cy + 1)); ++y)
        for (int j : bucket[dims == 1 ? x : x * cells + y]) visit(j);
  };
  std::vector<double> pot(n, 0.0);
  for (int i = 0; i < n; ++i) near(i, [&](int j) { pot[i] += std::exp(-alpha * d2(i, j)); });

  double first = -1;
  for (int guard = 0; guard < n; ++guard) {
    const int k = static_cast<int>(std::max_element(pot.begin(), pot.end()) - pot.begin());
    const double pk = pot[k];
    if (first < 0) first = pk;  // eq. 3.13
    if (pk <= 0) break;
    bool accept;
    if (pk > acceptRatio * first) {
      accept = true;
    } else if (pk < rejectRatio * first) {
      break;
    } else {
      // Eq. 3.17: between the thresholds, accept only if far enough from the centres.
      double dmin = kInf;
      for (int c : centres) dmin = std::min(dmin, std::sqrt(d2(k, c)));
      accept = dmin / ra + pk / first >= 1.0;
    }
    if (!accept) {
      pot[k] = 0;
      continue;
    }
    centres.push_back(k);
    near(k, [&](int j) { pot[j] -= pk * std::exp(-beta * d2(k, j)); });  // eq. 3.16
    pot[k] = 0;
  }
  return centres;
}

namespace {

void checkOptions(const std::vector<std::pair<double, double>>& bounds, const OptimizeOptions& opt) {
  if (bounds.empty() || bounds.size() > 2) throw Error("optimize: give bounds for one or two variables");
  for (size_t i = 0; i < bounds.size(); ++i) {
    const auto [a, b] = bounds[i];
    const std::string name = "optimize: bounds[" + std::to_string(i) + "]";
    if (!std::isfinite(a) || !std::isfinite(b)) throw Error(name + " is not finite");
    if (a == b) throw Error(name + " is an empty interval (a == b)");
    if (a > b) throw Error(name + " is reversed (a > b)");
  }
  if (opt.periodic && bounds.size() != 1) throw Error("optimize: only a function of one variable can be periodic");
  if (!(opt.clusterRadius > 0) || !(opt.squashFactor > 0)) throw Error("optimize: cluster radii must be > 0");
  if (opt.maxEvaluations <= 0) throw Error("optimize: maxEvaluations must be > 0");
}

// 1. Patching (3.4.1): g on a regular grid of n (x n) points of the unit box.
// In one periodic variable the last sample would repeat the first.
class Samples {
 public:
  Samples(Problem& pb, const OptimizeOptions& opt)
      : d_(pb.dims()), n_(opt.samples > 2 ? opt.samples : (d_ == 1 ? 201 : 41)), periodic_(opt.periodic),
        step_(opt.periodic ? 1.0 / n_ : 1.0 / (n_ - 1)), g_(d_ == 1 ? n_ : n_ * n_) {
    for (int i = 0; i < size(); ++i) g_[i] = pb.g(u(i));
  }
  int size() const { return static_cast<int>(g_.size()); }
  int dims() const { return d_; }
  double step() const { return step_; }
  double g(int i) const { return g_[i]; }
  int ix(int i) const { return d_ == 1 ? i : i % n_; }
  int iy(int i) const { return d_ == 1 ? 0 : i / n_; }
  Eigen::VectorXd u(int i) const {
    Eigen::VectorXd v(d_);
    v[0] = ix(i) * step_;
    if (d_ == 2) v[1] = iy(i) * step_;
    return v;
  }
  // g at grid indices; +inf outside the box (wrapped in x when periodic).
  double at(int x, int y) const {
    if (periodic_) x = (x % n_ + n_) % n_;
    if (x < 0 || x >= n_ || y < 0 || y >= (d_ == 1 ? 1 : n_)) return kInf;
    return g_[d_ == 1 ? x : y * n_ + x];
  }

 private:
  int d_, n_;
  bool periodic_;
  double step_;
  std::vector<double> g_;
};

// 2. Curvature classification (3.2): the convex group of the function to minimise.
std::vector<int> valleyGroup(const Samples& s) {
  double gmin = kInf, gmax = -kInf;
  for (int i = 0; i < s.size(); ++i)
    if (std::isfinite(s.g(i))) {
      gmin = std::min(gmin, s.g(i));
      gmax = std::max(gmax, s.g(i));
    }
  const double h = s.step();
  const double tiny = 1e-9 * (gmax - gmin + 1e-300) / (h * h);
  std::vector<int> group;
  for (int i = 0; i < s.size(); ++i) {
    const int ix = s.ix(i), iy = s.iy(i);
    const double c = s.at(ix, iy);
    if (!std::isfinite(c)) continue;
    if (s.dims() == 1) {
      const double l = s.at(ix - 1, 0), r = s.at(ix + 1, 0);
      if (!std::isfinite(l) || !std::isfinite(r)) continue;
      const double g1 = (r - l) / (2 * h), g2 = (r - 2 * c + l) / (h * h);
      const double k = g2 / std::pow(1 + g1 * g1, 1.5);  // eq. 3.3
      if (k > tiny) group.push_back(i);
      continue;
    }
    const double l = s.at(ix - 1, iy), r = s.at(ix + 1, iy), b = s.at(ix, iy - 1), t = s.at(ix, iy + 1);
    const double bl = s.at(ix - 1, iy - 1), br = s.at(ix + 1, iy - 1), tl = s.at(ix - 1, iy + 1),
                 tr = s.at(ix + 1, iy + 1);
    if (!std::isfinite(l + r + b + t + bl + br + tl + tr)) continue;
    const double gx = (r - l) / (2 * h), gy = (t - b) / (2 * h);
    const double gxx = (r - 2 * c + l) / (h * h), gyy = (t - 2 * c + b) / (h * h);
    const double gxy = (tr - tl - br + bl) / (4 * h * h);
    // Fundamental forms of the graph z = g(x, y) (eqs. 3.8-3.10), upward normal.
    const double E = 1 + gx * gx, F = gx * gy, G = 1 + gy * gy, w = std::sqrt(1 + gx * gx + gy * gy);
    const double L = gxx / w, M = gxy / w, N = gyy / w;
    const double K = (L * N - M * M) / (E * G - F * F);                     // eq. 3.6
    const double H = (E * N - 2 * F * M + G * L) / (2 * (E * G - F * F));  // eq. 3.7
    // Table 3.2: elliptic or parabolic and bending up = a valley of g.
    if (H > tiny && K > -tiny * tiny) group.push_back(i);
  }
  return group;
}

// 3. Subtractive clustering of the group (3.3.1): the start points; beyond the
// thesis also the grid's own local minima and its best point, so that optima
// in narrow or flat regions and on the box's faces are reached too.
std::vector<int> startPoints(const Samples& s, const std::vector<int>& group, const OptimizeOptions& opt) {
  std::vector<int> starts;
  std::vector<std::vector<double>> pts;
  for (int i : group) {
    const Eigen::VectorXd u = s.u(i);
    pts.emplace_back(u.data(), u.data() + s.dims());
  }
  for (int c : subtractiveClustering(pts, opt.clusterRadius, opt.squashFactor * opt.clusterRadius, opt.acceptRatio,
                                     opt.rejectRatio))
    starts.push_back(group[c]);
  int best = -1;
  const int reachY = s.dims() == 1 ? 0 : 1;
  for (int i = 0; i < s.size(); ++i) {
    if (!std::isfinite(s.g(i))) continue;
    if (best < 0 || s.g(i) < s.g(best)) best = i;
    bool lowest = true, lower = false;
    for (int dy = -reachY; dy <= reachY; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (!dx && !dy) continue;
        const double v = s.at(s.ix(i) + dx, s.iy(i) + dy);
        if (v < s.g(i)) lowest = false;
        if (v > s.g(i)) lower = true;
      }
    if (lowest && lower) starts.push_back(i);
  }
  if (best < 0) throw Error("optimize: the function has no finite value on the box");
  starts.push_back(best);
  std::sort(starts.begin(), starts.end());
  starts.erase(std::unique(starts.begin(), starts.end()), starts.end());
  return starts;
}

// A start and g there (NaN: not evaluated yet).
using Start = std::pair<Eigen::VectorXd, double>;

// 4. Quasi-Newton from every start (3.4.3), then a derivative-free polish; the
// distinct local minima of g found, lowest first. Past the budget, the
// sampled starts stand for themselves.

std::vector<std::pair<Eigen::VectorXd, double>> descend(Problem& pb, const std::vector<Start>& from,
                                                        bool periodic) {
  std::vector<std::pair<Eigen::VectorXd, double>> found;
  for (const auto& [start, known] : from) {
    double gu = known;
    Eigen::VectorXd u = start;
    if (pb.exhausted()) {  // out of budget: the start itself, as sampled
      if (std::isnan(gu)) continue;
    } else {
      u = pb.bfgs(start, gu);
      u = pb.polish(u, gu);
    }
    if (!std::isfinite(gu)) continue;
    bool dup = false;
    for (auto& [v, gvv] : found) {
      Eigen::VectorXd diff = v - u;
      if (periodic) diff[0] -= std::round(diff[0]);
      if (diff.lpNorm<Eigen::Infinity>() < 1e-6) {
        dup = true;
        if (gu < gvv) {
          v = u;
          gvv = gu;
        }
      }
    }
    if (!dup) found.emplace_back(u, gu);
  }
  std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  return found;
}

}  // namespace

OptimizeResult optimize(const Objective& f, const std::vector<std::pair<double, double>>& bounds, Goal goal,
                        const OptimizeOptions& opt) {
  checkOptions(bounds, opt);
  Problem pb(f, bounds, goal, opt);
  const Samples samples(pb, opt);
  std::vector<Start> from;
  for (int s : startPoints(samples, valleyGroup(samples), opt)) from.emplace_back(samples.u(s), samples.g(s));
  for (const std::vector<double>& x : opt.starts) {
    if (static_cast<int>(x.size()) != pb.dims()) throw Error("optimize: a start point has the wrong dimension");
    Eigen::VectorXd u(pb.dims());
    for (int i = 0; i < pb.dims(); ++i) u[i] = (x[i] - bounds[i].first) / (bounds[i].second - bounds[i].first);
    from.emplace_back(pb.project(u), kNaN);
  }
  OptimizeResult out;
  for (const auto& [u, gu] : descend(pb, from, opt.periodic)) out.locals.push_back({pb.toX(u), pb.sign() * gu});
  // Every start is a finite sample, but the descent may leave the finite part.
  if (out.locals.empty()) throw Error("optimize: no finite local optimum found from any start");
  out.x = out.locals.front().x;
  out.value = out.locals.front().value;
  out.evaluations = pb.evaluations();
  out.converged = !pb.exhausted();
  return out;
}

}  // namespace plunge
