// The radial engagement of a plunge, measured exactly against the plunges made
// before it (each a circle with its tool's shape and depth), not on a raster.
//
// A plunge's radial engagement is the most uncut material along any one radius
// of the tool, from its axis to its rim: the length of cutting edge in
// material at once. For a crescent at the rim it is the crescent's thickness;
// for a ridge left across the disk it can reach the radius, however thin the
// ridge; into solid it is the radius. The growth within an engagement limit
// (engagement.hpp) and the plan's own figures (motion.hpp) use this measure,
// so what they promise is what an exact replay of the posted order finds
// (tests/python/engagement_check.py).
#pragma once
#include <unordered_map>
#include <vector>

#include "material.hpp"
#include "plunge/geometry.hpp"
#include "plunge/types.hpp"

namespace plunge {

class Cuts {
 public:
  // `skin`: material thinner than this above a plunge's cutting surface does
  // not count (heightfield.hpp's kEngagementSkin).
  explicit Cuts(double skin);
  // Rest plunging: what the operations before left (material.hpp). Material
  // they cut down to a plunge's surface does not count in its engagement;
  // without, the stock is solid.
  Cuts(double skin, const Material& material);

  // A plunge made: the cutter with its tip at z, at c.
  void add(Vec2 c, const Cutter& cutter, double z);

  // The radial engagement of a plunge of `cutter` at c with its tip at z.
  // Radii every 0.25 degrees, and through every corner of the uncut material
  // (where two cuts' circles cross inside the disk, or one crosses its rim),
  // the best refined; each radius cut exactly by the circles of the cuts that
  // reach as deep. Stops early, returning a value above `enough`, as soon as
  // one radius has more than `enough` (a test against a limit needs no more).
  double engagement(Vec2 c, const Cutter& cutter, double z, double enough = 1e300) const;

 private:
  struct Cut {
    Vec2 c;
    Cutter cutter;
    double z;
  };
  // The cuts whose disks overlap a disk of radius r at c.
  std::vector<const Cut*> near(Vec2 c, double r) const;
  long long key(long i, long j) const;

  double skin_;
  Material material_{std::nullopt, 0.0};
  double cell_ = 0.0;  // the bucket size: the largest cut's diameter so far
  std::vector<Cut> cuts_;
  std::unordered_map<long long, std::vector<size_t>> grid_;
};

}  // namespace plunge
