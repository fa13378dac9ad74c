// Maximum-hole-degree circle packing (thesis section 4.2.2).
//
// Circles of the given radii, largest first, are placed one at a time at a
// *corner placement* (tangent to two items: walls, reflex wall vertices or
// circles already placed) chosen by the maximum hole degree rule (eq. 4.68).
// Unlike the thesis, which recomputes every pair of items for every circle,
// the corner placements are kept as a candidate set updated incrementally when
// a circle is placed, with R-trees for the feasibility and hole-degree queries.
#pragma once
#include "plunge/progress.hpp"
#include <vector>

#include "plunge/geometry.hpp"
#include "region.hpp"
#include "plunge/types.hpp"

namespace plunge {

struct PackedDisk {
  Vec2 center;
  double radius = 0.0;         // the plunger's radius: the disk it cuts
  double contactRadius = 0.0;  // radius used for circle-to-circle tangency while packing
  int tool = 0;                // index into the radii given to packMaxHoleDegree
};

struct PackingOptions {
  // Circle-to-circle tangency is taken at contactRatio x radius. 1 is the thesis
  // (disjoint disks); sqrt(3)/2 makes equal disks meet at the spacing of the
  // thinnest covering lattice, so the interior needs no gap plunges. A little below
  // sqrt(3)/2 keeps the triple points overlapped despite rounding.
  double contactRatio = 0.86;
  // Radial allowance: every disk keeps radius + allowance from the walls.
  double allowance = 0.0;
  PackingOrder order = PackingOrder::HoleDegree;
  // The wall band (mm beyond the allowance, "max_wall_stock"; 0: none). When
  // > 0, packMaxHoleDegree places wall rows only: disks touching the walls, those
  // of one tool meeting at the band's chord 2 sqrt(2 r b - b^2), so that their
  // scallops stay inside the band (packWithWallBand adds the inside).
  double maxWallStock = 0.0;
  Progress progress;  // checked per placement: a cancelled plan stops here
};



// Centre distance at which two packed circles touch. Circles of one tool touch
// at their contact radii; a smaller tool touches a larger tool's disk at that disk's true radius, so
// smaller circles are packed only into material the larger disks really leave.
double contactDistance(const PackedDisk& a, const PackedDisk& b);

// Corner placements (eqs. 4.18-4.54). A wall segment keeps the new centre at
// `clearance` on its left (the material side) with the tangent point inside the
// segment; a circle locus puts the centre at distance locus.r from locus.c (a
// reflex wall vertex: clearance; a placed circle: the sum of contact radii).
std::vector<Vec2> cornerPlacementsWallWall(const Segment& a, const Segment& b, double clearance);
std::vector<Vec2> cornerPlacementsWallCircle(const Segment& wall, double clearance, const Circle& locus);
std::vector<Vec2> cornerPlacementsCircleCircle(const Circle& locusA, const Circle& locusB);

// Centre spacing of a wall row of radius-r disks whose scallops reach `band`
// into the material (the chord of the disk at depth band); 0 without a band.
double wallRowSpacing(double r, double band);

// How far inside its wall row the plain packing starts (centre to centre,
// across the wall's normal): inner disks meeting at 2 rho leave scallops
// sqrt(r^2 - rho^2) deep, which must stay on the strip the row cuts whole.
double wallRowInset(double r, double rho, double band);

// Eq. 4.68: hole degree lambda = 1 - d_min / r, d_min being the gap to the
// nearest item the placement does not touch (clamped to [0, r]).
double holeDegree(double dMin, double r);

// Packs circles of `radii` (any order; packed largest first) into the region.
// The returned disks never overlap in contact radii and never come closer to a
// wall than radius + allowance.
std::vector<PackedDisk> packMaxHoleDegree(const Region& region, const std::vector<double>& radii,
                                          const PackingOptions& options = {});

// With a wall band: one tool's wall rows, then the plain packing inside them
// (its wall clearance increased by wallRowInset). No band: packMaxHoleDegree.
std::vector<PackedDisk> packWithWallBand(const Region& region, double radius, const PackingOptions& options);

}  // namespace plunge
