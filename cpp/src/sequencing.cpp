#include "plunge/sequencing.hpp"

#include <cmath>
#include <limits>

#include "plunge/error.hpp"

namespace plunge {

std::vector<int> tour(const std::vector<Vec2>& points, bool closed, std::optional<Vec2> start) {
  for (const Vec2& p : points)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw Error("tour: point coordinate is not a finite number");
  if (start && (!std::isfinite(start->x) || !std::isfinite(start->y)))
    throw Error("tour: start is not a finite point");
  (void)closed;
  const int n = static_cast<int>(points.size());
  std::vector<int> order;
  if (n == 0) return order;
  std::vector<char> used(n, 0);
  int cur = 0;
  if (start) {
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i)
      if (dist(points[i], *start) < best) {
        best = dist(points[i], *start);
        cur = i;
      }
  }
  // Nearest neighbour (placeholder until the sequencing issue).
  for (int k = 0; k < n; ++k) {
    order.push_back(cur);
    used[cur] = 1;
    double best = std::numeric_limits<double>::infinity();
    int next = -1;
    for (int i = 0; i < n; ++i)
      if (!used[i] && dist(points[i], points[cur]) < best) {
        best = dist(points[i], points[cur]);
        next = i;
      }
    cur = next;
  }
  return order;
}

double tourLength(const std::vector<Vec2>& points, const std::vector<int>& order, bool closed) {
  double len = 0.0;
  for (size_t i = 1; i < order.size(); ++i) len += dist(points[order[i - 1]], points[order[i]]);
  if (closed && order.size() > 1) len += dist(points[order.back()], points[order.front()]);
  return len;
}

}  // namespace plunge
