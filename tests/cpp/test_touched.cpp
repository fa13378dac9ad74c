// Touched, the plunges made so far as disks: checked against a raster of the
// test's own (the lowest bottom of the disks over each point, top_z where none).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "touched.hpp"

namespace plunge {
namespace {

struct Disk {
  Vec2 c;
  double r, bottom;
};

// The highest stock, sampled every 0.05 mm, under a disk of radius r swept from a to b.
double sampledHighest(const std::vector<Disk>& disks, double top, Vec2 a, Vec2 b, double r) {
  double highest = -1e9;
  const double len = dist(a, b);
  const int steps = std::max(1, static_cast<int>(std::ceil(len / 0.05)));
  for (int s = 0; s <= steps; ++s) {
    const Vec2 p = a + (b - a) * (static_cast<double>(s) / steps);
    for (double y = -r; y <= r; y += 0.05)
      for (double x = -r; x <= r; x += 0.05) {
        if (std::hypot(x, y) > r - 0.02) continue;
        const Vec2 q = p + Vec2{x, y};
        double z = top;
        for (const Disk& d : disks)
          if (dist(q, d.c) <= d.r) z = std::min(z, d.bottom);
        highest = std::max(highest, z);
      }
  }
  return highest;
}

TEST(Touched, HighestAlongBoundsTheStockAndStandsAboveAgreesWithIt) {
  // Rows of overlapping holes at random depths, some gaps left standing; moves
  // among them. highestAlong never below the stock the swept disk meets, and
  // standsAbove (which skips the polygons) gives the same answer as asking it.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const double top = 10.0;
  const Material material(std::nullopt, top);
  Touched touched(8.0, material);
  std::vector<Disk> disks;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 4; ++j) {
      if (u(rng) < 0.15) continue;  // a gap: full stock stays
      const Disk d{{i * 5.0 + u(rng), j * 5.0 + u(rng)}, 3.0 + u(rng), -5.0 * u(rng)};
      disks.push_back(d);
      touched.add(d.c, d.r, d.bottom);
    }
  int above = 0, below = 0;
  for (int m = 0; m < 60; ++m) {
    const Vec2 a{35 * u(rng), 15 * u(rng)};
    const Vec2 b = a + Vec2{4 * u(rng) - 2, 4 * u(rng) - 2};
    const double r = 0.5 + 2 * u(rng);
    const double h = touched.highestAlong(a, b, r);
    EXPECT_GE(h, sampledHighest(disks, top, a, b, r) - 1e-9) << m;
    for (double z : {-6.0, -3.0, -1.0, 0.0, h - 1e-6, h, 9.0}) {
      EXPECT_EQ(touched.standsAbove(a, b, r, z), h > z) << m << " z " << z;
      (h > z ? above : below) += 1;
    }
  }
  EXPECT_GT(above, 50);
  EXPECT_GT(below, 50);
}

}  // namespace
}  // namespace plunge
