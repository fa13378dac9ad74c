// The plunges made so far, as disks with the heights they cut to: the heights
// of rapids, the levels and the lead-outs (motion.hpp) ask it.
#pragma once
#include <limits>
#include <map>
#include <vector>

#include "material.hpp"
#include "plunge/geometry.hpp"

namespace plunge {

// Stock at a point is the
// lowest cut surface of the disks covering it, or top_z (stock or wall) where
// none does, so the highest stock under a rapid's swept disk is at most the
// highest bottom (tip + corner height) of the disks it meets, unless it meets
// untouched material. Exact where a raster could miss a feature narrower than
// a cell (a pin between three disks, the radial allowance). Pieces under
// 1e-4 mm^2, left by the disks' polygons (0.002 mm chords) and a 0.01 mm
// margin, do not count. A move meeting more than 150 disks goes over top_z.
class Touched {
 public:
  // The stock before any disk: the material the operations before left.
  Touched(double bucket, const Material& material) : bucket_(bucket), top_(material.topZ()), material_(material) {}
  void add(Vec2 c, double r, double bottom);
  // The top of the stock: the highest material anywhere (walls included).
  double topZ() const { return top_; }
  double bucket() const { return bucket_; }  // the side of its grid's cells
  // Centres of the disks at least `r` wide, cut no higher than `bottom`,
  // between `from` and `to` away from c, nearest first (at most `count`).
  std::vector<Vec2> holesNear(Vec2 c, double r, double bottom, double from, double to, size_t count) const;
  // Whether a disk of radius r moved from the hole at c to `end` reaches more
  // than `limit` beyond r from c into material: whether any of the crescent
  // of the moved disk farther than r + limit from c is left uncut by the
  // disks cut to `bottom` or deeper (polygons, nearest disks first; only the
  // crescent is clipped, so the booleans stay small).
  bool grazes(Vec2 c, Vec2 end, double r, double bottom, double limit) const;
  // The highest stock a disk of radius r swept from a to b passes over (an
  // upper bound; never above the material there).
  double highestAlong(Vec2 a, Vec2 b, double r) const;
  // Whether highestAlong(a, b, r) > z, without its polygon test where the
  // disks met already stand higher than z (a plunge deeper than its
  // neighbours: a floor-stock plunge on a fillet).
  bool standsAbove(Vec2 a, Vec2 b, double r, double z) const;

 private:
  struct Disk {
    Circle circle;
    double bottom;
  };
  template <class F>
  void forEachDiskNear(Vec2 c, double reach, F f) const;
  static bool coveredBy(Polygons rest, Vec2 from, std::vector<Circle> near, double tiny = 1e-4);
  static bool crescentWitness(Vec2 c, Vec2 end, double rs, double beyond, const std::vector<Circle>& near);
  static bool clearOf(const std::vector<Circle>& near, Vec2 q);
  static bool uncoveredWitness(Vec2 a, Vec2 b, double rs, const std::vector<Circle>& near);
  long cellOf(double v) const;
  double highestCut(Vec2 a, Vec2 b, double r, double above = kNoBound) const;  // as if the stock stood at top_z before the disks
  // highestCut answers early, with a height above `above`, once it knows it is.
  static constexpr double kNoBound = std::numeric_limits<double>::infinity();
  double bucket_, top_;
  Material material_;
  std::vector<Disk> disks_;
  std::map<long long, std::vector<size_t>> grid_;
};

}  // namespace plunge
