// Covering what the packing leaves (thesis section 4.2.3, then beyond it).
//
// 1. Delaunay gap covering (4.2.3): the packed centres are triangulated; a
//    triangle is *closed* when its three circles touch, *open* otherwise; open
//    triangles sharing an open edge merge into one gap polygon. The uncovered
//    part of each gap (exact polygon booleans, not the thesis's tangent-point
//    approximation) is enclosed by its smallest circle, whose radius is readjusted
//    to the next larger tool, or split when larger than the largest tool.
// 2. Residual covering: what is still uncovered is measured with polygon
//    booleans and covered greedily (largest uncovered area gained per plunge),
//    first every free-standing pin of material, then the material left along the
//    walls until the coverage target is met. The thesis stops at 84-93 %.
// 3. Pruning: plunges whose disk the others already cover are dropped.
#pragma once
#include "plunge/progress.hpp"
#include <vector>

#include "plunge/geometry.hpp"
#include "packing.hpp"
#include "region.hpp"

namespace plunge {

enum class Stage { Packing, Gap, Residual };

struct CoverDisk {
  Vec2 center;
  double radius = 0.0;
  int tool = 0;  // index into the radii list
  Stage stage = Stage::Packing;
};

struct CoveringOptions {
  double allowance = 0.0;  // radial allowance, as in packing
  // Stop covering material attached to the walls once this fraction of the
  // accessible region is covered (free-standing pins are always covered).
  double minCoverage = CoveringSettings{}.minCoverage;  // the input's default, written once (types.hpp)
  // The wall band (mm beyond the allowance, "max_wall_stock"): when > 0, every
  // point of the accessible region farther than allowance + maxWallStock from the
  // walls is covered (the core), material inside the band may stay, and
  // minCoverage is not used. 0: cover down to minCoverage.
  double maxWallStock = 0.0;
  // With a wall band: measure what the disks leave (CoverResult's uncovered,
  // coveredArea, coreUncovered). A plan that measures its final plunges
  // anyway skips it.
  bool measureCore = true;
  Progress progress;  // checked per plunge placed
};

// The region shrunk by the allowance (what may be cut at all).
Polygons allowedRegion(const Region& region, double allowance);
// The part of it that the smallest tool can reach: opening by its radius.
Polygons accessibleRegion(const Region& region, double minRadius, double allowance);
// What must be cut with a wall band: the accessible region minus the band
// (points farther than allowance + maxWallStock from every wall and island).
Polygons coreRegion(const Region& region, const Polygons& accessible, double allowance, double maxWallStock);
// The part of `area` outside every disk (polygon booleans; disks become
// inscribed polygons, so what is uncovered is never underestimated).
Polygons uncoveredRegion(const Polygons& area, const std::vector<Circle>& disks);

// Delaunay triangles of the packed centres grouped into gaps (4.2.3.1).
struct GapTriangle {
  int v[3];     // indices into the packed disks
  bool closed;  // all three circles touch (in contact radii)
};
struct DelaunayGaps {
  std::vector<GapTriangle> triangles;
  std::vector<std::vector<int>> groups;  // triangle indices: a closed triangle alone, or merged open ones
};
DelaunayGaps delaunayGaps(const std::vector<PackedDisk>& packed);

struct CoverResult {
  std::vector<CoverDisk> disks;  // packed disks first, then gap and residual plunges
  double accessibleArea = 0.0;
  double coveredArea = 0.0;
  Polygons uncovered;  // accessible region minus all disks
  // With a wall band: the core and what of it the disks leave (inscribed disks).
  double coreArea = 0.0;
  Polygons coreUncovered;
};

CoverResult coverRegion(const Region& region, const std::vector<double>& radii,
                        const std::vector<PackedDisk>& packed, const CoveringOptions& options = {});

}  // namespace plunge
