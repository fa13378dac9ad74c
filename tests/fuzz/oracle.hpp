// The fuzz target's judge of a plan: written from the input's JSON alone, with
// none of the planner's code (no Region, no geometry.hpp, no parser of its own
// beyond nlohmann's). A plunge gouges when its centre is outside the pocket
// (outside the boundary or inside an island), when its disk grown by the radial
// allowance crosses a wall segment, or when it stops below a flat floor plus
// the floor allowance.
#pragma once
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace plunge_oracle {

struct P {
  double x, y;
};
using Ring = std::vector<P>;

// Distance from p to the segment ab, by projection clamped to it.
inline double segmentDistance(P p, P a, P b) {
  const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

// Crossing-number containment of p in one ring.
inline bool insideRing(const Ring& r, P p) {
  bool in = false;
  for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
    if ((r[j].y > p.y) != (r[i].y > p.y) && r[j].x + (p.y - r[j].y) / (r[i].y - r[j].y) * (r[i].x - r[j].x) > p.x)
      in = !in;
  return in;
}

inline Ring ringOf(const nlohmann::json& j) {
  Ring r;
  for (const auto& q : j) r.push_back({q.at(0).get<double>(), q.at(1).get<double>()});
  return r;
}

// What a plan must keep, read from the input text the planner accepted.
struct Pocket {
  Ring boundary;
  std::vector<Ring> islands;
  double radialAllowance = 0.0, floorAllowance = 0.0;
  std::optional<double> flatFloor;  // "floor": {"z": ...}

  explicit Pocket(const std::string& text) {
    const nlohmann::json j = nlohmann::json::parse(text);
    boundary = ringOf(j.at("boundary"));
    if (j.contains("islands"))
      for (const auto& i : j["islands"]) islands.push_back(ringOf(i));
    if (j.contains("allowance")) {
      radialAllowance = j["allowance"].value("radial", 0.0);
      floorAllowance = j["allowance"].value("floor", 0.0);
    }
    if (j.contains("floor") && j["floor"].contains("z")) flatFloor = j["floor"]["z"].get<double>();
  }

  double wallDistance(P p) const {
    double best = INFINITY;
    auto walls = [&](const Ring& r) {
      for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) best = std::min(best, segmentDistance(p, r[j], r[i]));
    };
    walls(boundary);
    for (const Ring& r : islands) walls(r);
    return best;
  }

  bool inside(P p) const {
    if (!insideRing(boundary, p)) return false;
    return std::none_of(islands.begin(), islands.end(), [&](const Ring& r) { return insideRing(r, p); });
  }

  // "" when the plunge keeps every wall and the floor; otherwise what it breaks.
  std::string gouge(P c, double diameter, double z, double tol = 1e-6) const {
    std::ostringstream why;
    why.precision(9);
    if (!inside(c)) {
      why << "plunge of " << diameter << " mm at (" << c.x << ", " << c.y << ") is outside the pocket";
    } else if (const double d = wallDistance(c); d < 0.5 * diameter + radialAllowance - tol) {
      why << "plunge of " << diameter << " mm at (" << c.x << ", " << c.y << ") is " << d
          << " mm from a wall, less than its radius and the radial allowance";
    } else if (flatFloor && z < *flatFloor + floorAllowance - tol) {
      why << "plunge of " << diameter << " mm at (" << c.x << ", " << c.y << ") stops at " << z
          << ", below the floor and its allowance";
    }
    return why.str();
  }
};

}  // namespace plunge_oracle
