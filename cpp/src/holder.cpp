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

// Which part of the tool sets its floor at a place, and the floor.
struct Reach {
  double z = -std::numeric_limits<double>::infinity();
  HolderPart by = HolderPart::Holder;
};

// Each cylinder wider than the cutter, starting `from` mm above the tip with
// radius rho (infinite: as wide as the pocket), keeps `clearance` from the
// stock under its disk grown by the clearance.
Reach floorOf(const Tool& t, const Touched& stock, Vec2 a, Vec2 b, const HolderSettings& settings) {
  const double clearance = settings.clearance;
  Reach f;
  if (!holderKnown(t)) return f;
  const double r = 0.5 * t.diameter;
  auto keep = [&](double from, double rho, HolderPart by) {
    if (rho <= r + 1e-9) return;  // inside the hole the flutes cut
    // As wide as the pocket (or so wide that the search would cost more than
    // the height saves): the top of the stock.
    const double reach = rho + clearance;
    const bool wide = reach >= settings.pocketDiagonal || reach > kWideCells * stock.bucket();
    const double top = wide ? stock.topZ() : stock.highestAlong(a, b, reach);
    if (const double z = top + clearance - from; z > f.z) f = {z, by};
  };
  if (t.shankDiameter && t.fluteLength) keep(*t.fluteLength, 0.5 * *t.shankDiameter, HolderPart::Shank);
  keep(*t.stickOut, t.holderDiameter ? 0.5 * *t.holderDiameter : std::numeric_limits<double>::infinity(),
       HolderPart::Holder);
  return f;
}

// The worst stop of one tool.
struct Worst {
  int count = 0;
  double excess = -1.0;
  Vec2 at;
  HolderPart by = HolderPart::Holder;
};

}  // namespace

double holderFloor(const Tool& t, const Touched& stock, Vec2 a, Vec2 b, const HolderSettings& settings) {
  return floorOf(t, stock, a, b, settings).z;
}

HolderClearance clearHolders(const std::vector<Plunge>& ordered, const ToolTable& tools, const Material& material,
                             const HolderSettings& settings) {
  HolderClearance out;
  // No tool says what holds it: nothing to replay.
  if (std::none_of(tools.all().begin(), tools.all().end(), holderKnown)) {
    out.plunges = ordered;
    return out;
  }
  Touched stock(tools.all().front().diameter, material);
  // Each tool's position (its levels share it): the depth it was to reach,
  // the deepest it cuts, and what stopped it last.
  struct Spot {
    double target = std::numeric_limits<double>::infinity();
    double cut = std::numeric_limits<double>::infinity();
    HolderPart by = HolderPart::Holder;
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
  for (const auto& [key, spot] : spots)
    if (spot.cut > spot.target + 1e-9)
      out.stops.push_back({std::get<0>(key), {std::get<1>(key), std::get<2>(key)}, spot.target, spot.cut, spot.by});
  return out;
}

std::vector<std::string> uncheckedHolders(const std::vector<Plunge>& plunges, const ToolTable& tools, double topZ) {
  std::map<int, double> deepest;  // below top_z
  for (const Plunge& p : plunges) {
    const Tool& t = tools.byId(p.toolId);
    if (holderKnown(t) || !t.fluteLength || topZ - p.z <= *t.fluteLength + 1e-9) continue;
    deepest[p.toolId] = std::max(deepest[p.toolId], topZ - p.z);
  }
  std::vector<std::string> out;
  for (const auto& [id, depth] : deepest)
    out.push_back("tool " + std::to_string(id) + " goes " + detail::fixed(depth) + " mm below top_z, deeper than its " +
                  detail::fixed(*tools.byId(id).fluteLength) +
                  " mm flutes, and no stick_out is given: what holds it is not checked against the part (give its "
                  "stick_out and holder_diameter)");
  return out;
}

Said holderLimits(const std::vector<HolderStop>& stops, const ToolTable& tools, double clearance) {
  Said out;
  // Per tool: the places its plunges stop above their depth, and the worst.
  std::map<int, Worst> worst;
  for (const HolderStop& s : stops) {
    Worst& w = worst[s.toolId];
    ++w.count;
    if (s.cut - s.target > w.excess) w = {w.count, s.cut - s.target, s.at, s.by};
  }
  const auto mm = [](double v) { return detail::fixed(v); };
  for (const auto& [id, w] : worst) {
    const Tool& t = tools.byId(id);
    const std::string name = "tool " + std::to_string(id);
    const bool shank = w.by == HolderPart::Shank;
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
    out.limit("at " + std::to_string(w.count) + " places the plunges of " + name + " stop up to " + mm(w.excess) +
                  " mm above their depth where its " + (shank ? "shank" : "holder") + " would meet the stock",
              std::move(b));
  }
  return out;
}

}  // namespace plunge
