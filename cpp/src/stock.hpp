// The stock a plan leaves for the finisher, and plunges for the floor stock.
//
// Roughing is judged by what it leaves (docs/plan-format.md, "Stock left"):
// - along the walls, the band of material no plunge reaches (measured on the
//   uncovered polygons: their farthest point from the walls, minus the radial
//   allowance);
// - over the floor, the height of the stock above floor + floor allowance
//   where plunges cut: a plunge stops at the highest floor point under its disk
//   (depth.hpp, thesis 4.4), so over a sculptured floor it leaves steps.
// Both are measured on a raster of the pocket (StockGrid). The floor-stock step adds
// plunges where the floor stock exceeds a limit: smaller plungers, or the same
// one centred lower, each with its own gouge-free stop height (what CAM calls
// rest machining in Z; here "rest" means rest plunging only, material.hpp),
// chosen greedily by how many over-limit samples each clears.
#pragma once
#include <limits>
#include <vector>

#include "depth.hpp"
#include "floor.hpp"
#include "material.hpp"
#include "plunge/progress.hpp"
#include "region.hpp"
#include "plunge/tools.hpp"

namespace plunge {

// One plunge as the stock sees it: where, which cutter, and its tip height.
struct CutDisk {
  Vec2 center;
  int toolId = 0;
  double z = 0.0;
  bool forFloorStock = false;  // added by the floor-stock step (plungeFloorStock)
};

// Samples of the pocket every `spacing` mm (row-major from `origin`): the
// floor height (+ floor allowance) and the lowest cut so far. Samples outside
// the region shrunk by the radial allowance, or without floor, have a NaN floor.
// Samples farther than allowance + maxWallStock from the walls are the core: the
// floor stock is measured and limited there (nearer, the wall band's material
// is the finisher's, and a plunge covers it only with its rim).
struct StockSampling {
  double radialAllowance = 0.0;
  double floorAllowance = 0.0;
  double maxWallStock = 0.0;  // max_wall_stock: the band along the walls that is not the core
  double spacing = 1.0;   // mm between samples (stockSpacing)
};

class StockGrid {
 public:
  StockGrid(const Region& region, const FloorSurface& floor, const StockSampling& sampling,
            const Progress& progress = Progress());
  // Steps in the floor (where selected faces at two levels meet, 4.4) are walls
  // of the lower level: its samples within `reach` (the radial allowance and
  // the wall band) of a sample next to one higher by more than `rise` join the
  // wall band, as along the pocket's walls.
  void bandFloorSteps(double rise, double reach);
  bool inCore(size_t k) const { return core_[k] == 2; }
  bool restTarget(size_t k) const { return core_[k] != 0; }  // the core and one sample step around it
  // Lowers the cut height under a plunge's disk.
  void cut(const CutDisk& d, const Cutter& cutter);
  // Stock above floor + allowance at sample k: NaN where nothing cut it.
  double stock(size_t k) const;
  // The same, counting only plunges that cut the whole neighbourhood of the
  // sample (a disk of neighbourhood() around it; every point of the plane is
  // that close to a sample), at their highest over it: an upper bound of the
  // stock anywhere in the neighbourhood, but for the floor's own variation.
  double safeStock(size_t k) const;
  double neighbourhood() const { return 0.75 * spacing_; }
  bool valid(size_t k) const { return !std::isnan(floor_[k]); }
  Vec2 at(size_t k) const { return {origin_.x + (k % nx_) * spacing_, origin_.y + (k / nx_) * spacing_}; }
  double floorAt(size_t k) const { return floor_[k]; }
  double cutAt(size_t k) const { return cut_[k]; }
  // Sample indices whose position lies in the box [lo, hi].
  template <class F>
  void forEachIn(Vec2 lo, Vec2 hi, F&& f) const {
    const long i0 = std::max(0L, static_cast<long>(std::ceil((lo.x - origin_.x) / spacing_)));
    const long j0 = std::max(0L, static_cast<long>(std::ceil((lo.y - origin_.y) / spacing_)));
    const long i1 = std::min(static_cast<long>(nx_) - 1, static_cast<long>(std::floor((hi.x - origin_.x) / spacing_)));
    const long j1 = std::min(static_cast<long>(ny_) - 1, static_cast<long>(std::floor((hi.y - origin_.y) / spacing_)));
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) f(static_cast<size_t>(j) * nx_ + static_cast<size_t>(i));
  }
  // Sample indices within r of c, with their distance from c (row spans: no
  // test per sample outside the disk).
  template <class F>
  void forEachInDisk(Vec2 c, double r, F&& f) const {
    const long j0 = std::max(0L, static_cast<long>(std::ceil((c.y - r - origin_.y) / spacing_)));
    const long j1 = std::min(static_cast<long>(ny_) - 1, static_cast<long>(std::floor((c.y + r - origin_.y) / spacing_)));
    for (long j = j0; j <= j1; ++j) {
      const double dy = origin_.y + j * spacing_ - c.y, half = std::sqrt(std::max(0.0, r * r - dy * dy));
      const long i0 = std::max(0L, static_cast<long>(std::ceil((c.x - half - origin_.x) / spacing_)));
      const long i1 = std::min(static_cast<long>(nx_) - 1, static_cast<long>(std::floor((c.x + half - origin_.x) / spacing_)));
      for (long i = i0; i <= i1; ++i) {
        const double dx = origin_.x + i * spacing_ - c.x, rho = std::sqrt(dx * dx + dy * dy);
        if (rho <= r) f(static_cast<size_t>(j) * nx_ + static_cast<size_t>(i), rho);
      }
    }
  }
  // The sample nearest to p, if p lies on the raster (false outside it).
  bool nearest(Vec2 p, size_t& k) const {
    const long i = std::lround((p.x - origin_.x) / spacing_), j = std::lround((p.y - origin_.y) / spacing_);
    if (i < 0 || j < 0 || i >= static_cast<long>(nx_) || j >= static_cast<long>(ny_)) return false;
    k = static_cast<size_t>(j) * nx_ + static_cast<size_t>(i);
    return true;
  }
  size_t size() const { return floor_.size(); }
  size_t nx() const { return nx_; }
  size_t ny() const { return ny_; }
  double spacing() const { return spacing_; }
  Vec2 origin() const { return origin_; }
  // Steepest floor slope between neighbouring samples (for the sampling margin).
  double maxSlope() const;

 private:
  Vec2 origin_;
  double spacing_;
  size_t nx_ = 0, ny_ = 0;
  std::vector<double> floor_, cut_, safe_;
  std::vector<char> core_;  // 2: in the core, 1: one step around it (floor-stock targets), 0: the wall band
};

// Sample spacing for a pocket: fine enough to resolve the floor's steps
// (about 200,000 samples), never coarser than a quarter of the smallest tool.
double stockSpacing(double area, double minRadius);

// See FloorStockOptions::maxSearches: about 15 s on a fast expression floor,
// 30 s on a BREP floor, so the plan keeps its minute.
constexpr int kFloorStockSearches = 10000;

struct FloorStockOptions {
  double maxFloorStock = 1.0;  // mm above floor + floor allowance
  double radialAllowance = 0.0;
  double floorAllowance = 0.0;
  double topZ = 0.0;
  // The exact stop heights the step may search (a rim optimization each, up to
  // milliseconds on BREP floors). A floor that rises and falls faster than any
  // plunger follows keeps nearly every sample over the limit, and would be
  // searched for minutes; the sculptured example needs about 300.
  int maxSearches = kFloorStockSearches;
  Progress progress;
};

struct FloorStockResult {
  std::vector<CutDisk> added;  // appended to the plan's disks, in the order chosen
  int unreachable = 0;         // over-limit samples no plunge of the job can bring under the limit
  int searches = 0;            // exact stop heights searched
  bool outOfBudget = false;    // stopped at maxSearches with samples still over the limit
};

// Adds plunges until no cut sample's floor stock exceeds the limit (less a
// margin for what lies between samples), or no plunge of any tool helps.
// `grid` must already hold the plan's cuts; it is updated with the added ones.
FloorStockResult plungeFloorStock(const Region& region, const DepthSolver& depths, const ToolTable& tools,
                                  StockGrid& grid, const FloorStockOptions& options);

struct StockReport {
  double maxFloorStock = 0.0;   // over cut samples of the core
  Vec2 maxFloorStockAt;         // where it is
  double meanFloorStock = 0.0;  // over cut samples of the core
  double volumeBefore = 0.0;    // mm^3, the pocket: the material before this operation, down to floor + allowance
  double volumeRemoved = 0.0;   // mm^3, that material down to the cuts
  double volumeLeft = 0.0;      // mm^3, the pocket minus what is removed
};
// The pocket's volume is the material before this operation (material.hpp)
// down to floor + allowance; what is removed, that material down to the cuts.
StockReport measureStock(const StockGrid& grid, const Material& material);

// The thickest material the uncovered polygons leave along the walls: their
// farthest vertex from the walls, minus the radial allowance (0 if none).
// Vertices on the accessible region's outline do not count: they lie on a wall
// or on the arc of a corner the smallest tool cannot reach (stock any tool of
// that size leaves). Pieces under `sliver` mm^2 are the polygon approximation's.
struct WallStock {
  double thickest = 0.0;
  Vec2 at;  // the uncovered vertex farthest from the walls
};
WallStock wallStockLeft(const Region& region, const std::vector<Loop>& uncovered, const std::vector<Loop>& accessible,
                        double radialAllowance, double sliver = 0.01);

}  // namespace plunge
