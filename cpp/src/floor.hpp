// The pocket's floor as a height field z = f(x, y) (docs/plan-format.md,
// "floor"): flat, an expression (muParser), OpenCASCADE BREP faces
// (brep_floor.cpp) or a triangle mesh (mesh_floor.hpp).
// Not thread-safe: evaluation caches state; a clone evaluates on its own.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include <algorithm>
#include <cmath>
#include <optional>

#include "plunge/geometry.hpp"
#include "plunge/optimizer.hpp"
#include "plunge/progress.hpp"
#include "plunge/types.hpp"

namespace plunge {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

// The candidates for the floor's local maxima, and how many faces or edges
// the optimizer could not settle within its budget: their candidates are a
// dense sample instead, each raised by its largest difference to a neighbour
// (a bound on the surface between samples, never below it where it is smooth).
struct PeakSearch {
  std::vector<Vec3> points;
  int fallbacks = 0;
};

class FloorSurface {
 public:
  virtual ~FloorSurface() = default;
  // Height of the floor under (x, y); NaN where no floor is under the point
  // (or, for an expression, where it has no finite value).
  virtual double height(Vec2 p) const = 0;
  // Every point of the floor inside [lo, hi] where its height may have a local
  // maximum over the plane: its peaks, and the highest points of ridges (edges
  // between faces) and corners. The maximum over a disk is at one of these
  // inside the disk or on the disk's rim (thesis 4.4). `spacing` is the finest
  // feature the search must resolve. Ticks `progress` (it may cancel).
  virtual PeakSearch peaks(Vec2 lo, Vec2 hi, double spacing, const Progress& progress) const = 0;
  virtual bool isFlat() const { return false; }
  // The tip height at which `cutter` over `center` first touches the floor,
  // where the floor can say it exactly (a mesh: mesh_floor.hpp); NaN where no
  // floor is under the cutter. nullopt: the depth solver searches (depth.hpp).
  virtual std::optional<double> exactStopHeight(Vec2 /*center*/, const Cutter& /*cutter*/) const {
    return std::nullopt;
  }
  // The same floor with its own evaluation state, for another thread.
  virtual std::unique_ptr<FloorSurface> clone() const = 0;
  // Why no plunger can follow the floor over [lo, hi] ("" when one can): an
  // expression may rise and fall on a scale no cutter or depth search
  // resolves (sin(x*1e6)), and its depths would take hours to search. Faces
  // and meshes come from a part: they cannot.
  virtual std::string unfollowable(Vec2 /*lo*/, Vec2 /*hi*/) const { return {}; }
};

std::unique_ptr<FloorSurface> makeFlatFloor(double z);
// z = f(x, y) with x, y, numbers, + - * / ^, parentheses and sin cos tan exp
// log (natural) sqrt abs min max and muParser's other functions. Throws
// plunge::Error when it does not parse or uses another variable.
std::unique_ptr<FloorSurface> makeExpressionFloor(const std::string& expression);
// The face(s) of a BREP file (or BREP text): the floor height is the highest
// face point over (x, y). Throws plunge::Error when unreadable or without
// faces, or when the planner is built without OpenCASCADE (brep_floor.cpp).
std::unique_ptr<FloorSurface> makeBrepFloor(const std::string& path);
std::unique_ptr<FloorSurface> makeBrepFloorFromText(const std::string& brep);

// The floors' peak searches (floor.cpp, brep_floor.cpp).
namespace detail {

inline int samplesFor(double extent, double spacing, int lo, int hi) {
  return std::clamp(static_cast<int>(std::ceil(extent / spacing)) + 1, lo, hi);
}

inline bool inside(Vec3 p, Vec2 lo, Vec2 hi) { return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y; }

// Samples per variable of the fallback when the optimizer runs out of budget.
constexpr int kFallbackSamples = 241;

// The optimizer's options for a peak search: its grid, and progress polled.
inline OptimizeOptions peakOptions(int samples, const Progress& progress) {
  OptimizeOptions opt;
  opt.samples = samples;
  opt.clusterRadius = 2.5 / samples;  // a few grid steps: peaks stay apart
  opt.skipNonFinite = true;           // outside the domain (a trimmed face)
  opt.poll = [&progress] { progress.tick(); };
  return opt;
}

// The fallback of a peak search: `at(i, j)` on an n x m grid (m = 1: a curve)
// gives a point (z NaN outside the domain); every grid point at least as high
// as its neighbours, raised by its largest rise or fall to one of them.
template <class F>
std::vector<Vec3> sampledPeaks(int n, int m, F at, const Progress& progress) {
  std::vector<Vec3> g(static_cast<size_t>(n) * m);
  for (int j = 0; j < m; ++j) {
    progress.tick();
    for (int i = 0; i < n; ++i) g[static_cast<size_t>(j) * n + i] = at(i, j);
  }
  std::vector<Vec3> out;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec3& p = g[static_cast<size_t>(j) * n + i];
      if (!std::isfinite(p.z)) continue;
      bool top = true;
      double rise = 0;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int a = i + di, b = j + dj;
          if ((!di && !dj) || a < 0 || a >= n || b < 0 || b >= m) continue;
          const double z = g[static_cast<size_t>(b) * n + a].z;
          if (!std::isfinite(z)) continue;
          top = top && z <= p.z;
          rise = std::max(rise, std::fabs(z - p.z));
        }
      if (top) out.push_back({p.x, p.y, p.z + rise});
    }
  return out;
}

}  // namespace detail

}  // namespace plunge
