// The regular-grid baseline: the plunge patterns CAM systems offer (square grid
// and honeycomb), for comparison with packing and covering.
//
// Each tool, largest first, plunges at the nodes of its own grid whose disk (with
// the radial allowance) fits in the pocket; a smaller tool only plunges where its
// disk would still cut a noticeable part of what the larger ones left. Nothing
// else: the material the grids miss near free-form walls stays (the discrete
// pocket modelling paper's point, and what packing is measured against).
#pragma once
#include "plunge/progress.hpp"
#include <string>
#include <vector>

#include "covering.hpp"
#include "region.hpp"
#include "plunge/types.hpp"

namespace plunge {

struct GridOptions {
  GridPattern pattern = GridPattern::Honeycomb;
  // Grid step as a fraction of the tool diameter, in (0, 1]; 0 = the closest
  // step whose disks still cover the plane (honeycomb sqrt(3)/2, square sqrt(2)/2).
  double step = 0.0;
  double allowance = 0.0;
  // A smaller tool plunges where it cuts at least this fraction of its disk.
  double minGain = 0.05;
  Progress progress;  // checked per grid row
};

// Throws plunge::Error unless step is 0 or in (0, 1] (GridOptions::step).
void checkGridStep(double step);
// radii: tool radii (any order). Same result type as the covering.
CoverResult gridPlacements(const Region& region, const std::vector<double>& radii, const GridOptions& options);

}  // namespace plunge
