// The material before this operation (rest plunging): what the Job's stock and
// the operations before this one left, as MaterialGrid (types.hpp), asked the
// way the plan needs it. Every answer is an upper bound of the material (a
// cell counts wherever its square meets the asked disk), never above top_z, so
// no plunge is dropped and no rapid is lowered where material may stand.
// Without a grid the material is the full stock: top_z everywhere.
#pragma once
#include <memory>
#include <optional>

#include "plunge/geometry.hpp"
#include "plunge/types.hpp"

namespace plunge {

// A plunge is in air when no material stands more than this above its cutter's
// surface (mm): the float noise of a grid made by replaying paths.
constexpr double kAirTolerance = 0.01;

class Material {
 public:
  Material(const std::optional<MaterialGrid>& grid, double topZ);

  // Whether the operations before left less than the full stock anywhere.
  bool known() const { return grid_ != nullptr; }
  double topZ() const { return top_; }
  // The material at p (its cell's), top_z beyond the raster.
  double at(Vec2 p) const;
  // Highest material over the cells whose squares meet the disk of radius r
  // swept from a to b (at c: not swept).
  double highestAlong(Vec2 a, Vec2 b, double r) const;
  double highest(Vec2 c, double r) const { return highestAlong(c, c, r); }
  // Highest material over the cells meeting the box [lo, hi].
  double highestIn(Vec2 lo, Vec2 hi) const;
  // Whether a cutter at c with its tip at z would cut material standing more
  // than kAirTolerance above its surface (the surface's lowest over each cell).
  bool cutsAny(Vec2 c, const Cutter& cutter, double z) const;

 private:
  double cell(long i, long j) const;  // top_z beyond the raster
  // The cells' index range meeting [lo, hi] (clamped to one beyond the raster).
  void range(Vec2 lo, Vec2 hi, long& i0, long& i1, long& j0, long& j1) const;

  std::shared_ptr<const MaterialGrid> grid_;  // shared: options structs copy the material
  double top_;
};

}  // namespace plunge
