// Internal: conversions between millimetre loops and Clipper's integer paths.
#pragma once
#include <clipper.hpp>
#include <cmath>

#include "detail.hpp"
#include "plunge/geometry.hpp"

namespace plunge::clip {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

inline IntPoint toInt(Vec2 p) {
  return IntPoint(static_cast<ClipperLib::cInt>(std::llround(p.x * poly::kScale)),
                  static_cast<ClipperLib::cInt>(std::llround(p.y * poly::kScale)));
}
inline Vec2 toMm(const IntPoint& p) {
  return {static_cast<double>(p.X) / poly::kScale, static_cast<double>(p.Y) / poly::kScale};
}
Paths toPaths(const Polygons& p);
Polygons toPolygons(const Paths& p);
double area(const Paths& p);  // mm^2
// Polygon of a disk: inscribed (inside the disk) or circumscribed (containing it).
Path diskPath(const Circle& c, double chordError = poly::kArcTolerance, bool circumscribed = false);
Paths boolean(const Paths& a, const Paths& b, ClipperLib::ClipType op);
Paths offset(const Paths& p, double deltaMm, double arcTolerance = poly::kArcTolerance);
// Connected components (outer path followed by its holes).
std::vector<Paths> components(const Paths& p);
// Bounding box in mm.
void bounds(const Paths& p, Vec2& lo, Vec2& hi);

}  // namespace plunge::clip
