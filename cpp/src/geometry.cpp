#include "plunge/geometry.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Min_circle_2.h>
#include <CGAL/Min_circle_2_traits_2.h>

#include <algorithm>

namespace plunge {

Vec2 closestPointOnSegment(const Segment& s, Vec2 p, double* tOut) {
  const Vec2 d = s.b - s.a;
  const double len2 = dot(d, d);
  double t = len2 > 0.0 ? dot(p - s.a, d) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  if (tOut) *tOut = t;
  return s.a + d * t;
}

double distanceToSegment(const Segment& s, Vec2 p) { return dist(p, closestPointOnSegment(s, p)); }

double signedArea(const Loop& loop) {
  double a = 0.0;
  const size_t n = loop.size();
  for (size_t i = 0; i < n; ++i) a += cross(loop[i], loop[(i + 1) % n]);
  return 0.5 * a;
}

namespace {
int orientation(Vec2 a, Vec2 b, Vec2 c) {
  const double v = cross(b - a, c - a);
  return (v > 0) - (v < 0);
}
bool onSegment(Vec2 a, Vec2 b, Vec2 p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}
}  // namespace

bool segmentsIntersect(const Segment& s1, const Segment& s2) {
  const int o1 = orientation(s1.a, s1.b, s2.a), o2 = orientation(s1.a, s1.b, s2.b);
  const int o3 = orientation(s2.a, s2.b, s1.a), o4 = orientation(s2.a, s2.b, s1.b);
  if (o1 != o2 && o3 != o4) return true;
  if (o1 == 0 && onSegment(s1.a, s1.b, s2.a)) return true;
  if (o2 == 0 && onSegment(s1.a, s1.b, s2.b)) return true;
  if (o3 == 0 && onSegment(s2.a, s2.b, s1.a)) return true;
  if (o4 == 0 && onSegment(s2.a, s2.b, s1.b)) return true;
  return false;
}

std::vector<Vec2> intersectCircles(const Circle& c1, const Circle& c2) {
  // Eqs. 4.39-4.54 of the thesis, written with the radical line.
  const Vec2 d = c2.c - c1.c;
  const double l = norm(d);
  if (l <= 0.0 || l > c1.r + c2.r || l < std::fabs(c1.r - c2.r)) return {};
  const double a = (c1.r * c1.r - c2.r * c2.r + l * l) / (2.0 * l);
  const double h2 = c1.r * c1.r - a * a;
  const Vec2 u = d * (1.0 / l);
  const Vec2 m = c1.c + u * a;
  if (h2 <= 0.0) return {m};
  const double h = std::sqrt(h2);
  const Vec2 n = leftNormal(u);
  return {m + n * h, m - n * h};
}

std::vector<double> intersectLineCircle(Vec2 p, Vec2 d, const Circle& c) {
  // |p + t d - c|^2 = r^2, solved in the numerically stable form.
  const Vec2 f = p - c.c;
  const double A = dot(d, d);
  if (A <= 0.0) return {};
  const double B = dot(f, d);
  const double C = dot(f, f) - c.r * c.r;
  const double disc = B * B - A * C;
  if (disc < 0.0) return {};
  if (disc == 0.0) return {-B / A};
  const double s = std::sqrt(disc);
  const double q = -(B + std::copysign(s, B));
  if (q == 0.0) return {0.0};
  return {q / A, C / q};
}

std::optional<Vec2> intersectLines(Vec2 p1, Vec2 d1, Vec2 p2, Vec2 d2) {
  const double den = cross(d1, d2);
  const double scale = norm(d1) * norm(d2);
  if (scale <= 0.0 || std::fabs(den) <= 1e-12 * scale) return std::nullopt;
  const double t = cross(p2 - p1, d2) / den;
  return p1 + d1 * t;
}

Circle minEnclosingCircle(const std::vector<Vec2>& points) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Traits = CGAL::Min_circle_2_traits_2<K>;
  if (points.empty()) return {};
  std::vector<K::Point_2> pts;
  pts.reserve(points.size());
  for (const Vec2& p : points) pts.emplace_back(p.x, p.y);
  // Randomised for speed, with a fixed seed so that plans are deterministic.
  CGAL::Random random(0);
  CGAL::Min_circle_2<Traits> mc(pts.begin(), pts.end(), true, random);
  const auto& circ = mc.circle();
  Circle out{{CGAL::to_double(circ.center().x()), CGAL::to_double(circ.center().y())},
             std::sqrt(CGAL::to_double(circ.squared_radius()))};
  // Inexact constructions: widen so that every point is really inside.
  for (const Vec2& p : points) out.r = std::max(out.r, dist(out.c, p));
  return out;
}

}  // namespace plunge
