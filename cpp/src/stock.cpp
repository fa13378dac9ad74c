#include "plunge/stock.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <cmath>

#include "plunge/error.hpp"

namespace plunge {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr size_t kTargetSamples = 200000;

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
using BPoint = bg::model::point<double, 2, bg::cs::cartesian>;
using BBox = bg::model::box<BPoint>;
using BoxValue = std::pair<BBox, int>;

}  // namespace

double stockSpacing(double area, double minRadius) {
  const double fine = std::sqrt(std::max(area, 0.0) / kTargetSamples);
  return std::min(std::max(fine, 0.2), 0.25 * minRadius);
}

StockGrid::StockGrid(const Region& region, const FloorSurface& floor, double radialAllowance, double floorAllowance,
                     double spacing, const Progress& progress)
    : spacing_(spacing) {
  if (!(spacing > 0.0)) throw Error("stock sampling: spacing must be > 0");
  const Vec2 lo = region.minCorner(), hi = region.maxCorner();
  // Samples in the middle of raster cells, so that a pocket's edges fall between them.
  origin_ = lo + Vec2{0.5 * spacing, 0.5 * spacing};
  nx_ = static_cast<size_t>(std::max(1.0, std::floor((hi.x - lo.x) / spacing)));
  ny_ = static_cast<size_t>(std::max(1.0, std::floor((hi.y - lo.y) / spacing)));
  floor_.assign(nx_ * ny_, kNaN);
  cut_.assign(nx_ * ny_, kInf);
  for (size_t j = 0; j < ny_; ++j) {
    progress.tick();
    for (size_t i = 0; i < nx_; ++i) {
      const size_t k = j * nx_ + i;
      const Vec2 p = at(k);
      if (!region.contains(p) || region.wallDistance(p, radialAllowance) < radialAllowance) continue;
      const double z = floor.height(p);
      if (std::isfinite(z)) floor_[k] = z + floorAllowance;
    }
  }
}

void StockGrid::cut(const CutDisk& d, const Cutter& cutter) {
  const double r = cutter.radius;
  forEachIn(d.center - Vec2{r, r}, d.center + Vec2{r, r}, [&](size_t k) {
    const double rho = dist(at(k), d.center);
    if (rho <= r) cut_[k] = std::min(cut_[k], d.z + cutterProfile(cutter, rho));
  });
}

double StockGrid::stock(size_t k) const {
  if (!valid(k) || !std::isfinite(cut_[k])) return kNaN;
  return cut_[k] - floor_[k];
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

RestResult restInZ(const Region& region, const DepthSolver& depths, const std::vector<Cutter>& cutters,
                   StockGrid& grid, const RestOptions& opt) {
  RestResult out;
  if (cutters.empty()) return out;
  // Between samples the stock can be higher than at them: by at most the floor's
  // slope times half a sample step (plus the step of a neighbouring disk's rim).
  const double margin = std::min(0.25 * opt.maxFloorStock, grid.maxSlope() * grid.spacing());
  const double target = opt.maxFloorStock - margin;
  std::vector<size_t> over;
  for (size_t k = 0; k < grid.size(); ++k)
    if (grid.stock(k) > target) over.push_back(k);
  // Highest first, so each added plunge goes where the step is worst.
  std::stable_sort(over.begin(), over.end(), [&](size_t a, size_t b) { return grid.stock(a) > grid.stock(b); });
  std::vector<char> isOver(grid.size(), 0), given(grid.size(), 0);
  for (size_t k : over) isOver[k] = 1;

  auto fixes = [&](const CutDisk& d, size_t k) {
    const Cutter& c = cutters[d.tool];
    const double rho = dist(grid.at(k), d.center);
    return rho <= c.radius && d.z + cutterProfile(c, rho) <= grid.floorAt(k) + target;
  };
  for (size_t k : over) {
    opt.progress.tick();
    if (!isOver[k] || given[k]) continue;
    const Vec2 p = grid.at(k);
    CutDisk best;
    int bestScore = 0;
    for (size_t t = 0; t < cutters.size(); ++t) {
      const double r = cutters[t].radius, clearance = r + opt.radialAllowance;
      // Centres over the sample and around it, and the one pushed off the nearest wall.
      std::vector<Vec2> centres{p};
      for (double f : {0.4, 0.8})
        for (int a = 0; a < 6; ++a) centres.push_back(p + Vec2{std::cos(a * M_PI / 3), std::sin(a * M_PI / 3)} * (f * r));
      Vec2 w;
      double dw;
      if (region.nearestWallPoint(p, clearance, w, dw) && dw > 1e-9)
        centres.push_back(w + (p - w) * ((clearance + 1e-6) / dw));
      for (const Vec2& c : centres) {
        if (dist(c, p) > r || !region.diskFits(c, clearance)) continue;
        CutDisk d{c, static_cast<int>(t), 0.0};
        try {
          d.z = depths.stopHeight(c, cutters[t]) + opt.floorAllowance;
        } catch (const Error&) {
          continue;  // no floor under part of the disk
        }
        if (d.z >= opt.topZ || !fixes(d, k)) continue;
        int score = 0;
        grid.forEachIn(c - Vec2{r, r}, c + Vec2{r, r}, [&](size_t q) {
          if (isOver[q] && fixes(d, q)) ++score;
        });
        // Ties: the larger tool (it was listed first), then the first centre.
        if (score > bestScore) {
          bestScore = score;
          best = d;
        }
      }
    }
    if (bestScore == 0) {
      given[k] = 1;
      ++out.unreachable;
      continue;
    }
    grid.cut(best, cutters[best.tool]);
    const double r = cutters[best.tool].radius;
    grid.forEachIn(best.center - Vec2{r, r}, best.center + Vec2{r, r}, [&](size_t q) {
      if (isOver[q] && grid.stock(q) <= target) isOver[q] = 0;
    });
    out.added.push_back(best);
  }
  return out;
}

StockReport measureStock(const StockGrid& grid, double topZ) {
  StockReport r;
  const double cell = grid.spacing() * grid.spacing();
  size_t n = 0;
  double sum = 0.0, pocket = 0.0;
  for (size_t k = 0; k < grid.size(); ++k) {
    if (!grid.valid(k)) continue;
    pocket += std::max(0.0, topZ - grid.floorAt(k)) * cell;
    const double s = grid.stock(k);
    if (std::isnan(s)) continue;
    r.volumeRemoved += std::max(0.0, topZ - std::max(grid.cutAt(k), grid.floorAt(k))) * cell;
    r.maxFloorStock = std::max(r.maxFloorStock, s);
    sum += std::max(0.0, s);
    ++n;
  }
  r.meanFloorStock = n ? sum / n : 0.0;
  r.volumeLeft = std::max(0.0, pocket - r.volumeRemoved);
  return r;
}

double wallStockLeft(const Region& region, const std::vector<Loop>& uncovered, const std::vector<Loop>& accessible,
                     double radialAllowance, double sliver) {
  // The accessible region's outline, indexed: a vertex on it is on a wall (no
  // stock) or on the arc of a corner the smallest tool cannot reach.
  std::vector<Segment> edges;
  std::vector<BoxValue> boxes;
  for (const Loop& L : accessible)
    for (size_t i = 0, j = L.size() - 1; i < L.size(); j = i++) {
      edges.push_back({L[j], L[i]});
      boxes.emplace_back(BBox(BPoint(std::min(L[j].x, L[i].x), std::min(L[j].y, L[i].y)),
                              BPoint(std::max(L[j].x, L[i].x), std::max(L[j].y, L[i].y))),
                         static_cast<int>(edges.size() - 1));
    }
  const bgi::rtree<BoxValue, bgi::quadratic<16>> index(boxes.begin(), boxes.end());
  constexpr double onOutline = 1e-3;
  auto onAccessibleOutline = [&](Vec2 p) {
    const BBox b(BPoint(p.x - onOutline, p.y - onOutline), BPoint(p.x + onOutline, p.y + onOutline));
    for (auto it = index.qbegin(bgi::intersects(b)); it != index.qend(); ++it)
      if (distanceToSegment(edges[it->second], p) <= onOutline) return true;
    return false;
  };
  const Vec2 lo = region.minCorner(), hi = region.maxCorner();
  const double far = 2.0 * dist(lo, hi);
  double m = 0.0;
  for (const Loop& L : uncovered) {
    if (std::fabs(signedArea(L)) < sliver) continue;
    for (const Vec2& p : L)
      if (!onAccessibleOutline(p)) m = std::max(m, region.wallDistance(p, far) - radialAllowance);
  }
  return m;
}

}  // namespace plunge
