// Walking along a path at a step: the growth's rings and bridges
// (growth_paths.hpp) and the lead-outs' samples of a straight move
// (lead_out.hpp) take their points here, by one formula.
#pragma once
#include <cstddef>
#include <vector>

#include "plunge/geometry.hpp"

namespace plunge {

// The point a share t of the way from a to b.
inline Vec2 pointAlong(Vec2 a, Vec2 b, double t) { return a + (b - a) * t; }

// Whether f holds at the n points that divide the move from a to b into equal
// pieces (b included, a not), tried in order until one fails.
template <class F>
bool allAlong(Vec2 a, Vec2 b, int n, F f) {
  for (int s = 1; s <= n; ++s)
    if (!f(pointAlong(a, b, static_cast<double>(s) / n))) return false;
  return true;
}

// The points strictly between a and b that divide the way into the fewest
// equal pieces at most `step` long.
std::vector<Vec2> between(Vec2 a, Vec2 b, double step);

// Appends points `step` apart once around a closed loop, from its vertex
// `start` (included).
void walkLoop(const Loop& loop, size_t start, double step, std::vector<Vec2>& out);

}  // namespace plunge
