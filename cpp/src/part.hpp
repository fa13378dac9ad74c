// The part around the pocket ("part": {"mesh"}, docs/plan-format.md): the
// FreeCAD addon's triangles of the part's faces within reach of the pocket.
// The floor and the walls' outline say where the pocket is; the part says
// what else stands in it, seen whole:
// - part material over the pocket above its floor (a tab, a dome wider than
//   its stem) is taken out of the region: no plunge goes under it
//   (overhangsOver);
// - every stop is the drop of the cutter on the part as on the floor, the
//   higher of the two (DepthSolver, partInReach): a stop, lead-out or
//   retract never enters the part, whatever the outline says.
// The walls, whose triangles meet the region only along its loops, stay the
// region's: triangles no farther inside it than `margin` (their deviation)
// are left out of both.
#pragma once
#include <optional>
#include <vector>

#include "floor.hpp"
#include "region.hpp"
#include "plunge/geometry.hpp"
#include "plunge/types.hpp"

namespace plunge {

// How far inside the region a triangle must reach to count (mm): twice the
// part's largest deviation (a chord of a wall pokes that far in at most), and
// never less than kPartMargin.
constexpr double kPartMargin = 0.005;
double partMargin(const TriangleMesh& part);

// The shadow (plan view) of the part's material above height `above` that lies
// over `region` farther than `margin` inside it, grown back by `margin`: each
// piece is part material overhanging the pocket. Empty where none does.
Polygons overhangsOver(const TriangleMesh& part, double above, const Polygons& region, double margin);

// The part's triangles whose shadow reaches into `region` farther than `margin`.
TriangleMesh partInReach(const TriangleMesh& part, const Polygons& region, double margin);

// The pocket `region` at height z, less what of the part stands in it there
// or above (seen from above, as overhangsOver): an island's or a dome's top
// under a section of the pocket. None where nothing does; where the part
// parts it, its largest piece.
std::optional<Region> pocketBelow(const TriangleMesh& part, const Region& region, double z);

// The job without what of in.part overhangs `floor` (higher than the floor's
// highest point in the pocket): its boundary and islands are the pocket's
// less that shadow, and a note (in.notes) says how much floor is left under
// it, where, and what a piece it parts off measures (the largest is planned).
// Throws plunge::Error where nothing of the pocket is left.
PlanInput withoutOverhangs(PlanInput in, const FloorSurface& floor);

}  // namespace plunge
