// The material before this operation (rest plunging): what the Job's stock and
// the operations before this one left, as MaterialGrid (types.hpp), asked the
// way the plan needs it. The grid holds the material at each cell's centre (as
// the plan's own height fields do, heightfield.hpp); a disk is asked about the
// centres inside it. So a plunge whose rim follows the edge an earlier tool
// cut (the same allowance) sees no material there, and a rest narrower than
// the grid's spacing may go unseen (the resolution). Without a grid the
// material is the full stock: top_z everywhere.
#pragma once
#include <functional>
#include <memory>
#include <optional>

#include "plunge/geometry.hpp"
#include "plunge/types.hpp"

namespace plunge {

// A plunge is in air when no material stands more than this above its cutter's
// surface (mm): the float noise of a grid made by replaying paths.
constexpr double kAirTolerance = 0.01;
// A centre this close to a disk's rim is outside it (mm): an earlier tool's
// edge and a plunge's rim at the same offset differ by the paths' accuracy.
constexpr double kRimTolerance = 0.01;

class Material {
 public:
  Material(const std::optional<MaterialGrid>& grid, double topZ);

  // Whether the operations before left less than the full stock anywhere.
  bool known() const { return grid_ != nullptr; }
  double topZ() const { return top_; }
  double spacing() const { return grid_ ? grid_->spacing : 0.0; }
  // The material at p (its cell's), top_z beyond the raster.
  double at(Vec2 p) const;
  // Highest material at the centres inside the disk of radius r swept from a
  // to b (at c: not swept); top_z where the disk leaves the raster.
  double highestAlong(Vec2 a, Vec2 b, double r) const;
  double highest(Vec2 c, double r) const { return highestAlong(c, c, r); }
  // Whether a cutter at c with its tip at z would cut material standing more
  // than kAirTolerance above its surface, at a centre up to half a cell beyond
  // its rim (a plunge is rather made than left out) where `counts` (the
  // material the plan must cut: not the wall band it may leave).
  bool cutsAny(Vec2 c, const Cutter& cutter, double z,
               const std::function<bool(Vec2)>& counts = [](Vec2) { return true; }) const;

 private:
  double cell(long i, long j) const;  // top_z beyond the raster
  Vec2 centre(long i, long j) const;
  // The cells' index range meeting [lo, hi] (clamped to one beyond the raster).
  void range(Vec2 lo, Vec2 hi, long& i0, long& i1, long& j0, long& j1) const;

  std::shared_ptr<const MaterialGrid> grid_;  // shared: options structs copy the material
  double top_;
};

}  // namespace plunge
