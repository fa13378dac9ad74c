// Internal: small helpers the modules share (not installed, not part of the API).
#pragma once
#include <algorithm>
#include <cmath>
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "plunge/geometry.hpp"

namespace plunge::poly {

// Clipper works on integers: 1e5 units per millimetre (10 nm), exact 64-bit
// arithmetic for pockets up to 10 m.
constexpr double kScale = 1e5;
// Chord error used when arcs (offsets, disks) become polygons.
constexpr double kArcTolerance = 0.002;

}  // namespace plunge::poly

namespace plunge::detail {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Feasibility slack, mm: a disk may come this much nearer a wall or another disk
// than it should (rounding of tangent constructions).
constexpr double kTol = 1e-9;
// The hexagon each disk of radius r covers in the thinnest covering: 3 sqrt(3) / 2 r^2.
constexpr double kHexCellArea = 2.598076211353316;

// "(x, y)" for messages.
inline std::string formatPoint(const double* x, int dimensions, int digits = 6) {
  std::ostringstream s;
  s.precision(digits);
  s << "(";
  for (int i = 0; i < dimensions; ++i) s << (i ? ", " : "") << x[i];
  s << ")";
  return s.str();
}
inline std::string formatPoint(Vec2 p) {
  const double x[2] = {p.x, p.y};
  return formatPoint(x, 2);
}

// A number with a fixed count of decimals, for messages ("12.50").
inline std::string fixed(double v, int decimals = 2) {
  std::ostringstream s;
  s << std::fixed;
  s.precision(decimals);
  s << v;
  return s.str();
}

// An axis-aligned bounding box grown point by point.
struct Bounds {
  Vec2 lo{kInf, kInf};
  Vec2 hi{-kInf, -kInf};
  void add(Vec2 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  void add(const Loop& loop) {
    for (Vec2 p : loop) add(p);
  }
};

// Where segment a-b crosses the horizontal line at y, by the half-open rule (a
// vertex on the line counts for one of its two segments): the base of every
// ray-casting and scan-line test.
inline std::optional<double> crossingX(Vec2 a, Vec2 b, double y) {
  if ((a.y > y) == (b.y > y)) return std::nullopt;
  return a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x);
}
// Does segment a-b cross the ray from p towards +x?
inline bool crossesRay(Vec2 a, Vec2 b, Vec2 p) {
  const std::optional<double> x = crossingX(a, b, p.y);
  return x && *x > p.x;
}

// Boost.Geometry R-trees of boxes or points, each with an index into the caller's list.
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using BBox = bg::model::box<BPoint>;
using BoxValue = std::pair<BBox, int>;
using PointValue = std::pair<BPoint, int>;
template <class Value>
using RStarTree = bgi::rtree<Value, bgi::rstar<16>>;
// Quadratic splitting where GCC 12 reports a false maybe-uninitialized in rstar's insertion.
template <class Value>
using QuadraticTree = bgi::rtree<Value, bgi::quadratic<16>>;

inline BPoint toBPoint(Vec2 p) { return BPoint(p.x, p.y); }
inline BBox boxOf(const Segment& s) {
  return BBox(BPoint(std::min(s.a.x, s.b.x), std::min(s.a.y, s.b.y)),
              BPoint(std::max(s.a.x, s.b.x), std::max(s.a.y, s.b.y)));
}
inline BBox boxOf(Vec2 lo, Vec2 hi) { return BBox(BPoint(lo.x, lo.y), BPoint(hi.x, hi.y)); }
inline BBox boxAround(Vec2 c, double r) { return BBox(BPoint(c.x - r, c.y - r), BPoint(c.x + r, c.y + r)); }

// A grid cell's key. Unsigned: shifting a negative cell index left is undefined.
inline long long cellKey(long i, long j) {
  const unsigned long long hi = static_cast<unsigned long long>(i) << 32;
  return static_cast<long long>(hi ^ (static_cast<unsigned long long>(j) & 0xffffffffULL));
}
// The key of the cell `cell` wide that holds p.
inline long long cellKeyOf(Vec2 p, double cell) {
  return cellKey(static_cast<long>(std::floor(p.x / cell)), static_cast<long>(std::floor(p.y / cell)));
}

// Items of a grid keyed by cellKey, cells `cell` wide: whether f holds for
// any in the 3 x 3 cells around c (each visited until one does).
template <class T, class F>
bool anyNear(const std::unordered_map<long long, std::vector<T>>& grid, Vec2 c, double cell, F f) {
  const long ci = static_cast<long>(std::floor(c.x / cell)), cj = static_cast<long>(std::floor(c.y / cell));
  for (long j = cj - 1; j <= cj + 1; ++j)
    for (long i = ci - 1; i <= ci + 1; ++i) {
      const auto it = grid.find(cellKey(i, j));
      if (it != grid.end())
        for (const T& item : it->second)
          if (f(item)) return true;
    }
  return false;
}

}  // namespace plunge::detail
