#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "plunge/error.hpp"
#include "plunge/sequencing.hpp"

using namespace plunge;

namespace {

bool isPermutation(std::vector<int> order, size_t n) {
  std::sort(order.begin(), order.end());
  std::vector<int> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  return order == ids;
}

// Independent brute force: the shortest tour or path over all orders.
double bruteForce(const std::vector<Vec2>& pts, bool closed, int first) {
  std::vector<int> perm(pts.size());
  std::iota(perm.begin(), perm.end(), 0);
  double best = INFINITY;
  do {
    if (first >= 0 && perm[0] != first) continue;
    double len = 0;
    for (size_t i = 1; i < perm.size(); ++i) len += dist(pts[perm[i - 1]], pts[perm[i]]);
    if (closed) len += dist(pts[perm.back()], pts[perm.front()]);
    best = std::min(best, len);
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

std::vector<Vec2> randomPoints(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(0, 100);
  std::vector<Vec2> pts(n);
  for (Vec2& p : pts) p = {u(rng), u(rng)};
  return pts;
}

}  // namespace

class SmallOptimum : public ::testing::TestWithParam<TourMethod> {};

TEST_P(SmallOptimum, MatchesBruteForceUpToNinePoints) {
  std::mt19937 rng(42);
  TourOptions opt;
  opt.method = GetParam();
  for (int n = 3; n <= 9; ++n)
    for (int trial = 0; trial < 4; ++trial) {
      const auto pts = randomPoints(rng, n);
      const auto closed = tour(pts, true, std::nullopt, opt);
      ASSERT_TRUE(isPermutation(closed, n));
      EXPECT_NEAR(tourLength(pts, closed, true), bruteForce(pts, true, -1), 1e-9) << "closed, n=" << n;
      const auto open = tour(pts, false, std::nullopt, opt);
      EXPECT_NEAR(tourLength(pts, open, false), bruteForce(pts, false, -1), 1e-9) << "open, n=" << n;
      // From a place: the shortest path with the place as its first point.
      const Vec2 start{0, 0};
      const auto fromStart = tour(pts, false, start, opt);
      ASSERT_TRUE(isPermutation(fromStart, n));
      std::vector<Vec2> withStart(pts);
      withStart.push_back(start);
      EXPECT_NEAR(dist(start, pts[fromStart.front()]) + tourLength(pts, fromStart, false),
                  bruteForce(withStart, false, n), 1e-9)
          << "start, n=" << n;
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, SmallOptimum, ::testing::Values(TourMethod::LocalSearch, TourMethod::Annealing));

TEST(Sequencing, LargeInstancesArePermutationsAndDeterministic) {
  std::mt19937 rng(1);
  const auto pts = randomPoints(rng, 600);
  for (TourMethod m : {TourMethod::LocalSearch, TourMethod::Annealing}) {
    TourOptions opt;
    opt.method = m;
    opt.seed = 7;
    const auto a = tour(pts, false, Vec2{0, 0}, opt);
    EXPECT_TRUE(isPermutation(a, pts.size()));
    EXPECT_EQ(tour(pts, false, Vec2{0, 0}, opt), a);
  }
}

TEST(Sequencing, NearTheRandomUniformOptimum) {
  // A uniform random instance: the optimum is about 0.7124 sqrt(n A); local search
  // with kicks lands within a few per cent, the bare nearest-neighbour order ~25 % above.
  std::mt19937 rng(3);
  const auto pts = randomPoints(rng, 2000);
  const double len = tourLength(pts, tour(pts, true), true);
  EXPECT_LT(len, 1.08 * 0.7124 * std::sqrt(2000.0 * 100 * 100));
}

// An open path from a start, over a lattice of equal edges beside one far point:
// the path's dummy constant is then ~1e7 mm, and swapping two equal edges gained
// one rounding unit (2e-10 mm) both ways, so the local search never ended.
TEST(Sequencing, RoundingIsNoGain) {
  std::vector<Vec2> pts;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) pts.push_back({0.3 * i + 0.15 * (j % 2), 0.3 * j * std::sqrt(3.0) / 2});
  pts.push_back({1e5, 1e5});
  for (TourMethod m : {TourMethod::LocalSearch, TourMethod::Annealing}) {
    TourOptions opt;
    opt.method = m;
    const auto order = tour(pts, false, Vec2{0, 0}, opt);
    ASSERT_TRUE(isPermutation(order, pts.size()));
    EXPECT_EQ(order.front(), 0);
    EXPECT_EQ(order.back(), 100);  // the far point last
    // The lattice in about one edge per point: 99 edges of 0.3 mm (a few longer).
    EXPECT_LT(tourLength(pts, order, false) - dist(pts[order[99]], pts[100]), 1.1 * 99 * 0.3);
  }
}

// Annealing beyond kAnnealFull points makes fewer moves per stage (its moves
// cost O(n)) and then a local search: as short as the default method's path.
TEST(Sequencing, LargeAnnealingStaysShort) {
  std::mt19937 rng(5);
  const auto pts = randomPoints(rng, 6000);
  TourOptions opt;
  opt.method = TourMethod::Annealing;
  const auto annealed = tour(pts, false, Vec2{0, 0}, opt);
  ASSERT_TRUE(isPermutation(annealed, pts.size()));
  const double local = tourLength(pts, tour(pts, false, Vec2{0, 0}), false);
  EXPECT_LT(tourLength(pts, annealed, false), 1.05 * local);
}

TEST(Sequencing, CollinearPointsGoInOrder) {
  std::vector<Vec2> pts;
  for (int i : {5, 2, 9, 0, 7, 3, 8, 1, 6, 4, 11, 10}) pts.push_back({static_cast<double>(i), 0});
  const auto open = tour(pts, false, Vec2{-1, 0});
  EXPECT_NEAR(tourLength(pts, open, false), 11, 1e-12);
  EXPECT_DOUBLE_EQ(pts[open.front()].x, 0);
  EXPECT_NEAR(tourLength(pts, tour(pts, true), true), 22, 1e-12);
}

TEST(Sequencing, DegenerateInput) {
  EXPECT_TRUE(tour({}).empty());
  EXPECT_TRUE(tour({}, false, Vec2{1, 1}).empty());
  EXPECT_EQ(tour({{1, 1}}), std::vector<int>{0});
  EXPECT_EQ(tour({{1, 1}}, false, Vec2{5, 5}), std::vector<int>{0});
  EXPECT_EQ(tour({{0, 0}, {3, 4}}, false, Vec2{3, 3}), (std::vector<int>{1, 0}));
  // Duplicates: all at one spot, and many copies of a few spots.
  std::vector<Vec2> same(40, Vec2{2, 2});
  const auto s = tour(same);
  EXPECT_TRUE(isPermutation(s, same.size()));
  EXPECT_DOUBLE_EQ(tourLength(same, s, true), 0);
  std::vector<Vec2> dup;
  for (int k = 0; k < 30; ++k) dup.push_back({static_cast<double>(k % 3) * 10, 0});
  EXPECT_NEAR(tourLength(dup, tour(dup, false), false), 20, 1e-12);
  EXPECT_THROW(tour({{0, 0}, {NAN, 1}}), Error);
  EXPECT_THROW(tour({{0, 0}, {1, INFINITY}}), Error);
  EXPECT_THROW(tour({{0, 0}}, true, Vec2{INFINITY, 0}), Error);
}

// Or-opt within an order: every dependent pair keeps its order, the first
// point stays first, and the path never gets longer; it does get shorter
// where points are free to move.
TEST(Sequencing, ShortenKeepingOrderKeepsEveryDependentPair) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 100);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec2> p(60);
    for (Vec2& q : p) q = {u(rng), u(rng)};
    const double reach = 5 + trial;  // from almost free to tightly bound
    auto dependent = [&](int a, int b) { return dist(p[a], p[b]) < reach; };
    std::vector<int> given(p.size());
    std::iota(given.begin(), given.end(), 0);
    const std::vector<int> order = shortenKeepingOrder(p, dependent);
    std::vector<int> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    ASSERT_EQ(sorted, given);
    EXPECT_EQ(order.front(), 0);
    std::vector<int> at(p.size());
    for (size_t k = 0; k < order.size(); ++k) at[order[k]] = static_cast<int>(k);
    for (int a = 0; a < 60; ++a)
      for (int b = a + 1; b < 60; ++b)
        if (dependent(a, b)) {
          EXPECT_LT(at[a], at[b]) << trial << " " << a << " " << b;
        }
    EXPECT_LE(tourLength(p, order, false), tourLength(p, given, false) + 1e-9);
    if (trial == 0) {
      EXPECT_LT(tourLength(p, order, false), 0.5 * tourLength(p, given, false));
    }
  }
  // A chain (each point depends on the next) cannot move at all.
  std::vector<Vec2> chain;
  for (int k = 0; k < 10; ++k) chain.push_back({(k % 2) * 50.0, 1.0 * k});
  const std::vector<int> fixed = shortenKeepingOrder(chain, [](int a, int b) { return std::abs(a - b) == 1; });
  for (int k = 0; k < 10; ++k) EXPECT_EQ(fixed[k], k);
}
