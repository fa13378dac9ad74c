#include "lead_out.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "path_walk.hpp"

namespace plunge {

namespace {

// The search for one plunge's lead-out. Only directions that keep the
// allowance to the walls and do not cut the floor; of those, first one ending
// in cut space (no material under the moved disk, the most room from the
// walls first), then one toward a hole cut before (whose graze is bounded by
// geometry, below), then any that grazes material at its flanks by at most
// half the lead-out beyond the plunge's own hole, measured with the holes'
// polygons, then one raised out of the steps around. Cheap tests first, so
// the exact ones run on few directions.
class LeadOutSearch {
 public:
  LeadOutSearch(const LeadOutContext& context, const Plunge& p, const Cutter& cutter);
  LeadOut find(const std::optional<Plunge>& back);

 private:
  // Lead-out directions tried around each plunge, and holes cut before that it may lead toward.
  static constexpr int kLeadOutDirections = 16;
  static constexpr size_t kHolesTried = 8;
  // A raster cell's centre to its corner, in cells (sqrt(2) / 2, rounded up): how
  // far a material cell's centre may lie from the material it stands for.
  static constexpr double kCellHalfDiagonal = 0.71;
  // A raised lead-out: its height is searched on the first few directions that
  // clear at the highest it may be, to this precision (mm); the lowest wins.
  static constexpr int kRaisedTried = 4;
  static constexpr double kRaisedPrecision = 0.002;
  struct End {
    Vec2 at;
    double room;  // from the walls
    bool towardHole;
  };
  std::vector<Vec2> holesAround(const std::optional<Plunge>& back) const;
  void addEnd(Vec2 d, bool towardHole);
  void layEnds(const std::optional<Plunge>& back);
  bool wallsKept(Vec2 end) const;
  bool noGouge(Vec2 end) const;
  bool fitsAt(size_t k);
  template <class F>
  std::optional<Vec2> firstFitting(F worth);
  bool grazes(Vec2 end, double z) const;
  std::vector<std::pair<double, Vec2>> raisedHeights() const;
  std::optional<std::pair<double, Vec2>> raised() const;

  const LeadOutContext& x_;
  const Plunge& p_;
  const Cutter& cutter_;
  const Vec2 c_;
  const double r_, L_;
  const int samples_;  // along the way out, for walls and floor
  std::vector<End> ends_;
  std::vector<signed char> fits_;  // noGouge, computed once when needed
};

LeadOutSearch::LeadOutSearch(const LeadOutContext& context, const Plunge& p, const Cutter& cutter)
    : x_(context), p_(p), cutter_(cutter), c_{p.x, p.y}, r_(cutter.radius), L_(context.in.settings.leadOut),
      samples_(std::max(2, static_cast<int>(std::ceil(context.in.settings.leadOut / (0.25 * cutter.radius))))) {}

// Toward holes cut before, as wide and as deep, d from this one (the
// plunge before first): the moved disk lies in the two holes but where it
// crosses between them, at most sqrt(r^2 + L^2 + L (d - L)) - r beyond this
// hole, no more than half the lead-out L while d <= r + L / 4.
std::vector<Vec2> LeadOutSearch::holesAround(const std::optional<Plunge>& back) const {
  std::vector<Vec2> holes;
  const double reach = r_ + 0.25 * L_;
  if (!(L_ < r_)) return holes;
  if (back && dist(Vec2{back->x, back->y}, c_) >= L_ && dist(Vec2{back->x, back->y}, c_) <= reach &&
      back->z <= p_.z + 1e-9)
    holes.push_back({back->x, back->y});
  for (Vec2 h : x_.touched.holesNear(c_, r_, p_.z + cutterProfile(cutter_, r_), L_, reach, kHolesTried))
    holes.push_back(h);
  return holes;
}

void LeadOutSearch::addEnd(Vec2 d, bool towardHole) {
  const Vec2 end = c_ + d * (L_ / norm(d));
  ends_.push_back({end, x_.region.wallDistance(end, 4 * cutter_.radius), towardHole});
}

// The ends tried, the most room from the walls first: toward the holes, every
// direction, and beside the way to a hole (a contour along a wall that bulges
// in: the straight way back comes too near the wall).
void LeadOutSearch::layEnds(const std::optional<Plunge>& back) {
  const std::vector<Vec2> holes = holesAround(back);
  for (Vec2 h : holes) addEnd(h - c_, true);
  for (int d = 0; d < kLeadOutDirections; ++d)
    addEnd({std::cos(2 * kPi * d / kLeadOutDirections), std::sin(2 * kPi * d / kLeadOutDirections)}, false);
  for (Vec2 h : holes)
    for (double turn : {-20.0, 20.0, -40.0, 40.0}) {
      const double a = std::atan2(h.y - c_.y, h.x - c_.x) + turn * kPi / 180;
      addEnd({std::cos(a), std::sin(a)}, false);
    }
  std::stable_sort(ends_.begin(), ends_.end(), [](const End& a, const End& b) { return a.room > b.room + 1e-9; });
  fits_.assign(ends_.size(), -1);
}

// Walls and islands along the way out, never nearer than the allowance.
bool LeadOutSearch::wallsKept(Vec2 end) const {
  const double fit = cutter_.radius + x_.in.radialAllowance;
  return allAlong(c_, end, samples_, [&](Vec2 q) { return x_.region.diskFits(q, fit); });
}

// The walls, then the floor under the moving tool (a depth optimization per
// sample on sculptured floors).
bool LeadOutSearch::noGouge(Vec2 end) const {
  if (!wallsKept(end)) return false;
  return allAlong(c_, end, samples_, [&](Vec2 q) {
    return x_.depths.plungesTo(q, cutter_, x_.in.floorAllowance, x_.in.radialAllowance, p_.z + 1e-6);
  });
}

bool LeadOutSearch::fitsAt(size_t k) {
  if (fits_[k] < 0) fits_[k] = noGouge(ends_[k].at) ? 1 : 0;
  return fits_[k] == 1;
}

// The first end `worth` taking that keeps walls and floor.
template <class F>
std::optional<Vec2> LeadOutSearch::firstFitting(F worth) {
  for (size_t k = 0; k < ends_.size(); ++k)
    if (worth(ends_[k]) && fitsAt(k)) return ends_[k].at;
  return std::nullopt;
}

// Whether the way out at height z grazes more than half the lead-out.
bool LeadOutSearch::grazes(Vec2 end, double z) const {
  return x_.stock.bite(c_, end, cutter_, z) > 0.5 * L_ ||
         x_.touched.grazes(c_, end, r_, z + cutterProfile(cutter_, r_), 0.5 * L_);
}

// The height each of the first few directions clear at the highest needs to
// graze no more (bisection), lowest first.
std::vector<std::pair<double, Vec2>> LeadOutSearch::raisedHeights() const {
  const double highest = p_.z + L_;
  std::vector<std::pair<double, Vec2>> heights;
  for (size_t k = 0; k < ends_.size() && heights.size() < kRaisedTried; ++k) {
    const Vec2 end = ends_[k].at;
    if (grazes(end, highest) || !wallsKept(end)) continue;
    double lo = p_.z, hi = highest;  // grazes at lo (the tests before), not at hi
    while (hi - lo > kRaisedPrecision) {
      const double mid = 0.5 * (lo + hi);
      (grazes(end, mid) ? lo : hi) = mid;
    }
    heights.push_back({hi, end});
  }
  std::stable_sort(heights.begin(), heights.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return heights;
}

// Raised: a plunge that went deeper than the plunges around it (a hollow of a
// sculptured floor, uneven depths) sits in a ring of their steps. It feeds up
// the ring's height, if that is no more than the lead-out is long (the edges
// drag along at most that much of the wall just cut), then out, grazing no
// more than half the lead-out at that height and clear of the floor under
// the way out. The lowest such height and its end, or none.
std::optional<std::pair<double, Vec2>> LeadOutSearch::raised() const {
  const double highest = p_.z + L_;
  std::optional<std::pair<double, Vec2>> best;
  for (const std::pair<double, Vec2>& h : raisedHeights()) {
    double z = h.first;
    if (best && z >= best->first) break;
    allAlong(c_, h.second, samples_, [&](Vec2 q) {
      z = std::max(z, x_.depths.plungeHeight(q, cutter_, x_.in.floorAllowance, x_.in.radialAllowance));
      return z <= highest;
    });
    if (z <= highest && (!best || z < best->first)) best = {{z, h.second}};
  }
  return best;
}

LeadOut LeadOutSearch::find(const std::optional<Plunge>& back) {
  layEnds(back);
  // Into no material (cells touching the moved disk: the crescent it adds is
  // narrower than a cell), then the exact bound of the stock left.
  const double margin = kCellHalfDiagonal * x_.stock.spacing();
  const double floor = p_.z + cutterProfile(cutter_, cutter_.radius) + kEngagementSkin;
  std::optional<Vec2> to = firstFitting([&](const End& e) {
    return !x_.stock.meetsMaterial(e.at, cutter_, p_.z, margin) && !x_.touched.standsAbove(c_, e.at, r_, floor);
  });
  if (!to) to = firstFitting([](const End& e) { return e.towardHole; });
  // Else any direction whose disk the holes cut so far (as deep) leave to
  // graze less than half the lead-out, measured exactly with their polygons.
  if (!to)
    to = firstFitting([&](const End& e) {
      return !e.towardHole && x_.stock.bite(c_, e.at, cutter_, p_.z) <= 0.5 * L_ &&
             !x_.touched.grazes(c_, e.at, r_, p_.z + cutterProfile(cutter_, r_), 0.5 * L_);
    });
  if (to) return {to, std::nullopt, NoLeadOut::None};
  bool room = false;
  for (size_t k = 0; k < ends_.size() && !room; ++k) room = fits_[k] == 1 || wallsKept(ends_[k].at);
  if (!room) return {std::nullopt, std::nullopt, NoLeadOut::Walls};
  const std::optional<std::pair<double, Vec2>> up = raised();
  if (!up) return {std::nullopt, std::nullopt, NoLeadOut::Material};
  LeadOut out{up->second, std::nullopt, NoLeadOut::None};
  if (up->first > p_.z + 1e-6) out.z = up->first;
  return out;
}

}  // namespace

LeadOut leadOutOf(const LeadOutContext& context, const Plunge& p, const Cutter& cutter,
                  const std::optional<Plunge>& back) {
  return LeadOutSearch(context, p, cutter).find(back);
}

}  // namespace plunge
