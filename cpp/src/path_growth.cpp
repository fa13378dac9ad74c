// The growth along the paths (Grower::growAlongPaths): each path is entered
// next to cut material, nearest first, and walked while its plunges keep the
// limit; where nothing can be entered, a start. Leaves to the rings what the
// paths cannot reach.
#include <algorithm>
#include <cmath>
#include <tuple>
#include <unordered_map>

#include "growth_paths.hpp"
#include "grower.hpp"

namespace plunge {

namespace {

// The contour along the walls is spaced for this share of max_wall_stock on
// straight walls (the raster measures to a cell; refineContour adds plunges
// where curved walls leave up to kWallBand).
constexpr double kContourScallop = 0.8;
// Entries to the paths: a row entered before the contour beside it is cut
// cuts its ends, which the contour covers (on sculptured floors, where walks
// stop at deeper neighbours, that costs plunges); so the contour's positions
// come first unless a row is this many tool radii nearer (the tour's length).
constexpr double kRowDetour = 1.0;

}  // namespace

class PathGrowth {
 public:
  PathGrowth(Grower& g, ToolRun& run, const Polygons& centres, GrowthPattern pattern);
  void grow();

 private:
  enum class Verdict { Skip, Blocked, Solid, Thin, Ok };
  struct Pos {
    Pos(Vec2 at, size_t onPath, size_t i, bool cut) : c(at), path(onPath), index(i), covered(cut) {}
    Vec2 c;
    size_t path, index;
    bool covered = false;  // a row position the contour cuts anyway (coveredByContour)
    bool open = true;
    // What a plunge here would meet, measured until a plunge lands nearby.
    bool known = false, skip = false, solid = false, coreClear = true;
    double engagement = 0.0;
    std::optional<double> z;
    bool zKnown = false;
  };
  std::vector<GrowthPath> layPaths(const Polygons& centres, GrowthPattern pattern) const;
  void index();
  std::optional<double> zOf(Pos& p);
  void measure(Pos& p);
  Verdict judge(size_t k);
  void cut(size_t k, bool start);
  std::optional<size_t> along(size_t k, int dir) const;
  bool contourOpens(Vec2 c);
  bool nextCutsWider(size_t k, int dir);
  void walkOn(size_t k);
  std::vector<size_t> inOrder(const std::vector<size_t>& open, std::optional<size_t> piece) const;
  std::optional<size_t> enter(const std::vector<size_t>& order);

  Grower& g_;
  ToolRun& run_;
  // A core is checked three quarters of a cell wider (a cell's centre may lie
  // that far from a point it stands for), so steps keep that much inside.
  double coreMargin_;
  std::vector<GrowthPath> paths_;
  std::vector<Pos> pos_;
  std::vector<size_t> first_;  // each path's first position in pos_
  // Positions by cell, to forget the verdicts a new plunge may change.
  double cell_;
  std::unordered_map<long long, std::vector<size_t>> near_;
};

PathGrowth::PathGrowth(Grower& g, ToolRun& run, const Polygons& centres, GrowthPattern pattern)
    : g_(g), run_(run), coreMargin_(0.75 * g.stock_.spacing()) {
  paths_ = layPaths(centres, pattern);
  cell_ = 2 * run.cutter.radius + run.limit + 2 * g.stock_.spacing();
  index();
}

// The contour and rows (or offsets): a step a little under the band (the
// raster measures to a cell); rows as far apart as the scallops along them
// allow, a cell of overlap; along the walls, plunges close enough that their
// scallops keep the wall stock limit (with a margin for the raster).
std::vector<GrowthPath> PathGrowth::layPaths(const Polygons& centres, GrowthPattern pattern) const {
  const double r = run_.cutter.radius, e = run_.limit, coreR = run_.coreR, h = g_.stock_.spacing();
  const double step = std::max(std::min(e - 0.25 * h, coreR > 0 ? r - coreR - coreMargin_ - 0.05 * h : e),
                               std::max(run_.tool.minEngagement.value_or(0.0), 2 * h));
  double wallStep = step;
  const double scallop = kContourScallop * g_.in_.maxWallStock;
  if (scallop > 0 && scallop < r) wallStep = std::min(step, 2 * std::sqrt(r * r - (r - scallop) * (r - scallop)));
  const double spacing = (pattern == GrowthPattern::Offsets ? loopSpacing(r, step) : rowSpacing(r, step)) - h;
  std::vector<GrowthPath> paths = growthPaths(centres, step, wallStep, spacing, pattern);
  if (scallop > 0)
    for (GrowthPath& p : paths)
      if (p.contour)
        refineContour(p, centres, g_.region_, {r, g_.in_.radialAllowance, kWallBand * g_.in_.maxWallStock});
  return paths;
}

// The paths' positions in one list, and by cell.
void PathGrowth::index() {
  const std::vector<std::vector<bool>> covered = coveredByContour(paths_, run_.cutter.radius);
  for (size_t k = 0; k < paths_.size(); ++k) {
    first_.push_back(pos_.size());
    for (size_t i = 0; i < paths_[k].at.size(); ++i) pos_.emplace_back(paths_[k].at[i], k, i, covered[k][i]);
  }
  for (size_t k = 0; k < pos_.size(); ++k) near_[detail::cellKeyOf(pos_[k].c, cell_)].push_back(k);
}

std::optional<double> PathGrowth::zOf(Pos& p) {
  if (!p.zKnown) {
    p.zKnown = true;
    if (g_.region_.diskFits(p.c, run_.cutter.radius + g_.in_.radialAllowance)) p.z = g_.stopAt(p.c, run_.tool);
  }
  return p.z;
}

// Every plunge, entered anywhere or a step on along its path, is measured
// exactly (cuts.hpp) against the plunges before it.
void PathGrowth::measure(Pos& p) {
  g_.progress_.tick();
  p.known = true;
  const Cutter& cutter = run_.cutter;
  if (run_.targets.open(p.c, cutter.radius) < run_.minGain || !zOf(p)) {
    p.skip = true;
    return;
  }
  if (run_.targets.gain(p.c, cutter, *p.z, g_.stock_) < run_.minGain) {
    run_.targets.defer(p.c, cutter, *p.z, g_.stock_);
    p.skip = true;
    return;
  }
  const HeightField::Contact m = g_.stock_.contact(p.c, cutter, *p.z, run_.coreR > 0 ? run_.coreR + coreMargin_ : 0.0);
  p.solid = m.solid;
  p.coreClear = m.coreClear;
  if (!p.solid && p.coreClear) p.engagement = g_.cuts_.engagement(p.c, cutter, *p.z, run_.limit + kExactSlack);
}

PathGrowth::Verdict PathGrowth::judge(size_t k) {
  Pos& p = pos_[k];
  if (!p.known) measure(p);
  if (p.skip) return Verdict::Skip;
  if (p.solid) return Verdict::Solid;  // a drill into solid: a start, whatever the limit
  if (!p.coreClear || p.engagement > run_.limit + kExactSlack) return Verdict::Blocked;
  return p.engagement < run_.tool.minEngagement.value_or(0.0) ? Verdict::Thin : Verdict::Ok;
}

// A plunge at position k; the verdicts near it are measured again.
void PathGrowth::cut(size_t k, bool start) {
  pos_[k].open = false;
  g_.place(run_, pos_[k].c, *pos_[k].z, start);
  detail::anyNear(near_, run_.at, cell_, [&](size_t q) {
    if (pos_[q].open && !pos_[q].skip) pos_[q].known = false;
    return false;  // every one
  });
}

// The next position along a path (dir +1 or -1), or none.
std::optional<size_t> PathGrowth::along(size_t k, int dir) const {
  const GrowthPath& path = paths_[pos_[k].path];
  const long n = static_cast<long>(path.at.size()), i = static_cast<long>(pos_[k].index) + dir;
  if (!path.closed && (i < 0 || i >= n)) return std::nullopt;
  return first_[pos_[k].path] + static_cast<size_t>((i + n) % n);
}

// Can a contour's position near c be entered now?
bool PathGrowth::contourOpens(Vec2 c) {
  return detail::anyNear(near_, c, cell_, [&](size_t q) {
    return pos_[q].open && paths_[pos_[q].path].contour && dist(pos_[q].c, c) <= 2 * run_.cutter.radius &&
           judge(q) == Verdict::Ok;
  });
}

// Past a thin position k, the next one along cuts within the limit without it.
bool PathGrowth::nextCutsWider(size_t k, int dir) {
  const std::optional<size_t> next = along(k, dir);
  return next && pos_[*next].open && judge(*next) == Verdict::Ok;
}

// From a plunge just made, on along its path while the plunges keep the
// limit; a thin plunge only where the next one needs it. A walk stops
// before a position the contour cuts anyway (until the contour is cut
// there, when it is skipped); a connector (a walk entered at such a
// position) stops as soon as a contour beside it can be entered.
void PathGrowth::walkOn(size_t k) {
  const std::optional<size_t> ahead = along(k, +1);
  const int dir = ahead && pos_[*ahead].open ? +1 : -1;
  const bool connector = pos_[k].covered;
  size_t last = k;
  for (std::optional<size_t> q = along(k, dir); q && pos_[*q].open; q = along(*q, dir)) {
    g_.progress_.tick();
    if (connector && contourOpens(pos_[last].c)) break;
    if (!connector && pos_[*q].covered && judge(*q) != Verdict::Skip) break;
    zOf(pos_[*q]);
    const Verdict v = judge(*q);
    if (v == Verdict::Blocked || v == Verdict::Solid) break;
    if (v == Verdict::Skip || (v == Verdict::Thin && nextCutsWider(*q, dir))) {
      pos_[*q].open = false;
      continue;
    }
    cut(*q, false);
    last = *q;
  }
}

// The open positions in the order they are tried: the piece of the region the
// tool is in first, then nearest first (ties by index, so deterministic), the
// contour's positions kRowDetour radii nearer than the rows'. Row positions
// the contour cuts anyway come last, after a start: a start is one plunge, a
// row between two contours a dozen.
std::vector<size_t> PathGrowth::inOrder(const std::vector<size_t>& open, std::optional<size_t> piece) const {
  std::vector<std::pair<std::tuple<bool, bool, double>, size_t>> order;
  for (size_t k : open) {
    const Vec2 d = pos_[k].c - run_.at;
    const double detour = paths_[pos_[k].path].contour ? 0.0 : kRowDetour * run_.cutter.radius;
    order.push_back({{pos_[k].covered, piece && paths_[pos_[k].path].piece != *piece, norm(d) + detour}, k});
  }
  std::sort(order.begin(), order.end());
  std::vector<size_t> out;
  for (const auto& [unused, k] : order) out.push_back(k);
  return out;
}

// The first position of `order` within the limit (else the first thin one)
// is cut, else the first start; returns where, or none.
std::optional<size_t> PathGrowth::enter(const std::vector<size_t>& order) {
  std::optional<size_t> entry, thin, start;
  for (size_t k : order) {
    if (pos_[k].covered && (thin || start)) break;
    const Verdict v = judge(k);
    if (v == Verdict::Skip) {
      pos_[k].open = false;
    } else if (v == Verdict::Ok) {
      entry = k;
      break;
    } else if (v == Verdict::Thin && !thin) {
      thin = k;
    } else if (v == Verdict::Solid && !start && g_.canStart(run_.tool, pos_[k].c)) {
      start = k;
    }
  }
  if (!entry) entry = thin;
  if (entry) {
    cut(*entry, false);
    return entry;
  }
  if (!start) return std::nullopt;
  g_.drillStart(run_.tool, pos_[*start].c);
  cut(*start, true);
  return start;
}

void PathGrowth::grow() {
  if (pos_.empty()) return;
  std::vector<size_t> open(pos_.size());
  for (size_t k = 0; k < pos_.size(); ++k) open[k] = k;
  std::optional<size_t> piece;  // where the last plunge was
  while (run_.targets.left() > 0) {
    g_.progress_.tick();
    open.erase(std::remove_if(open.begin(), open.end(), [&](size_t k) { return !pos_[k].open; }), open.end());
    if (open.empty()) break;
    const std::optional<size_t> entered = enter(inOrder(open, piece));
    if (!entered) break;
    walkOn(*entered);
    piece = paths_[pos_[*entered].path].piece;
  }
}

void Grower::growAlongPaths(ToolRun& run, const Polygons& centres, GrowthPattern pattern) {
  PathGrowth(*this, run, centres, pattern).grow();
}

}  // namespace plunge
