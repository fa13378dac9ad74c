#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "plunge/error.hpp"
#include "plunge/geometry.hpp"
#include "plunge/optimizer.hpp"

using namespace plunge;
using ::testing::HasSubstr;

namespace {
bool hasLocal(const OptimizeResult& r, std::vector<double> x, double tol = 1e-5) {
  for (const LocalOptimum& o : r.locals) {
    double d = 0;
    for (size_t i = 0; i < x.size(); ++i) d = std::max(d, std::fabs(o.x[i] - x[i]));
    if (d < tol) return true;
  }
  return false;
}
}  // namespace

TEST(Optimizer, HimmelblauHasFourMinima) {
  const auto f = [](double x, double y) { return std::pow(x * x + y - 11, 2) + std::pow(x + y * y - 7, 2); };
  const OptimizeResult r = optimize2(f, {-5, 5}, {-5, 5}, Goal::Minimize);
  EXPECT_NEAR(r.value, 0, 1e-12);
  EXPECT_TRUE(hasLocal(r, {3, 2}));
  EXPECT_TRUE(hasLocal(r, {-2.805118, 3.131312}));
  EXPECT_TRUE(hasLocal(r, {-3.779310, -3.283186}));
  EXPECT_TRUE(hasLocal(r, {3.584428, -1.848126}));
  for (size_t i = 1; i < r.locals.size(); ++i) EXPECT_LE(r.locals[i - 1].value, r.locals[i].value);
  // Its local maximum (-0.270845, -0.923039), value 181.617.
  const OptimizeResult m = optimize2(f, {-2, 2}, {-2, 2}, Goal::Maximize);
  EXPECT_TRUE(hasLocal(m, {-0.270845, -0.923039}));
}

TEST(Optimizer, RosenbrockOnABox) {
  const auto f = [](double x, double y) { return std::pow(1 - x, 2) + 100 * std::pow(y - x * x, 2); };
  const OptimizeResult r = optimize2(f, {-2, 2}, {-1, 3}, Goal::Minimize);
  EXPECT_NEAR(r.x[0], 1, 1e-5);
  EXPECT_NEAR(r.x[1], 1, 1e-5);
  EXPECT_NEAR(r.value, 0, 1e-10);
  // With the minimum cut off by the box, the constrained optimum sits on its face
  // y = 0.5; compare with a dense search along that face.
  const OptimizeResult c = optimize2(f, {-2, 2}, {-1, 0.5}, Goal::Minimize);
  EXPECT_NEAR(c.x[1], 0.5, 1e-9);
  double bestX = 0, best = INFINITY;
  for (double x = -2; x <= 2; x += 1e-5)
    if (f(x, 0.5) < best) {
      best = f(x, 0.5);
      bestX = x;
    }
  EXPECT_NEAR(c.x[0], bestX, 2e-5);
  EXPECT_LE(c.value, best + 1e-12);
}

TEST(Optimizer, RastriginOneAndTwoVariables) {
  const auto r1 = optimize1([](double x) { return 10 + x * x - 10 * std::cos(2 * kPi * x); }, -5.12, 5.12,
                            Goal::Minimize);
  EXPECT_NEAR(r1.x[0], 0, 1e-6);
  EXPECT_NEAR(r1.value, 0, 1e-10);
  EXPECT_GE(r1.locals.size(), 10u);  // many local minima, all found
  const auto r2 = optimize2(
      [](double x, double y) { return 20 + x * x + y * y - 10 * (std::cos(2 * kPi * x) + std::cos(2 * kPi * y)); },
      {-5.12, 5.12}, {-5.12, 5.12}, Goal::Minimize);
  EXPECT_NEAR(r2.x[0], 0, 1e-6);
  EXPECT_NEAR(r2.x[1], 0, 1e-6);
  EXPECT_NEAR(r2.value, 0, 1e-10);
}

TEST(Optimizer, OptimumOnTheBoxEdgeAndCorner) {
  const auto r = optimize1([](double x) { return x * x * x - 2 * x; }, -2, 3, Goal::Maximize);  // f(3) = 21
  EXPECT_NEAR(r.x[0], 3, 1e-9);
  EXPECT_NEAR(r.value, 21, 1e-7);
  EXPECT_TRUE(hasLocal(r, {-std::sqrt(2.0 / 3.0)}, 1e-5));  // the interior local maximum too
  const auto c = optimize2([](double x, double y) { return x + 2 * y; }, {0, 1}, {0, 1}, Goal::Maximize);
  EXPECT_NEAR(c.x[0], 1, 1e-9);
  EXPECT_NEAR(c.x[1], 1, 1e-9);
}

TEST(Optimizer, PlateauAndSingleOptimum) {
  const auto flat = optimize2([](double, double) { return 4.0; }, {0, 1}, {0, 1}, Goal::Maximize);
  EXPECT_DOUBLE_EQ(flat.value, 4.0);
  const auto bowl = optimize2([](double x, double y) { return (x - 0.3) * (x - 0.3) + 2 * (y + 0.2) * (y + 0.2); },
                              {-1, 1}, {-1, 1}, Goal::Minimize);
  EXPECT_NEAR(bowl.x[0], 0.3, 1e-7);
  EXPECT_NEAR(bowl.x[1], -0.2, 1e-7);
  EXPECT_EQ(bowl.locals.size(), 1u);
}

TEST(Optimizer, ThesisCase483) {
  // Eq. 4.83: cos(3x + 3.15) + sin(y + 3.15) on [-2, 2]^2 has two maxima of value 2.
  const auto r = optimize2([](double x, double y) { return std::cos(3 * x + 3.15) + std::sin(y + 3.15); }, {-2, 2},
                           {-2, 2}, Goal::Maximize);
  EXPECT_NEAR(r.value, 2, 1e-12);
  // cos(3x + 3.15) = 1 at x = (2 pi k - 3.15) / 3, sin(y + 3.15) = 1 at y = pi / 2 - 3.15.
  EXPECT_TRUE(hasLocal(r, {-3.15 / 3, kPi / 2 - 3.15}));
  EXPECT_TRUE(hasLocal(r, {(2 * kPi - 3.15) / 3, kPi / 2 - 3.15}));
  int twos = 0;
  for (const auto& o : r.locals) twos += std::fabs(o.value - 2) < 1e-9;
  EXPECT_EQ(twos, 2);
}

TEST(Optimizer, PeriodicVariable) {
  const auto r = optimize1([](double t) { return std::cos(t - 6.2); }, 0, 2 * kPi, Goal::Maximize,
                           [] { OptimizeOptions o; o.periodic = true; return o; }());
  EXPECT_NEAR(r.x[0], 6.2, 1e-7);
  EXPECT_NEAR(r.value, 1, 1e-12);
}

TEST(Optimizer, BadInput) {
  const Objective f = [](const double* x) { return x[0]; };
  EXPECT_THROW(optimize(f, {}, Goal::Minimize), Error);
  EXPECT_THROW(optimize(f, {{1, 1}}, Goal::Minimize), Error);                 // empty box
  EXPECT_THROW(optimize(f, {{2, 1}}, Goal::Minimize), Error);                 // reversed
  EXPECT_THROW(optimize(f, {{0, INFINITY}}, Goal::Minimize), Error);
  EXPECT_THROW(optimize(f, {{0, 1}, {0, 1}, {0, 1}}, Goal::Minimize), Error);  // three variables
  try {
    optimize([](const double* x) { return x[0] > 0.5 ? NAN : x[0]; }, {{0, 1}}, Goal::Minimize);
    FAIL();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("non-finite"));
  }
  // A callable that throws: its exception comes through untouched.
  EXPECT_THROW(optimize([](const double*) -> double { throw std::runtime_error("boom"); }, {{0, 1}}, Goal::Minimize),
               std::runtime_error);
}

TEST(Optimizer, SubtractiveClusteringFindsSeparateBlobs) {
  std::vector<std::vector<double>> pts;
  for (int i = 0; i < 30; ++i) pts.push_back({0.2 + 0.01 * (i % 5), 0.2 + 0.01 * (i / 5)});
  for (int i = 0; i < 30; ++i) pts.push_back({0.8 + 0.01 * (i % 5), 0.7 + 0.01 * (i / 5)});
  const auto c = subtractiveClustering(pts, 0.15, 0.1875);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NE(c[0] < 30, c[1] < 30);  // one centre per blob
}

// Every iteration is bounded and never leaves the finite numbers: f is never
// called at a non-finite point (OpenCASCADE's face classifier does not return
// from one), the budget stops the search, and poll is called along the way.
TEST(Optimizer, BoundedAndFinite) {
  // A narrow finite domain against the box's faces, steep inside: finite
  // differences at the faces once made BFGS step to NaN.
  long calls = 0, polls = 0;
  bool nonFinite = false;
  auto f = [&](const double* x) {
    ++calls;
    if (!std::isfinite(x[0]) || !std::isfinite(x[1])) nonFinite = true;
    if (x[1] > 1.4 - 0.3 * x[0]) return std::nan("");
    return 1e9 * std::sin(40 * x[0]) * x[1] * x[1] + x[0];
  };
  OptimizeOptions o;
  o.skipNonFinite = true;
  o.poll = [&] { ++polls; };
  const OptimizeResult all = optimize(f, {{3.25, 4.71}, {0.0, 1.43}}, Goal::Maximize, o);
  EXPECT_FALSE(nonFinite);
  EXPECT_EQ(all.evaluations, calls);
  EXPECT_GE(polls, calls / 64);
  o.maxEvaluations = 3000;
  calls = 0;
  const OptimizeResult cut = optimize(f, {{3.25, 4.71}, {0.0, 1.43}}, Goal::Maximize, o);
  EXPECT_FALSE(cut.converged);
  EXPECT_LE(calls, 3000 + 8);  // the last step's few evaluations
  EXPECT_FALSE(cut.locals.empty());
  EXPECT_TRUE(all.converged || all.evaluations >= OptimizeOptions{}.maxEvaluations);
  // A poll that throws (a cancel) stops the search.
  o.poll = [] { throw std::runtime_error("cancel"); };
  EXPECT_THROW(optimize(f, {{3.25, 4.71}, {0.0, 1.43}}, Goal::Maximize, o), std::runtime_error);
  o.poll = nullptr;
  o.maxEvaluations = 0;
  EXPECT_THROW(optimize(f, {{3.25, 4.71}, {0.0, 1.43}}, Goal::Maximize, o), Error);
}
