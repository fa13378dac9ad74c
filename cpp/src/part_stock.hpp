// The stock a plan leaves, measured in 3D against the whole part ("part"):
// what the floor's outline cannot show. At heights from the floor up to
// top_z, the air of the part there (the part seen from above: an overhang is
// material below it too) that still holds stock after the plunges, farther
// from the part's material than the radial allowance and the wall band:
// rings around islands that narrow upward, columns over a window or a trough
// the outline left out, stock beside an open side. The stock over the floor
// within max_floor_stock is the floor stock's (stock.hpp), not counted here.
// Measured on a raster of the pocket's outline: the part's upper envelope
// and the floor's heights (the higher), the stock's top after every plunge
// (the cutter's profile at its stop), and at each height the distance of the
// stock standing in the air there to the nearest material (an exact Euclidean
// distance transform of the raster).
#pragma once
#include <vector>

#include "floor.hpp"
#include "material.hpp"
#include "plunge/progress.hpp"
#include "plunge/tools.hpp"
#include "plunge/types.hpp"

namespace plunge {

struct PartStockOptions {
  double radialAllowance = 0.0;
  double floorAllowance = 0.0;
  double maxFloorStock = 0.0;  // the floor stock's own limit: stock under it over the floor is not the walls'
  double spacing = 0.5;        // mm between samples
  Progress progress;
};

// The thickest stock beyond the radial allowance, at its height: 0 where the
// plunges leave none farther from the part than the allowance.
struct PartStock {
  double thickest = 0.0;
  Vec2 at;
  double z = 0.0;
};

// `boundary`: the pocket's outline (its islands' areas are measured too: an
// island that narrows upward leaves a ring above the floor).
PartStock measurePartStock(const TriangleMesh& part, const FloorSurface& floor, const Loop& boundary,
                           const Material& material, const std::vector<Plunge>& plunges, const ToolTable& tools,
                           const PartStockOptions& options);

}  // namespace plunge
