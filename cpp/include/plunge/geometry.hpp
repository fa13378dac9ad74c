// Small value types and free functions of plane geometry used by every module.
#pragma once
#include <cmath>
#include <optional>
#include <vector>

namespace plunge {

// Pi (kPi is not standard C++).
inline constexpr double kPi = 3.14159265358979323846;

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
inline Vec2 operator*(double s, Vec2 a) { return {a.x * s, a.y * s}; }
inline bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }
inline bool operator!=(Vec2 a, Vec2 b) { return !(a == b); }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
// sqrt, not std::hypot: lengths here are millimetres (no overflow to guard
// against), and glibc's hypot cost a fifth of a plan's time.
inline double norm(Vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }
inline double dist(Vec2 a, Vec2 b) { return norm(a - b); }
inline Vec2 leftNormal(Vec2 d) { return {-d.y, d.x}; }

// A closed polyline: the last point does not repeat the first.
using Loop = std::vector<Vec2>;
// Several loops: a region (its outer loop and islands), or pieces of one.
using Polygons = std::vector<Loop>;

struct Segment {
  Vec2 a, b;
};

struct Circle {
  Vec2 c;
  double r = 0.0;
};

// Closest point of segment s to p, and the segment parameter t in [0, 1].
Vec2 closestPointOnSegment(const Segment& s, Vec2 p, double* t = nullptr);
double distanceToSegment(const Segment& s, Vec2 p);

// Signed area (positive when counter-clockwise).
double signedArea(const Loop& loop);

// Do two closed segments share a point?
bool segmentsIntersect(const Segment& s1, const Segment& s2);

// Intersections of two circles (0, 1 or 2 points).
std::vector<Vec2> intersectCircles(const Circle& c1, const Circle& c2);

// Intersections of the infinite line through p with direction d and a circle;
// returns the line parameters t (point = p + t d).
std::vector<double> intersectLineCircle(Vec2 p, Vec2 d, const Circle& c);

// Intersection of two infinite lines p1 + t d1 and p2 + u d2 (none if parallel).
std::optional<Vec2> intersectLines(Vec2 p1, Vec2 d1, Vec2 p2, Vec2 d2);

// Smallest circle enclosing the points (CGAL Min_circle_2).
Circle minEnclosingCircle(const std::vector<Vec2>& points);

}  // namespace plunge
