// Polygon areas, offsets and booleans (Clipper, libpolyclipping) on millimetre
// coordinates. Used to measure and find what the plunges leave uncovered;
// gouge checks never rely on these approximations (see region.hpp).
#pragma once
#include <vector>

#include "detail.hpp"
#include "plunge/geometry.hpp"
#include "region.hpp"

namespace plunge::poly {

// kScale and kArcTolerance: detail.hpp (clip.hpp, the layer below, uses them too).

double area(const Polygons& p);
// Round-joined offset; negative delta shrinks.
Polygons offset(const Polygons& p, double delta, double arcTolerance = kArcTolerance);
Polygons unite(const Polygons& a, const Polygons& b = {});
Polygons intersect(const Polygons& a, const Polygons& b);
Polygons subtract(const Polygons& a, const Polygons& b);
// Connected components: each is an outer loop followed by its holes.
std::vector<Polygons> components(const Polygons& p);
// Polygon inscribed in the circle, vertex count chosen from the chord error.
Loop disk(const Circle& c, double chordError = kArcTolerance);
Polygons unionOfDisks(const std::vector<Circle>& disks, double chordError = kArcTolerance);

}  // namespace plunge::poly
