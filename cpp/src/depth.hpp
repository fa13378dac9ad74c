// Plunge depths over a sculptured floor (thesis section 4.4).
//
// A plunger stops where its lowest surface first touches the floor: for a
// flat-bottomed plunger, at the highest floor point under its disk. That point
// is either a local maximum of the floor inside the disk or the maximum along
// the disk's rim (eqs. 4.83-4.84). The floor's peaks are found once for the
// whole pocket with the global optimizer (optimizer.hpp); each plunge then needs
// only a one-variable optimization around its rim. Ball-end and bull-nose
// plungers (drop-cutter) maximise floor height minus the tool's profile over
// the disk, started from the grid and from the floor's peaks.
#pragma once
#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "floor.hpp"
#include "plunge/progress.hpp"
#include "plunge/types.hpp"

namespace plunge {

// Height of the cutter's lower surface above its tip at distance rho from its
// axis. Inline: the rasters call it per cell.
inline double cutterProfile(const Cutter& c, double rho) {
  if (c.shape == CutterShape::Flat) return 0.0;
  rho = std::clamp(rho, 0.0, c.radius);
  const double rc = c.shape == CutterShape::Ball ? c.radius : c.cornerRadius;
  const double flat = c.radius - rc;
  if (rho <= flat) return 0.0;
  const double t = rho - flat;
  return rc - std::sqrt(std::max(0.0, rc * rc - t * t));
}

class DepthSolver {
 public:
  // Finds the floor's peaks over [lo, hi], resolving features down to `spacing`
  // (ticking `progress`, which may cancel).
  // `part`: the part's triangles within reach of the pocket (part.hpp), when
  // given: every height below is the higher of the floor's and the part's,
  // the allowances kept from both.
  DepthSolver(const FloorSurface& floor, Vec2 lo, Vec2 hi, double spacing, const Progress& progress = {},
              std::shared_ptr<const FloorSurface> part = nullptr);
  // The same solver over another instance of the same floor (a clone, for
  // another thread): the peaks are not searched again (the part's mesh reads
  // from any thread).
  DepthSolver(const FloorSurface& floor, const DepthSolver& like)
      : floor_(floor), part_(like.part_), spacing_(like.spacing_), peaks_(like.peaks_),
        peakFallbacks_(like.peakFallbacks_), depthFallbacks_(like.depthFallbacks_) {}
  // Tip height at which the cutter at `center` first touches the floor or the
  // part (no allowance). Throws plunge::Error when no floor is under the cutter.
  double stopHeight(Vec2 center, const Cutter& cutter) const;
  // Where a plunge at `center` stops: `floorAllowance` above the floor under the
  // cutter, and `radialAllowance` from the floor beside it (the cutter grown
  // sideways by it does not touch the floor). The second holds the cutter up
  // where the floor rises steeply beyond its rim: a fillet rising into its
  // wall, or a step between two selected levels, which is a wall of the lower
  // one. Throws plunge::Error when no floor is under the cutter.
  double plungeHeight(Vec2 center, const Cutter& cutter, double floorAllowance, double radialAllowance) const;
  // A lower bound of plungeHeight from the floor at 16 points of the rim
  // (where a flat plunger on a fillet stops) and, with a radial allowance, as
  // far beyond it: about 1 % of the exact height's cost. It lets the floor-stock step
  // and the lead-outs turn down most plunges and moves that would stop too
  // high without the exact height (-inf where no floor is under those points).
  double plungeHeightAtLeast(Vec2 center, const Cutter& cutter, double floorAllowance, double radialAllowance) const;
  // plungeHeight(...) <= z, the bound first.
  bool plungesTo(Vec2 center, const Cutter& cutter, double floorAllowance, double radialAllowance, double z) const {
    return !(plungeHeightAtLeast(center, cutter, floorAllowance, radialAllowance) > z) &&
           !(plungeHeight(center, cutter, floorAllowance, radialAllowance) > z);
  }
  const std::vector<Vec3>& peaks() const { return peaks_; }
  const FloorSurface& floor() const { return floor_; }
  // Where the optimizer ran out of its (generous) budget and a dense sample
  // stood in: faces or edges of the peak search, and plunge depths so far.
  int peakFallbacks() const { return peakFallbacks_; }
  int depthFallbacks() const { return *depthFallbacks_; }

 private:
  double floorStopHeight(Vec2 center, const Cutter& cutter) const;
  double partStopHeight(Vec2 center, const Cutter& cutter) const;  // -inf without a part under the cutter
  double searchedStopHeight(Vec2 center, const Cutter& cutter, bool& converged) const;
  const FloorSurface& floor_;
  std::shared_ptr<const FloorSurface> part_;
  double spacing_;
  std::vector<Vec3> peaks_;
  int peakFallbacks_ = 0;
  // Shared by the solvers of every thread (the constructor above).
  std::shared_ptr<std::atomic<int>> depthFallbacks_ = std::make_shared<std::atomic<int>>(0);
};

// The cutter widened by `by` at every height: a flat one wider, a ball or bull
// nose with a flat of `by` more at its centre.
Cutter grownSideways(const Cutter& cutter, double by);

// The cutter offset by `by` in every direction (its Minkowski sum with a ball),
// its tip `by` lower: a flat one a bull nose with corners of radius `by`, a
// bull nose's corners and a ball `by` larger.
Cutter grownAround(const Cutter& cutter, double by);

// Reference: dense sampling of the disk every `spacing`, then a local
// derivative-free refinement of the best samples. Slow; for tests and benchmarks.
double stopHeightBruteForce(const FloorSurface& floor, Vec2 center, const Cutter& cutter, double spacing);

}  // namespace plunge
