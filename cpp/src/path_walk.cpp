#include "path_walk.hpp"

#include <cmath>

namespace plunge {

std::vector<Vec2> between(Vec2 a, Vec2 b, double step) {
  std::vector<Vec2> out;
  const int n = static_cast<int>(std::ceil(dist(a, b) / step - 1e-9));
  for (int i = 1; i < n; ++i) out.push_back(pointAlong(a, b, static_cast<double>(i) / n));
  return out;
}

void walkLoop(const Loop& loop, size_t start, double step, std::vector<Vec2>& out) {
  double carry = 0.0;  // distance walked since the last point
  out.push_back(loop[start]);
  for (size_t s = 0; s < loop.size(); ++s) {
    const Vec2 a = loop[(start + s) % loop.size()], b = loop[(start + s + 1) % loop.size()];
    const double len = dist(a, b);
    double t = step - carry;
    for (; t <= len; t += step) out.push_back(pointAlong(a, b, t / len));
    carry = len - (t - step);
  }
}

}  // namespace plunge
