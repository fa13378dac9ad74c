#include "holder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "depth.hpp"
#include "detail.hpp"

namespace plunge {

bool holderKnown(const Tool& t) { return t.stickOut.has_value(); }

namespace {

// A holder wider than this many of the stock's grid cells is taken as wide as
// the pocket (Touched scans every cell under it).
constexpr double kWideCells = 32.0;

// Which part of the tool sets its floor at a place.
enum class Limiter { None, Shank, Holder };

struct Reach {
  double z = -std::numeric_limits<double>::infinity();
  Limiter by = Limiter::None;
};

// Each cylinder wider than the cutter, starting `from` mm above the tip with
// radius rho (infinite: as wide as the pocket), keeps `clearance` from the
// stock under its disk grown by the clearance.
Reach floorOf(const Tool& t, const Touched& stock, Vec2 a, Vec2 b, const HolderSettings& settings) {
  const double clearance = settings.clearance;
  Reach f;
  if (!holderKnown(t)) return f;
  const double r = 0.5 * t.diameter;
  auto keep = [&](double from, double rho, Limiter by) {
    if (rho <= r + 1e-9) return;  // inside the hole the flutes cut
    // As wide as the pocket (or so wide that the search would cost more than
    // the height saves): the top of the stock.
    const double reach = rho + clearance;
    const bool wide = reach >= settings.pocketDiagonal || reach > kWideCells * stock.bucket();
    const double top = wide ? stock.topZ() : stock.highestAlong(a, b, reach);
    if (const double z = top + clearance - from; z > f.z) f = {z, by};
  };
  if (t.shankDiameter && t.fluteLength) keep(*t.fluteLength, 0.5 * *t.shankDiameter, Limiter::Shank);
  keep(*t.stickOut, t.holderDiameter ? 0.5 * *t.holderDiameter : std::numeric_limits<double>::infinity(),
       Limiter::Holder);
  return f;
}

// The worst raised plunge of one tool.
struct Worst {
  int count = 0;
  double excess = -1.0;
  Vec2 at;
  Limiter by = Limiter::None;
};

}  // namespace

double holderFloor(const Tool& t, const Touched& stock, Vec2 a, Vec2 b, const HolderSettings& settings) {
  return floorOf(t, stock, a, b, settings).z;
}

HolderClearance clearHolders(const std::vector<Plunge>& ordered, const ToolTable& tools, const Material& material,
                             const HolderSettings& settings) {
  const double clearance = settings.clearance;
  HolderClearance out;
  // No tool says what holds it: nothing to replay.
  if (std::none_of(tools.all().begin(), tools.all().end(), holderKnown)) {
    out.plunges = ordered;
    return out;
  }
  Touched stock(tools.all().front().diameter, material);
  // The deepest cut so far at each tool's position: a level raised to where
  // an earlier level already cut adds nothing.
  // Each tool's position (its levels share it): the depth it was to reach,
  // the deepest it cuts, and what stopped it last.
  struct Spot {
    double target = std::numeric_limits<double>::infinity();
    double cut = std::numeric_limits<double>::infinity();
    Limiter by = Limiter::None;
  };
  std::map<std::tuple<int, double, double>, Spot> spots;
  for (const Plunge& p : ordered) {
    const Tool& t = tools.byId(p.toolId);
    const Vec2 c{p.x, p.y};
    Spot& spot = spots[std::make_tuple(p.toolId, p.x, p.y)];
    spot.target = std::min(spot.target, p.z);
    Plunge q = p;
    const Reach f = floorOf(t, stock, c, c, settings);
    if (q.z < f.z - 1e-9) {
      q.z = f.z;
      q.holderLimited = true;
      spot.by = f.by;
      // A level raised to where an earlier level already cut adds nothing.
      if (spot.cut <= q.z + 1e-9) continue;
    }
    spot.cut = std::min(spot.cut, q.z);
    stock.add(c, 0.5 * t.diameter, q.z + cutterProfile(cutterOf(t), 0.5 * t.diameter));
    out.plunges.push_back(q);
  }
  // Per tool: the places its plunges stop above their depth, and the worst.
  std::map<int, Worst> worst;
  for (const auto& [key, spot] : spots) {
    if (!(spot.cut > spot.target + 1e-9)) continue;
    Worst& w = worst[std::get<0>(key)];
    ++w.count;
    if (spot.cut - spot.target > w.excess) w = {w.count, spot.cut - spot.target, {std::get<1>(key), std::get<2>(key)}, spot.by};
  }
  const auto mm = [](double v) { return detail::fixed(v); };
  for (const auto& [id, w] : worst) {
    const Tool& t = tools.byId(id);
    const std::string name = "tool " + std::to_string(id);
    const bool shank = w.by == Limiter::Shank;
    BrokenLimit b;
    b.limit = "stick_out";
    b.asked = *t.stickOut;
    b.worst = *t.stickOut + w.excess;
    b.at = w.at;
    b.count = w.count;
    std::string part;
    if (shank)
      part = "the " + mm(*t.shankDiameter) + " mm shank of " + name + " (from " + mm(*t.fluteLength) +
             " mm above its tip)";
    else if (t.holderDiameter)
      part = "the " + mm(*t.holderDiameter) + " mm holder of " + name + " (" + mm(*t.stickOut) + " mm above its tip)";
    else
      part = "the holder of " + name + ", " + mm(*t.stickOut) +
             " mm above its tip, its diameter not given (so taken as wide as the pocket)";
    b.why = part + " would come within the holder clearance (" + mm(clearance) +
            " mm) of the part or the material still standing; they stop where it clears, leaving up to " +
            mm(w.excess) + " mm above their depth; " +
            (shank ? "flutes " + mm(*t.fluteLength + w.excess) + " mm long, or a slimmer shank, would reach"
                   : "a stick-out of " + mm(b.worst) + " mm" +
                         (t.holderDiameter ? std::string(", or a slimmer holder,") : std::string(" (or the holder's diameter given)")) +
                         " would reach");
    out.said.push_back("at " + std::to_string(w.count) + " places the plunges of " + name + " stop up to " +
                       mm(w.excess) + " mm above their depth where its " + (shank ? "shank" : "holder") +
                       " would meet the stock");
    out.broken.push_back(std::move(b));
  }
  return out;
}

}  // namespace plunge
