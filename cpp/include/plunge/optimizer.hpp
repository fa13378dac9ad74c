// Global optimization of a function of one or two variables on a box
// (thesis chapter 3):
//   1. patching: the box becomes a grid of points (3.4.1);
//   2. curvature classification of every grid point: one variable, eq. 3.3;
//      two variables, Gaussian and mean curvature from the fundamental forms,
//      eqs. 3.6-3.10 and table 3.2; the convex group for a minimum, the concave
//      group for a maximum;
//   3. subtractive clustering of that group (eqs. 3.11-3.17, acceptance
//      thresholds 0.5 and 0.15) gives the start points (3.4.2);
//   4. quasi-Newton (BFGS, Eigen) from every start (3.4.3); the best local
//      optimum is the global one.
// What the thesis skips: optima on the box boundary (projected BFGS finds the
// constrained optimum), flat plateaus and functions without curvature of the
// wanted sign (the best grid point and the grid's own local optima are started
// from as well), non-finite values (an error naming the point), ridges (a
// derivative-free compass search polishes every local optimum).
#pragma once
#include <functional>
#include <utility>
#include <vector>

namespace plunge {

enum class Goal { Minimize, Maximize };

struct OptimizeOptions {
  int samples = 0;             // grid points per variable (0: 201 for one, 41 for two variables)
  double clusterRadius = 0.15;  // r_a of eq. 3.11b, as a fraction of the box
  double squashFactor = 1.25;   // r_b = squashFactor * r_a (eq. 3.14b)
  double acceptRatio = 0.5;     // eq. 3.17: accept a centre above this share of the first potential
  double rejectRatio = 0.15;    // ... stop below this share
  bool periodic = false;        // one variable only: the function wraps around (an angle)
  // Non-finite values are outside the domain (never optimal) instead of an error.
  bool skipNonFinite = false;
  double tolerance = 1e-10;     // on x, relative to the box
  // More start points for the local optimizer (in the function's coordinates),
  // e.g. where a coarse grid may miss a narrow optimum that is known elsewhere.
  std::vector<std::vector<double>> starts;
  // Every iteration is bounded: the whole search stops after this many
  // evaluations of f (grid included) and says so (OptimizeResult::converged).
  int maxEvaluations = 200000;
  // Called every few dozen evaluations: a long search reports progress and can
  // be cancelled (Progress::tick throws), whatever f costs.
  std::function<void()> poll;
};

struct LocalOptimum {
  std::vector<double> x;
  double value = 0.0;
};

struct OptimizeResult {
  std::vector<double> x;  // the global optimum
  double value = 0.0;
  std::vector<LocalOptimum> locals;  // every local optimum found, best first
  int evaluations = 0;
  // False when the evaluation budget ran out before every start had descended:
  // the optimum may be missed, and a caller that needs a bound falls back.
  bool converged = true;
};

using Objective = std::function<double(const double* x)>;

// bounds: one (a, b) per variable, one or two variables, a < b, all finite.
// Throws plunge::Error for a bad box or a non-finite value; exceptions thrown by
// f or by options.poll pass through unchanged. f is never called at a
// non-finite point (OpenCASCADE's classifiers do not return from one).
OptimizeResult optimize(const Objective& f, const std::vector<std::pair<double, double>>& bounds, Goal goal,
                        const OptimizeOptions& options = {});

// The same for any callable taking the coordinates as doubles.
template <class F>
OptimizeResult optimize1(F&& f, double a, double b, Goal goal, const OptimizeOptions& options = {}) {
  return optimize([&](const double* x) { return f(x[0]); }, {{a, b}}, goal, options);
}
template <class F>
OptimizeResult optimize2(F&& f, std::pair<double, double> bx, std::pair<double, double> by, Goal goal,
                         const OptimizeOptions& options = {}) {
  return optimize([&](const double* x) { return f(x[0], x[1]); }, {bx, by}, goal, options);
}

// Subtractive clustering (eqs. 3.11-3.17) of points in the unit box: the
// indices of the accepted cluster centres, in order of acceptance.
std::vector<int> subtractiveClustering(const std::vector<std::vector<double>>& points, double ra, double rb,
                                       double acceptRatio = 0.5, double rejectRatio = 0.15);

}  // namespace plunge
