// Internal to the growth within engagement limits (engagement.hpp): the
// Grower, which rebuilds a plan's plunges so that every tool keeps its limit.
#pragma once
#include <optional>
#include <vector>

#include "cuts.hpp"
#include "depth.hpp"
#include "heightfield.hpp"
#include "options.hpp"
#include "region.hpp"
#include "targets.hpp"

namespace plunge {

// The wall band a limited tool leaves to its contour, as a share of
// max_wall_stock: the contour is spaced for 0.8 of it on straight walls and
// refined where curved walls leave more than this.
constexpr double kWallBand = 0.9;
// A plunge is within its limit when its exact engagement (cuts.hpp) is at
// most this over it: the measure's own rounding (its circles are exact, its
// radii 0.25 degrees apart, refined).
constexpr double kExactSlack = 0.002;

// One limited tool's growth: what its steps share.
struct ToolRun {
  const Tool& tool;
  Cutter cutter;
  double limit = 0.0;  // its engagement limit, at most the diameter
  double coreR = 0.0;  // its core's radius (0: centre-cutting)
  const std::vector<Plunge>& planned;  // its share of the plan: the targets' source
  Targets& targets;
  int minGain = 0;  // raster cells a plunge must cut to be worth making
  Vec2 at;          // where the tool is: its last plunge
};

class Grower {
 public:
  Grower(const EngagementOptions& in, const Region& region, const DepthSolver& depths, HeightField& stock)
      : in_(in), region_(region), depths_(depths), stock_(stock), cuts_(kEngagementSkin, in.material),
        progress_(in.progress) {}

  // The plunges of `ordered` (tools largest first), limited tools' regrown.
  std::vector<Plunge> run(const std::vector<Plunge>& ordered);

 private:
  friend class PathGrowth;  // the growth along the paths (path_growth.cpp)

  const Tool& toolOf(int id) const { return in_.tools.byId(id); }
  void add(const Plunge& p);
  void settle();
  std::optional<double> stopAt(Vec2 c, const Tool& t) const;
  void grow(const Tool& tool, const std::vector<Plunge>& planned);
  void grow(const Tool& tool, const std::vector<Plunge>& planned, GrowthPattern pattern);
  void adopt(Grower& other, HeightField& otherStock);
  void forgetWallBand(Targets& targets);
  void growAlongPaths(ToolRun& run, const Polygons& centres, GrowthPattern pattern);
  void growInRings(ToolRun& run, const Polygons& centres);
  struct RingPlunge {
    double z;
    bool thin;  // under the tool's min engagement
  };
  std::optional<RingPlunge> ringPlunge(ToolRun& run, Vec2 c);
  int ringRound(ToolRun& run, const std::vector<Vec2>& positions);
  void shortenTour(size_t begin);
  void keepFloorStock(Targets& targets) const;
  bool sculptured() const;
  bool canStart(const Tool& tool, Vec2 c) const;
  void drillStart(const Tool& tool, Vec2 c);
  void drillHole(const Tool& drill, Vec2 c, double z);
  std::vector<size_t> sliverPlunges(const ToolRun& run);
  void finishSlivers(ToolRun& run);
  template <class Keeps>
  int placeNearestFirst(ToolRun& run, std::vector<size_t> left, Keeps keeps);
  void place(ToolRun& run, Vec2 c, double z, bool start);
  int finishPlanned(ToolRun& run);
  std::optional<size_t> richestStart(const ToolRun& run, const std::vector<bool>& tried) const;
  bool startAt(ToolRun& run, std::vector<bool>& tried);

  const EngagementOptions& in_;
  const Region& region_;
  const DepthSolver& depths_;
  HeightField& stock_;
  Cuts cuts_;  // the same plunges as circles (and the material before): the exact engagement
  const Progress& progress_;
  Polygons cleared_;
  std::vector<Circle> newDisks_;
  std::vector<Plunge> order_, holes_;
};

}  // namespace plunge
