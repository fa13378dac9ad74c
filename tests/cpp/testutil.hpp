// Shared helpers of the GoogleTest suite: random pockets and brute-force checks.
#pragma once
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "../fuzz/oracle.hpp"
#include "plunge/error.hpp"
#include "plunge/geometry.hpp"
#include "plunge/plan.hpp"
#include "region.hpp"

namespace plunge::test {

// A small job as plan input JSON: a 100 x 60 mm box with a triangular island,
// two tools, a flat floor, allowances (the output files' tests plan it).
inline std::string smallJobJson() {
  return R"({"version": 1, "boundary": [[0,0],[100,0],[100,60],[0,60]],
    "islands": [[[40,20],[60,20],[50,40]]], "tools": [{"diameter": 12, "id": 4}, {"diameter": 6}],
    "top_z": 0, "safe_z": 5, "floor": {"z": -10}, "allowance": {"radial": 0.2, "floor": 0.1},
    "strategy": "packing", "seed": 3})";
}

// A random star-shaped (hence simple) polygon around c with radii in [r0, r1].
inline Loop randomStar(std::mt19937& rng, Vec2 c, double r0, double r1, int n) {
  std::uniform_real_distribution<double> rad(r0, r1), jitter(-0.3, 0.3);
  Loop out;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * (i + 0.5 + jitter(rng)) / n;
    const double r = rad(rng);
    out.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
  return out;
}

inline Loop circleLoop(Vec2 c, double r, int n) {
  Loop out;
  for (int i = 0; i < n; ++i) out.push_back({c.x + r * std::cos(2 * kPi * i / n), c.y + r * std::sin(2 * kPi * i / n)});
  return out;
}

// Brute force: distance from p to the nearest wall of the loops (the fuzz
// oracle's segment distance, not the planner's).
inline double bruteWallDistance(const std::vector<Loop>& loops, Vec2 p) {
  double best = INFINITY;
  for (const Loop& L : loops)
    for (size_t i = 0; i < L.size(); ++i) {
      const Vec2 a = L[i], b = L[(i + 1) % L.size()];
      best = std::min(best, plunge_oracle::segmentDistance({p.x, p.y}, {a.x, a.y}, {b.x, b.y}));
    }
  return best;
}

// Brute force: even-odd point containment over all loops.
inline bool bruteInside(const std::vector<Loop>& loops, Vec2 p) {
  bool in = false;
  for (const Loop& L : loops)
    for (size_t i = 0, j = L.size() - 1; i < L.size(); j = i++) {
      const Vec2 a = L[j], b = L[i];
      if ((a.y > p.y) != (b.y > p.y) && a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) > p.x) in = !in;
    }
  return in;
}

// A rectangular pocket with a triangular island, 12 mm deep, and two plungers
// (20 mm T1, 10 mm T2), allowances 0.3 mm radial and 0.2 mm on the floor.
inline PlanInput rectanglePocket(double width = 120, double height = 80) {
  PlanInput in;
  in.boundary = {{0, 0}, {width, 0}, {width, height}, {0, height}};
  const Vec2 c{0.5 * width, 0.5 * height};
  in.islands = {{c + Vec2{-10, -10}, c + Vec2{10, -10}, c + Vec2{0, 10}}};
  in.tools = {{20, 1, 100}, {10, 2, 100}};
  in.floor.surface.z = -12;
  in.floorAllowance = 0.2;
  in.radialAllowance = 0.3;
  return in;
}

inline std::string readData(const std::string& rel) {
  std::ifstream f(std::string(PLUNGE_TEST_DATA) + "/" + rel);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The message plan() refuses the input with ("" when it plans).
inline std::string planError(PlanInput in) {
  try {
    plan(in);
  } catch (const Error& e) {  // only the library's own refusals: anything else fails the test
    return e.what();
  }
  return "";
}

// The same plunges, in the same order, bit for bit (determinism).
inline void expectSamePlunges(const Plan& a, const Plan& b) {
  ASSERT_EQ(a.plunges.size(), b.plunges.size());
  for (size_t i = 0; i < a.plunges.size(); ++i) {
    EXPECT_EQ(a.plunges[i].x, b.plunges[i].x);
    EXPECT_EQ(a.plunges[i].y, b.plunges[i].y);
    EXPECT_EQ(a.plunges[i].z, b.plunges[i].z);
    EXPECT_EQ(a.plunges[i].toolId, b.plunges[i].toolId);
  }
}

}  // namespace plunge::test
