#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "plunge/error.hpp"
#include "plunge/sequencing.hpp"

using namespace plunge;

TEST(Sequencing, PermutationAndStart) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0, 100);
  std::vector<Vec2> pts(200);
  for (Vec2& p : pts) p = {u(rng), u(rng)};
  std::vector<int> order = tour(pts, false, Vec2{0, 0});
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> ids(pts.size());
  std::iota(ids.begin(), ids.end(), 0);
  EXPECT_EQ(sorted, ids);
  int nearest = 0;
  for (size_t i = 0; i < pts.size(); ++i)
    if (norm(pts[i]) < norm(pts[nearest])) nearest = static_cast<int>(i);
  EXPECT_EQ(order.front(), nearest);
  EXPECT_EQ(tour(pts, false, Vec2{0, 0}), order);  // deterministic
}

TEST(Sequencing, DegenerateInput) {
  EXPECT_TRUE(tour({}).empty());
  EXPECT_EQ(tour({{1, 1}}), std::vector<int>{0});
  EXPECT_EQ(tour({{1, 1}, {1, 1}}).size(), 2u);
  EXPECT_THROW(tour({{0, 0}, {NAN, 1}}), Error);
  EXPECT_THROW(tour({{0, 0}}, true, Vec2{INFINITY, 0}), Error);
}
