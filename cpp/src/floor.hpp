// The pocket's floor as a height field z = f(x, y) (docs/plan-format.md,
// "floor"): flat, an expression (muParser), or OpenCASCADE BREP faces.
// Not thread-safe: evaluation caches state; a clone evaluates on its own.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "plunge/geometry.hpp"
#include "plunge/progress.hpp"

namespace plunge {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

// The candidates for the floor's local maxima, and how many faces or edges
// the optimizer could not settle within its budget: their candidates are a
// dense sample instead, each raised by its largest difference to a neighbour
// (a bound on the surface between samples, never below it where it is smooth).
struct PeakSearch {
  std::vector<Vec3> points;
  int fallbacks = 0;
};

class FloorSurface {
 public:
  virtual ~FloorSurface() = default;
  // Height of the floor under (x, y); NaN where no floor is under the point
  // (or, for an expression, where it has no finite value).
  virtual double height(Vec2 p) const = 0;
  // Every point of the floor inside [lo, hi] where its height may have a local
  // maximum over the plane: its peaks, and the highest points of ridges (edges
  // between faces) and corners. The maximum over a disk is at one of these
  // inside the disk or on the disk's rim (thesis 4.4). `spacing` is the finest
  // feature the search must resolve. Ticks `progress` (it may cancel).
  virtual PeakSearch peaks(Vec2 lo, Vec2 hi, double spacing, const Progress& progress) const = 0;
  virtual bool isFlat() const { return false; }
  // The same floor with its own evaluation state, for another thread.
  virtual std::unique_ptr<FloorSurface> clone() const = 0;
};

std::unique_ptr<FloorSurface> makeFlatFloor(double z);
// z = f(x, y) with x, y, numbers, + - * / ^, parentheses and sin cos tan exp
// log (natural) sqrt abs min max and muParser's other functions. Throws
// plunge::Error when it does not parse or uses another variable.
std::unique_ptr<FloorSurface> makeExpressionFloor(const std::string& expression);
// The face(s) of a BREP file (or BREP text): the floor height is the highest
// face point over (x, y). Throws plunge::Error when unreadable or without faces.
std::unique_ptr<FloorSurface> makeBrepFloor(const std::string& path);
std::unique_ptr<FloorSurface> makeBrepFloorFromText(const std::string& brep);

}  // namespace plunge
