// The stock a plan leaves, measured in 3D against the whole part ("part"):
// what the floor's outline cannot show. At heights from the floor up to
// the part's top, the stock standing over the floor (or over no part at all)
// after the plunges, and how far it is across from the part's material at
// that height (seen from above: an overhang is material below it too) or
// from the pocket's outline: rings around islands that narrow upward,
// columns over a window or a trough the outline left out. Stock within the
// floor allowance and max_floor_stock over the floor is the floor stock's;
// what stands over the part's other faces, the sections' (plan.cpp).
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
  // Heights the stock is worst just below (the sections' and the plunges'
  // stops), measured besides a uniform spread from the floor to the top.
  std::vector<double> heights;
  Progress progress;
};

// The thickest stock left across (beyond the radial allowance), at its
// height: 0 where none is left.
struct PartStock {
  double thickest = 0.0;
  Vec2 at;
  double z = 0.0;
};

// `outlines`: the pocket's outline and its sections' (where it is wider
// above its floor), each measured with what lies inside it (its islands'
// areas too: an island that narrows upward leaves a ring above the floor).
PartStock measurePartStock(const TriangleMesh& part, const FloorSurface& floor, const std::vector<Loop>& outlines,
                           const Material& material, const std::vector<Plunge>& plunges, const ToolTable& tools,
                           const PartStockOptions& options);

}  // namespace plunge
