// The exact radial engagement (cuts.hpp): the most uncut material along one
// radius, against known answers and a dense brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "cuts.hpp"

using namespace plunge;

namespace {

const Cutter kR5{CutterShape::Flat, 5.0, 0.0};

struct Made {
  Vec2 c;
  double r;
};

// The same measure the slow way: 3600 radii, each sampled every 2 micrometres
// against the circles (flat tools, one depth).
double bruteForce(const std::vector<Made>& made, Vec2 c, double r) {
  double most = 0;
  for (int k = 0; k < 3600; ++k) {
    const Vec2 u{std::cos(2 * kPi * k / 3600), std::sin(2 * kPi * k / 3600)};
    int in = 0;
    const int n = static_cast<int>(r / 0.002);
    for (int s = 0; s < n; ++s) {
      const Vec2 p = c + u * ((s + 0.5) * 0.002);
      bool cut = false;
      for (const Made& m : made) cut = cut || dist(p, m.c) <= m.r;
      in += !cut;
    }
    most = std::max(most, in * 0.002);
  }
  return most;
}

}  // namespace

// Into solid: the radius. Beside a hole at centre distance s: a crescent s
// thick, at most the radius. Into its own hole: nothing.
TEST(Cuts, SolidCrescentAndNothing) {
  Cuts cuts(0.5);
  EXPECT_DOUBLE_EQ(cuts.engagement({0, 0}, kR5, -10), 5.0);
  cuts.add({0, 0}, kR5, -10);
  for (double s : {0.5, 1.0, 2.5, 4.0, 7.0}) EXPECT_NEAR(cuts.engagement({s, 0}, kR5, -10), std::min(s, 5.0), 1e-6) << s;
  EXPECT_NEAR(cuts.engagement({0, 0}, kR5, -10), 0.0, 1e-9);
  // Deeper than the hole by less than the skin: nothing; by more: solid.
  EXPECT_NEAR(cuts.engagement({0, 0}, kR5, -10.4), 0.0, 1e-9);
  EXPECT_NEAR(cuts.engagement({0, 0}, kR5, -11), 5.0, 1e-9);
}

// A ridge 2 mm wide between two holes, the plunge centred on it: the
// material along the ridge is the whole radius, though the ridge is thin.
// Off the ridge's middle by 0.5 mm, still the radius; a plunge whose axis is
// in a hole beside the ridge meets the ridge's chord along one radius.
TEST(Cuts, ARidgeAcrossTheDiskIsItsLength) {
  Cuts cuts(0.5);
  cuts.add({-6, 0}, kR5, -10);
  cuts.add({6, 0}, kR5, -10);
  EXPECT_NEAR(cuts.engagement({0, 0}, kR5, -10), 5.0, 1e-6);
  EXPECT_NEAR(cuts.engagement({0.5, 0}, kR5, -10), 5.0, 1e-6);
  const std::vector<Made> made{{{-6, 0}, 5}, {{6, 0}, 5}};
  EXPECT_NEAR(cuts.engagement({-3, 1}, kR5, -10), bruteForce(made, {-3, 1}, 5), 0.005);
}

// A very thin ridge, 0.004 mm, crossing the disk away from every sampled
// radius: the corner radii (through the circles' crossings) find it.
TEST(Cuts, AThinRidgeBetweenSampledRadii) {
  Cuts cuts(0.5);
  const double a = 0.3 * 2 * kPi / 1440;  // between two of the even radii
  const Vec2 u{std::cos(a), std::sin(a)}, n{-u.y, u.x};
  cuts.add(n * (5.002), kR5, -10);
  cuts.add(n * (-5.002), kR5, -10);
  EXPECT_GT(cuts.engagement({0, 0}, kR5, -10), 4.0);
}

// Random holes of several sizes: the measure against the brute force.
TEST(Cuts, AgreesWithBruteForce) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> pos(-8, 8), rad(2, 6);
  for (int trial = 0; trial < 12; ++trial) {
    Cuts cuts(0.5);
    std::vector<Made> made;
    for (int i = 0; i < 5; ++i) {
      const Made m{{pos(rng), pos(rng)}, rad(rng)};
      made.push_back(m);
      cuts.add(m.c, {CutterShape::Flat, m.r, 0}, -10);
    }
    const Vec2 c{0.3 * pos(rng), 0.3 * pos(rng)};
    EXPECT_NEAR(cuts.engagement(c, kR5, -10), bruteForce(made, c, 5), 0.005) << trial;
  }
}

// Enough: the measure stops as soon as one radius has more.
TEST(Cuts, StopsOnceOverEnough) {
  Cuts cuts(0.5);
  cuts.add({0, 0}, kR5, -10);
  EXPECT_GT(cuts.engagement({4, 0}, kR5, -10, 1.0), 1.0);
  EXPECT_NEAR(cuts.engagement({0.5, 0}, kR5, -10, 1.0), 0.5, 1e-6);
}

// A ball nose: the cut of one beside it clears the material only where its
// surface is as low as this one's (beyond the skin); shallower, none.
TEST(Cuts, ProfiledToolsCompareDepths) {
  const Cutter ball{CutterShape::Ball, 5.0, 5.0};
  Cuts cuts(0.5);
  cuts.add({0, 0}, ball, -10);
  const double beside = cuts.engagement({2, 0}, ball, -10);
  EXPECT_GT(beside, 2.0);  // the ball's rim rises: less is cleared than for flat tools
  EXPECT_LT(beside, 5.0);
  Cuts shallow(0.5);
  shallow.add({0, 0}, ball, -5);
  EXPECT_NEAR(shallow.engagement({0, 0}, ball, -10), 5.0, 1e-9);
}
