// Depth benchmark: 1000 plunges over the B-spline floor tests/data/floors/bumps.brep.
// Times this method (the floor's peaks once, then each plunge's rim) against
// brute-force sampling of every disk, in one run, and reports how far apart
// their answers are.   build/tests/bench_depth tests/data/floors/bumps.brep
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "depth.hpp"

using namespace plunge;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: bench_depth FLOOR.brep\n");
    return 2;
  }
  const auto floor = makeBrepFloor(argv[1]);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> ux(10, 90), uy(10, 65);
  std::vector<std::pair<Vec2, Cutter>> plunges;
  for (int i = 0; i < 1000; ++i) plunges.push_back({{ux(rng), uy(rng)}, {CutterShape::Flat, 3.0 + i % 4 * 2.0, 0}});
  using clock = std::chrono::steady_clock;
  auto seconds = [](clock::time_point a) { return std::chrono::duration<double>(clock::now() - a).count(); };

  auto t0 = clock::now();
  const DepthSolver solver(*floor, {0, 0}, {100, 75}, 1.5);
  std::vector<double> ours;
  for (const auto& [c, k] : plunges) ours.push_back(solver.stopHeight(c, k));
  const double tOurs = seconds(t0);

  for (double h : {0.5, 0.25}) {
    t0 = clock::now();
    double worstBelow = 0, worstAbove = 0;
    for (size_t i = 0; i < plunges.size(); ++i) {
      const double b = stopHeightBruteForce(*floor, plunges[i].first, plunges[i].second, h);
      worstBelow = std::max(worstBelow, b - ours[i]);
      worstAbove = std::max(worstAbove, ours[i] - b);
    }
    std::printf("brute force, samples every %.2f mm: %.2f s; this method higher by at most %.2e mm, lower by at most %.2e mm\n",
                h, seconds(t0), worstAbove, worstBelow);
  }
  std::printf("this method (peaks once + 1000 rims): %.2f s\n", tOurs);
  return 0;
}
