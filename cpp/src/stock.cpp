#include "stock.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "detail.hpp"
#include "plunge/error.hpp"

namespace plunge {

using namespace detail;

namespace {

constexpr size_t kTargetSamples = 200000;
// mm: how far a bound of a stop height may sit above the optimizer's value (depth.hpp) before it counts.
constexpr double kBoundSlack = 1e-6;

// x moved away from the walls closer than `clearance` (a few steps: corners).
Vec2 pushOffWalls(const Region& region, Vec2 x, double clearance) {
  for (int i = 0; i < 4; ++i) {
    Vec2 w;
    double d;
    // nearestWallPoint may return a farther wall (a long slanted wall's box holds x): only nearer ones push.
    if (!region.nearestWallPoint(x, clearance, w, d) || d < 1e-9 || d >= clearance || !region.contains(x)) break;
    x = w + (x - w) * ((clearance + 1e-6) / d);
  }
  return x;
}

}  // namespace

double stockSpacing(double area, double minRadius) {
  const double fine = std::sqrt(std::max(area, 0.0) / kTargetSamples);
  return std::min(std::max(fine, 0.2), 0.25 * minRadius);
}

StockGrid::StockGrid(const Region& region, const FloorSurface& floor, const StockSampling& sampling,
                     const Progress& progress)
    : spacing_(sampling.spacing) {
  const auto [radialAllowance, floorAllowance, maxWallStock, spacing] = sampling;
  if (!(spacing > 0.0)) throw Error("stock sampling: spacing must be > 0");
  const Vec2 lo = region.minCorner(), hi = region.maxCorner();
  // Samples in the middle of raster cells, so that a pocket's edges fall between them.
  origin_ = lo + Vec2{0.5 * spacing, 0.5 * spacing};
  nx_ = static_cast<size_t>(std::max(1.0, std::floor((hi.x - lo.x) / spacing)));
  ny_ = static_cast<size_t>(std::max(1.0, std::floor((hi.y - lo.y) / spacing)));
  floor_.assign(nx_ * ny_, kNaN);
  cut_.assign(nx_ * ny_, kInf);
  safe_.assign(nx_ * ny_, kInf);
  core_.assign(nx_ * ny_, 0);
  for (size_t j = 0; j < ny_; ++j) {
    progress.tick();
    for (size_t i = 0; i < nx_; ++i) {
      const size_t k = j * nx_ + i;
      const Vec2 p = at(k);
      if (!region.contains(p)) continue;
      const double w = region.wallDistance(p, radialAllowance + maxWallStock + spacing);
      if (w < radialAllowance) continue;
      const double z = floor.height(p);
      if (!std::isfinite(z)) continue;
      floor_[k] = z + floorAllowance;
      // The floor-stock step also targets one sample step beyond the band: the core's
      // own edge is a thin strip that a raster would otherwise sample only here and there.
      core_[k] = w >= radialAllowance + maxWallStock ? 2 : w >= radialAllowance + maxWallStock - spacing ? 1 : 0;
    }
  }
}

void StockGrid::bandFloorSteps(double rise, double reach) {
  std::vector<size_t> feet;
  for (size_t k = 0; k < size(); ++k) {
    if (!valid(k)) continue;
    const long i = static_cast<long>(k % nx_), j = static_cast<long>(k / nx_);
    bool foot = false;
    for (long dj = -1; dj <= 1 && !foot; ++dj)
      for (long di = -1; di <= 1 && !foot; ++di) {
        const long a = i + di, b = j + dj;
        if (a < 0 || b < 0 || a >= static_cast<long>(nx_) || b >= static_cast<long>(ny_)) continue;
        const size_t q = static_cast<size_t>(b) * nx_ + static_cast<size_t>(a);
        foot = valid(q) && floor_[q] - floor_[k] > rise;
      }
    if (foot) feet.push_back(k);
  }
  for (size_t k : feet) {
    const Vec2 p = at(k);
    forEachIn(p - Vec2{reach, reach}, p + Vec2{reach, reach}, [&](size_t m) {
      if (valid(m) && dist(at(m), p) <= reach && floor_[m] < floor_[k] + 0.5 * rise) core_[m] = 0;
    });
  }
}

void StockGrid::cut(const CutDisk& d, const Cutter& cutter) {
  const double r = cutter.radius, h = neighbourhood();
  forEachIn(d.center - Vec2{r, r}, d.center + Vec2{r, r}, [&](size_t k) {
    const double rho = dist(at(k), d.center);
    if (rho > r) return;
    cut_[k] = std::min(cut_[k], d.z + cutterProfile(cutter, rho));
    if (rho + h <= r) safe_[k] = std::min(safe_[k], d.z + cutterProfile(cutter, rho + h));
  });
}

double StockGrid::stock(size_t k) const {
  if (!valid(k) || !std::isfinite(cut_[k])) return kNaN;
  return cut_[k] - floor_[k];
}

double StockGrid::safeStock(size_t k) const {
  if (!valid(k) || !std::isfinite(safe_[k])) return kNaN;
  return safe_[k] - floor_[k];
}

double StockGrid::maxSlope() const {
  double m = 0.0;
  for (size_t j = 0; j < ny_; ++j)
    for (size_t i = 0; i < nx_; ++i) {
      const size_t k = j * nx_ + i;
      if (!valid(k)) continue;
      if (i + 1 < nx_ && valid(k + 1)) m = std::max(m, std::fabs(floor_[k + 1] - floor_[k]) / spacing_);
      if (j + 1 < ny_ && valid(k + nx_)) m = std::max(m, std::fabs(floor_[k + nx_] - floor_[k]) / spacing_);
    }
  return m;
}

namespace {

// The floor-stock step, step by step: the samples over the limit, highest first;
// for each still over it, unless hopeless, the candidate plunges of every tool
// around it, ranked by a bound of how many over-limit samples each fixes; the
// best by exact stop height (branch and bound: the same choice as trying them
// all); cut, and the samples it fixed struck off.
class FloorStockStep {
 public:
  FloorStockStep(const Region& region, const DepthSolver& depths, const ToolTable& tools, StockGrid& grid,
                 const FloorStockOptions& opt)
      : region_(region), depths_(depths), tools_(tools), grid_(grid), opt_(opt), h_(grid.neighbourhood()) {
    for (const Tool& t : tools.all()) cutters_.push_back(cutterOf(t));
    // Every point lies within a neighbourhood (0.75 of a sample step) of a sample,
    // and a sample only counts as cut by a plunge that cuts all of its neighbourhood
    // (StockGrid::safeStock); what stays between samples is then the floor's slope
    // times that distance.
    const double margin = std::min(0.25 * opt.maxFloorStock, grid.maxSlope() * h_);
    target_ = opt.maxFloorStock - margin;
    for (int a = 0; a < 8; ++a) compass_[a] = {std::cos(a * kPi / 4), std::sin(a * kPi / 4)};
  }

  FloorStockResult run() {
    FloorStockResult out;
    for (size_t k : overLimit()) {
      opt_.progress.tick();
      if (!isOver_[k]) continue;
      if (hopeless(k)) {
        ++out.unreachable;
        continue;
      }
      if (searches_ >= opt_.maxSearches) {
        out.outOfBudget = true;
        break;
      }
      const std::optional<CutDisk> best = bestOf(candidatesFor(k), k);
      if (!best) {
        ++out.unreachable;
        continue;
      }
      cut(*best);
      out.added.push_back(*best);
      out.added.back().forFloorStock = true;
    }
    out.searches = searches_;
    return out;
  }

 private:
  struct Candidate {
    CutDisk disk;
    int bound = 0;  // samples it may fix at most (from a lower bound of its stop height)
    size_t order = 0;
  };

  // The samples over the limit (less the margin), highest first: each added
  // plunge goes where the step is worst.
  std::vector<size_t> overLimit() {
    std::vector<size_t> over;
    for (size_t k = 0; k < grid_.size(); ++k)
      if (grid_.restTarget(k) && grid_.safeStock(k) > target_) over.push_back(k);
    std::stable_sort(over.begin(), over.end(),
                     [&](size_t a, size_t b) { return grid_.safeStock(a) > grid_.safeStock(b); });
    isOver_.assign(grid_.size(), 0);
    for (size_t k : over) isOver_[k] = 1;
    return over;
  }

  // A plunge fixes a sample when it cuts the sample's whole neighbourhood low enough.
  bool fixes(const CutDisk& d, size_t k) const {
    const Cutter& c = cutter(d);
    const double rho = dist(grid_.at(k), d.center) + h_;
    return rho <= c.radius && d.z + cutterProfile(c, rho) <= grid_.floorAt(k) + target_;
  }

  // A necessary condition, before the exact stop height (an optimization, up
  // to a millisecond): the plunge stops no lower than the floor at any sample
  // under it less the cutter's profile there, so a few samples under the disk
  // (its centre, 8 points at 0.9 r) bound its stop height from below. Over a
  // floor too steep for the limit (no plunger can meet it) this skips nearly
  // every stop height.
  bool mayFix(Vec2 c, size_t t, size_t k) const {
    const Cutter& cut = cutters_[t];
    double low = -std::numeric_limits<double>::infinity();
    for (int a = -1; a < 8; ++a) {
      const Vec2 x = a < 0 ? c : c + compass_[a] * (0.9 * cut.radius);
      size_t q;
      if (!grid_.nearest(x, q) || !grid_.valid(q)) continue;
      const double rho = dist(grid_.at(q), c);
      if (rho <= cut.radius) low = std::max(low, grid_.floorAt(q) - cutterProfile(cut, rho));
    }
    const double rho = dist(grid_.at(k), c) + h_;
    return low + cutterProfile(cut, rho) <= grid_.floorAt(k) + target_ + kBoundSlack;
  }

  // Necessary for every plunge, whatever its tool and centre: the floor in the
  // sample's neighbourhood rises at most `target` above the sample. (Over the
  // neighbourhood, inside the disk, the tip stops no lower than the floor less
  // the profile there, and `fixes` adds at least that profile back.) Checked on
  // the neighbourhood's rim: a floor far too steep for the limit is given up
  // sample by sample, without trying any plunge.
  bool hopeless(size_t k) const {
    const Vec2 p = grid_.at(k);
    for (int a = 0; a < 8; ++a) {
      const double z = depths_.floor().height(p + compass_[a] * h_);
      if (z + opt_.floorAllowance > grid_.floorAt(k) + target_ + kBoundSlack) return true;  // false for NaN
    }
    return false;
  }

  // Over-limit samples a plunge fixes.
  int score(const CutDisk& d) const {
    const Cutter& c = cutter(d);
    int s = 0;
    // fixes(d, q), with the distance the disk's walk gives.
    grid_.forEachInDisk(d.center, c.radius - h_, [&](size_t q, double rho) {
      if (isOver_[q] && d.z + cutterProfile(c, rho + h_) <= grid_.floorAt(q) + target_) ++s;
    });
    return s;
  }

  // The lowest a plunge at c can stop: the floor at every sample under it less the profile.
  double lowestStop(Vec2 c, size_t t) const {
    const Cutter& cut = cutters_[t];
    double low = -std::numeric_limits<double>::infinity();
    grid_.forEachInDisk(c, cut.radius, [&](size_t q, double rho) {
      if (grid_.valid(q)) low = std::max(low, grid_.floorAt(q) - cutterProfile(cut, rho));
    });
    return low;
  }

  // Candidates for sample k, each with a lower bound of its stop height and so
  // an upper bound of its score, best bound first: for every tool, centres over
  // the sample and around it (12 directions, 0.45 r and 0.9 r away), each
  // pushed off the walls it is too close to (beside a wall the disk may reach
  // lower floor along the wall than across it).
  std::vector<Candidate> candidatesFor(size_t k) const {
    const Vec2 p = grid_.at(k);
    std::vector<Candidate> candidates;
    for (size_t t = 0; t < cutters_.size(); ++t) {
      const double r = cutters_[t].radius, clearance = r + opt_.radialAllowance;
      std::vector<Vec2> centres{pushOffWalls(region_, p, clearance)};
      for (double f : {0.45, 0.9})
        for (int a = 0; a < 12; ++a)
          centres.push_back(
              pushOffWalls(region_, p + Vec2{std::cos(a * kPi / 6), std::sin(a * kPi / 6)} * (f * r), clearance));
      for (const Vec2& c : centres) {
        // Only a disk over the sample's whole neighbourhood can fix it (`fixes`):
        // others are not worth a stop height.
        if (dist(c, p) + h_ > r || !region_.diskFits(c, clearance)) continue;
        if (!mayFix(c, t, k)) continue;
        CutDisk low{c, tools_.all()[t].id, lowestStop(c, t) - kBoundSlack};
        if (low.z >= opt_.topZ || !fixes(low, k)) continue;
        candidates.push_back({low, score(low), candidates.size()});
      }
    }
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.bound > b.bound; });
    return candidates;
  }

  // The candidate that fixes the most at its exact stop height (a rim
  // optimization each, milliseconds on BREP floors), computed only while a
  // candidate may still beat or tie the best; none if none fixes sample k.
  std::optional<CutDisk> bestOf(const std::vector<Candidate>& candidates, size_t k) {
    CutDisk best;
    int bestScore = 0;
    size_t bestOrder = 0;
    // A candidate that fixes at most `bound` samples cannot beat the best so far.
    auto outranked = [&](int bound, size_t order) {
      return bound < bestScore || (bestScore > 0 && bound == bestScore && order > bestOrder);
    };
    for (const Candidate& cand : candidates) {
      if (cand.bound < bestScore) break;  // sorted by bound: so are all after it
      if (outranked(cand.bound, cand.order)) continue;
      CutDisk d = cand.disk;
      // The rim's bound first (DepthSolver::plungeHeightAtLeast): the same
      // pruning, tighter where the floor rises between samples.
      d.z = std::max(
          d.z, depths_.plungeHeightAtLeast(d.center, cutter(d), opt_.floorAllowance, opt_.radialAllowance) - kBoundSlack);
      if (d.z >= opt_.topZ || !fixes(d, k)) continue;
      if (outranked(score(d), cand.order)) continue;
      ++searches_;
      try {
        d.z = depths_.plungeHeight(d.center, cutter(d), opt_.floorAllowance, opt_.radialAllowance);
      } catch (const Error&) {
        continue;  // no floor under part of the disk
      }
      if (d.z >= opt_.topZ || !fixes(d, k)) continue;
      const int s = score(d);
      // Ties: the larger tool (it was listed first), then the first centre.
      if (s > bestScore || (s == bestScore && s > 0 && cand.order < bestOrder)) {
        bestScore = s;
        best = d;
        bestOrder = cand.order;
      }
    }
    if (bestScore == 0) return std::nullopt;
    return best;
  }

  // Cuts the plunge into the grid and strikes off the samples it brought under the limit.
  void cut(const CutDisk& d) {
    grid_.cut(d, cutter(d));
    const double r = cutter(d).radius;
    grid_.forEachIn(d.center - Vec2{r, r}, d.center + Vec2{r, r}, [&](size_t q) {
      if (isOver_[q] && grid_.safeStock(q) <= target_) isOver_[q] = 0;
    });
  }

  const Region& region_;
  const DepthSolver& depths_;
  const Cutter& cutter(const CutDisk& d) const { return cutters_[tools_.indexOf(d.toolId)]; }

  const ToolTable& tools_;
  std::vector<Cutter> cutters_;  // in the table's order
  StockGrid& grid_;
  const FloorStockOptions& opt_;
  const double h_;
  double target_ = 0.0;
  std::array<Vec2, 8> compass_;  // unit vectors every 45 degrees
  std::vector<char> isOver_;
  int searches_ = 0;  // exact stop heights searched (bestOf), against opt_.maxSearches
};

}  // namespace

FloorStockResult plungeFloorStock(const Region& region, const DepthSolver& depths, const ToolTable& tools,
                                  StockGrid& grid, const FloorStockOptions& opt) {
  if (tools.all().empty()) return {};
  return FloorStockStep(region, depths, tools, grid, opt).run();
}

StockReport measureStock(const StockGrid& grid, const Material& material) {
  StockReport r;
  const double cell = grid.spacing() * grid.spacing();
  size_t n = 0;
  double sum = 0.0, pocket = 0.0;
  for (size_t k = 0; k < grid.size(); ++k) {
    if (!grid.valid(k)) continue;
    const double top = material.at(grid.at(k));
    pocket += std::max(0.0, top - grid.floorAt(k)) * cell;
    const double s = grid.stock(k);
    if (std::isnan(s)) continue;
    r.volumeRemoved += std::max(0.0, top - std::max(grid.cutAt(k), grid.floorAt(k))) * cell;
    if (!grid.inCore(k)) continue;  // the wall band's material, not the floor's
    if (s > r.maxFloorStock) {
      r.maxFloorStock = s;
      r.maxFloorStockAt = grid.at(k);
    }
    sum += std::max(0.0, s);
    ++n;
  }
  r.meanFloorStock = n ? sum / n : 0.0;
  r.volumeBefore = pocket;
  r.volumeLeft = std::max(0.0, pocket - r.volumeRemoved);
  return r;
}

WallStock wallStockLeft(const Region& region, const std::vector<Loop>& uncovered, const std::vector<Loop>& accessible,
                        double radialAllowance, double sliver) {
  // The accessible region's outline, indexed: a vertex on it is on a wall (no
  // stock) or on the arc of a corner the smallest tool cannot reach.
  std::vector<Segment> edges;
  std::vector<BoxValue> boxes;
  for (const Loop& L : accessible)
    for (size_t i = 0, j = L.size() - 1; i < L.size(); j = i++) {
      edges.push_back({L[j], L[i]});
      boxes.emplace_back(boxOf(edges.back()), static_cast<int>(edges.size() - 1));
    }
  const QuadraticTree<BoxValue> index(boxes.begin(), boxes.end());
  constexpr double onOutline = 1e-3;
  auto onAccessibleOutline = [&](Vec2 p) {
    for (auto it = index.qbegin(bgi::intersects(boxAround(p, onOutline))); it != index.qend(); ++it)
      if (distanceToSegment(edges[it->second], p) <= onOutline) return true;
    return false;
  };
  const Vec2 lo = region.minCorner(), hi = region.maxCorner();
  const double far = 2.0 * dist(lo, hi);
  WallStock m;
  for (const Loop& L : uncovered) {
    if (std::fabs(signedArea(L)) < sliver) continue;
    for (const Vec2& p : L) {
      if (onAccessibleOutline(p)) continue;
      const double d = region.wallDistance(p, far) - radialAllowance;
      if (d > m.thickest) m = {d, p};
    }
  }
  return m;
}

}  // namespace plunge
