// The stock as the plunges leave it: a height field (top of the material per
// raster cell) over the pocket's bounds, cut by each plunge's tool shape in
// execution order. The real-plunge-mill planning (engagement.hpp, motion.hpp)
// asks it what material a plunge meets: its radial engagement, whether a
// non-centre-cutting core lies over removed material, how high the stock
// stands under a rapid.
#pragma once
#include <cmath>
#include <vector>

#include "depth.hpp"
#include "material.hpp"
#include "plunge/geometry.hpp"

namespace plunge {

// Material thinner than this above a plunge's cutting surface does not count
// in its radial engagement: the skins left on sculptured floors (rest stock,
// previous levels' cusps) do not load the flutes radially.
constexpr double kEngagementSkin = 0.5;  // mm

class HeightField {
 public:
  // Cells of `spacing` covering [lo, hi]; the stock starts at topZ everywhere.
  // Outside [lo, hi] (beyond the walls) the stock is topZ.
  HeightField(Vec2 lo, Vec2 hi, double spacing, double topZ);

  // Lowers every cell to the material the operations before left at its
  // centre (material.hpp), as the plunges' cuts are sampled.
  void lowerTo(const Material& material);
  // Removes what a plunge of `cutter` with its tip at z cuts.
  void cut(Vec2 c, const Cutter& cutter, double z);
  // Stock height at the cell containing p.
  double heightAt(Vec2 p) const;
  // Highest stock under a disk of radius r at c, and under it swept from a to b.
  double highest(Vec2 c, double r) const;
  double highestAlong(Vec2 a, Vec2 b, double r) const;

  struct Contact {
    double deepest = 0.0;     // thickest material above the cutting surface (mm)
    int materialCells = 0;    // cells with material thicker than the skin
    bool solid = false;       // material everywhere under the disk: a plunge into solid
    bool coreClear = true;    // every cell within the core radius is cut to z + skin
  };
  // What a plunge at c to tip height z would meet: material is stock more than
  // kEngagementSkin above the cutter's surface. Its radial engagement is
  // measured exactly, not on the raster (cuts.hpp).
  Contact contact(Vec2 c, const Cutter& cutter, double z, double coreRadius = 0.0) const;
  // Whether a cutter at c with its tip at z meets a cell of material (beyond
  // the skin), counting cells whose centre lies up to `margin` beyond its radius.
  bool meetsMaterial(Vec2 c, const Cutter& cutter, double z, double margin = 0.0) const;
  // How deep a cutter moved sideways at tip height z from `from` to `c` bites
  // into the stock: the largest distance beyond its radius from `from` of a
  // material cell under it at c (cells up to `margin` beyond its radius
  // counted); negative when it meets no material.
  double bite(Vec2 from, Vec2 c, const Cutter& cutter, double z, double margin = 0.0) const;

  // Centre of the cell containing p (the point whose stock the cell holds).
  Vec2 cellCentre(Vec2 p) const {
    return centre(static_cast<long>(std::floor((p.x - lo_.x) / h_)), static_cast<long>(std::floor((p.y - lo_.y) / h_)));
  }
  double spacing() const { return h_; }
  double topZ() const { return top_; }

 private:
  // Calls f(cell centre) for each cell of material (beyond the skin) under a
  // cutter at c with its tip at z, counting cells up to `margin` beyond its
  // radius, until f returns false. A cell no higher than z plus the skin holds
  // none (the cutter's profile is never below its tip): tested first, cheaply.
  template <class F>
  void forEachMaterialCell(Vec2 c, const Cutter& cutter, double z, double margin, F f) const {
    const double r = cutter.radius + margin;
    const long i0 = static_cast<long>(std::floor((c.x - r - lo_.x) / h_));
    const long j0 = static_cast<long>(std::floor((c.y - r - lo_.y) / h_));
    const long m = static_cast<long>(std::ceil(2 * r / h_)) + 1;
    for (long j = j0; j <= j0 + m; ++j)
      for (long i = i0; i <= i0 + m; ++i) {
        const double a = at(i, j);
        if (a <= z + kEngagementSkin) continue;
        if (const double rho = dist(centre(i, j), c); rho <= r && a > z + cutterProfile(cutter, rho) + kEngagementSkin)
          if (!f(centre(i, j))) return;
      }
  }
  bool index(Vec2 p, long& i, long& j) const;
  double at(long i, long j) const;
  Vec2 centre(long i, long j) const { return {lo_.x + (i + 0.5) * h_, lo_.y + (j + 0.5) * h_}; }
  Vec2 lo_;
  double h_, top_;
  long nx_, ny_;
  std::vector<float> z_;
};

// A raster spacing fine enough for the smallest tool and engagement limit,
// with at most about four million cells.
double heightFieldSpacing(Vec2 lo, Vec2 hi, double smallestRadius, double smallestLimit);

}  // namespace plunge
