// Rest plunging: the material before this operation. The Job's stock and the
// operations before this one, replayed as moves of their cutters over a
// MaterialGrid (types.hpp), give the "material" a plan starts from
// (docs/plan-format.md); the plan's own moves, swept the same way, give the
// material it hands on.
#pragma once
#include <vector>

#include "plunge/progress.hpp"
#include "plunge/types.hpp"

namespace plunge {

// A straight move of the tool tip (program coordinates, mm).
struct Move {
  double x0, y0, z0, x1, y1, z1;
};

// A grid of nx x ny cells of `spacing` from `origin`, every cell at `top`.
MaterialGrid materialGrid(Vec2 origin, double spacing, size_t nx, size_t ny, double top);

// Lowers each cell of `grid` to what `cutter` leaves at its centre moving
// along `moves` in order (rapids too: the machine cuts whatever it meets), as
// the plan reads the grid ("material" in docs/plan-format.md). Throws
// plunge::Error on a move that is not finite; `progress` may cancel.
void sweep(MaterialGrid& grid, const Cutter& cutter, const std::vector<Move>& moves,
           const Progress& progress = Progress());

}  // namespace plunge
