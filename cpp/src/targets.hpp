// The material a limited tool must clear while it grows its cut
// (engagement.hpp): what its share of the packing/covering plan would cut.
#pragma once
#include <cmath>
#include <limits>
#include <unordered_map>
#include <vector>

#include "detail.hpp"
#include "heightfield.hpp"
#include "plunge/progress.hpp"
#include "plunge/types.hpp"

namespace plunge {

// Points sampled on the height field's raster inside a tool's planned disks,
// each with the height the planned plunges cut it to.
class Targets {
 public:
  // The points are the stock's cell centres: a plunge covers a point exactly
  // when it cuts the point's cell.
  Targets(const std::vector<Plunge>& planned, const Cutter& cutter, const HeightField& stock, const Progress& progress);

  // Target points a plunge at c (tip at z) would still cut, beyond the skin.
  template <class F>
  void forEachOpen(Vec2 c, double r, F f, bool withDeferred = true) const {
    const long bi = static_cast<long>(std::floor(c.x / bucket_)), bj = static_cast<long>(std::floor(c.y / bucket_));
    for (long j = bj - 1; j <= bj + 1; ++j)
      for (long i = bi - 1; i <= bi + 1; ++i) {
        auto it = grid_.find(detail::cellKey(i, j));
        if (it == grid_.end()) continue;
        for (size_t k : it->second) {
          if (points_[k].done || (!withDeferred && points_[k].deferred)) continue;
          const Vec2 d = points_[k].p - c;
          if (d.x * d.x + d.y * d.y <= r * r) f(k);
        }
      }
  }
  int gain(Vec2 c, const Cutter& cutter, double z, const HeightField& stock) const;
  // Target points still to cut under a disk (whatever the plunge's depth),
  // not counting those the rings gave up on.
  int open(Vec2 c, double r) const;
  // Over a sculptured floor a ring plunge may stop above a point its target
  // plunge reached: the rings leave such points to the starts at the planned
  // positions (startAt), instead of trying them again on every ring.
  void defer(Vec2 c, const Cutter& cutter, double z, const HeightField& stock);
  // Marks the points cut to their target height (within the skin), or to
  // within the floor stock they may keep, as done.
  void update(Vec2 c, double r, const HeightField& stock);
  // Over a sculptured floor a point cut to `enough(p)` needs no more: what is
  // left there is the floor's stock, the finisher's.
  template <class F>
  void keepAbove(F enough) {
    for (Point& q : points_) q.enough = enough(q.p);
  }
  // Gives up the points `skip` says need no cutting.
  template <class F>
  void forget(F skip) {
    for (Point& q : points_)
      if (!q.done && skip(q.p)) {
        q.done = true;
        --left_;
      }
  }
  size_t left() const { return left_; }
  size_t size() const { return points_.size(); }

 private:
  struct Point {
    Vec2 p;
    double z;
    bool done;
    bool deferred = false;
    double enough = -std::numeric_limits<double>::infinity();
  };
  // Adds the cells a planned plunge cuts (`cell`: each cell's point by its key).
  void addDisk(const Plunge& p, const Cutter& cutter, const HeightField& stock,
               std::unordered_map<long long, size_t>& cell);
  double bucket_;
  std::vector<Point> points_;
  std::unordered_map<long long, std::vector<size_t>> grid_;
  size_t left_ = 0;
};

}  // namespace plunge
