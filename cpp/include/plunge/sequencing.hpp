// Plunge sequencing: a short visiting order of points (thesis section 4.3.1).
#pragma once
#include <optional>
#include <vector>

#include "plunge/geometry.hpp"

namespace plunge {

// A permutation of the point indices making the tour short. closed = false
// gives an open path; with `start`, it begins at the point nearest to start.
std::vector<int> tour(const std::vector<Vec2>& points, bool closed = true,
                      std::optional<Vec2> start = std::nullopt);

double tourLength(const std::vector<Vec2>& points, const std::vector<int>& order, bool closed);

}  // namespace plunge
