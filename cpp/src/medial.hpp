// Medial axis, necks and subdivision of a pocket (polygon-subdivision thesis,
// chapters 4 and 5.1), for choosing the plungers.
//
// The thesis draws a pixel skeleton and finds necks from control-polygon
// convexity and angle tests. Here the medial axis is exact: the Voronoi diagram
// of the wall and island segments (Boost.Polygon), kept inside the pocket, each
// node with its clearance (distance to the nearest wall). A neck is then simply
// a node where the clearance has a local minimum and, on both sides, rises to at
// least `riseFactor` times that minimum: boundary necks and island necks alike.
#pragma once
#include <utility>
#include <vector>

#include "plunge/geometry.hpp"
#include "region.hpp"
#include "plunge/types.hpp"

namespace plunge {

struct MedialAxis {
  std::vector<Vec2> nodes;
  std::vector<double> radius;  // clearance of each node: the largest disk centred there
  std::vector<std::pair<int, int>> edges;
};

// Voronoi diagram of the region's segments, the part inside the region.
MedialAxis medialAxis(const Region& region);

// Largest disk inside the region (centre on the medial axis).
Circle largestInscribedCircle(const MedialAxis& axis);

std::vector<Neck> findNecks(const Region& region, const MedialAxis& axis, double riseFactor = 1.5);

// The region cut along the neck lines.
std::vector<SubRegion> subdivide(const Region& region, const MedialAxis& axis, const std::vector<Neck>& necks);

// Visiting order of the sub-regions (5.5): a minimum spanning tree over their
// centres of the inscribed circles, walked depth first from the one nearest `start`.
std::vector<int> subRegionOrder(const std::vector<SubRegion>& parts, Vec2 start);

}  // namespace plunge
