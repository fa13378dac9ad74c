// The paths a tool limited to a radial band grows its cut along
// (engagement.hpp): the contour of its centre region, then rows or offsets of
// the contour inside it.
#pragma once
#include <vector>

#include "plunge/types.hpp"
#include "region.hpp"

namespace plunge {

// Positions a limited tool grows its cut along (thesis: none; what plunge-mill
// makers prescribe): the contour of its centre region (every loop, walls and
// islands) at most `wallStep` apart, and rows along the region's long axis (or
// offsets of the contour), at most `spacing` apart, their positions at most
// `step` apart. A plunge next
// to the last one on its path cuts a crescent no thicker than the step, so a
// limit e costs about area / (rowSpacing x e) plunges, however wide the rows.
struct GrowthPath {
  std::vector<Vec2> at;
  bool closed = false;   // a loop: its last position is next to its first
  bool contour = false;  // a loop of the contour (entered first; keeps the wall band)
  size_t piece = 0;      // the connected piece of the region it lies in
};
// Inside the contour, `pattern`: rows `spacing` apart, or offsets of the
// contour `spacing` apart (loops, each with a bridge from the loop outside it
// as a row meets the contour). Auto is taken as rows here; the growth tries
// both.
std::vector<GrowthPath> growthPaths(const Polygons& centres, double step, double wallStep, double spacing,
                                    GrowthPattern pattern = GrowthPattern::Rows);
// How far apart rows of plunges of radius r, `step` apart along each row and
// staggered by half a step, may run and still cut everything between them.
double rowSpacing(double r, double step);
// The same for loops side by side (offsets: not staggered).
double loopSpacing(double r, double step);

// Points along every loop of `ring`, `step` apart, the loops visited nearest
// first from `at`, each walked from its vertex nearest to where the last ended
// (the growth's rings, after the paths).
std::vector<Vec2> walk(const Polygons& ring, Vec2 at, double step);

// Where a wall curves away from the contour, neighbours a wall step apart
// leave a deeper scallop at the wall than on a straight one: a position is
// added between two whose scallop (the circles' crossing on the wall side)
// stands more than `scallop` beyond the allowance.
struct WallScallop {
  double r;          // the plunges' radius
  double allowance;  // the radial allowance
  double scallop;    // the most the scallops may stand beyond it
};
void refineContour(GrowthPath& path, const Polygons& centres, const Region& region, const WallScallop& band);

// Row positions the contour cuts anyway: every sample of the disk (rings a
// quarter radius apart) lies within r of a contour position. Between the
// wall's contour and an island's less than two swaths apart, a row would cut
// only what the contours cut; the growth enters such a position only where
// nothing else can be entered or started (a connector to a contour).
std::vector<std::vector<bool>> coveredByContour(const std::vector<GrowthPath>& paths, double r);

}  // namespace plunge
