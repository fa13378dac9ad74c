#include "motion.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "broken.hpp"
#include "cuts.hpp"
#include "holder.hpp"
#include "lead_out.hpp"
#include "touched.hpp"

namespace plunge {

namespace {

// Runs of consecutive plunges with the same tool and role.
template <class F>
void forEachGroup(const std::vector<Plunge>& order, F f) {
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j < order.size() && order[j].toolId == order[i].toolId && order[j].startHole == order[i].startHole) ++j;
    f(i, j);
    i = j;
  }
}

// Height of the tool's corner above its tip: the flutes above it cut walls.
double cornerHeight(const Tool& t) { return cutterProfile(cutterOf(t), 0.5 * t.diameter); }

}  // namespace

HeightField stockOf(const std::vector<Tool>& tools, const Material& material, const Region& region) {
  double rMin = 0.5 * tools.back().diameter, limit = rMin;
  for (const Tool& t : tools) {
    rMin = std::min(rMin, 0.5 * t.diameter);
    limit = std::min({limit, t.minEngagement.value_or(limit), t.maxEngagement.value_or(limit)});
  }
  const double rMax = 0.5 * tools.front().diameter;
  const Vec2 lo = region.minCorner() - Vec2{rMax, rMax}, hi = region.maxCorner() + Vec2{rMax, rMax};
  HeightField stock(lo, hi, heightFieldSpacing(lo, hi, rMin, limit), material.topZ());
  stock.lowerTo(material);
  return stock;
}

Levels splitIntoLevels(const std::vector<Plunge>& ordered, const MotionOptions& in) {
  Touched touched(in.tools.all().front().diameter, in.material);
  Levels split;
  std::vector<Plunge>& out = split.plunges;
  forEachGroup(ordered, [&](size_t i, size_t j) {
    const Tool& t = in.tools.byId(ordered[i].toolId);
    const Cutter cutter = cutterOf(t);
    std::vector<double> top;
    int levels = 1;
    const double step = t.fluteLength.value_or(0.0) - cornerHeight(t);
    for (size_t k = i; k < j; ++k) {
      const Vec2 c{ordered[k].x, ordered[k].y};
      top.push_back(touched.highestAlong(c, c, cutter.radius));
      if (t.fluteLength)
        levels = std::max(levels, static_cast<int>(std::ceil((top.back() - ordered[k].z) / step - 1e-9)));
    }
    split.levels = std::max(split.levels, levels);
    // Every other level runs its path backwards: it starts where the level
    // above ended instead of crossing the pocket back. Not for a tool with an
    // engagement limit: its order is what keeps each plunge within it.
    const bool turn = !std::isfinite(engagementLimit(t));
    for (int level = 1; level <= levels; ++level)
      for (size_t n = 0; n < j - i; ++n) {
        const size_t k = turn && level % 2 == 0 ? j - 1 - n : i + n;
        Plunge p = ordered[k];
        p.z = level == levels ? p.z : std::max(p.z, top[k - i] - level * step);
        // Already at its depth on an earlier level.
        if (level > 1 && std::max(ordered[k].z, top[k - i] - (level - 1) * step) <= ordered[k].z) continue;
        p.level = level - 1;
        out.push_back(p);
        touched.add({p.x, p.y}, cutter.radius, p.z + cornerHeight(t));
      }
  });
  return split;
}

namespace {

// A plunge over its tool's max engagement by more than this is counted: the
// exact measure's rounding (cuts.hpp), as the tests' polygon replay allows.
constexpr double kEngagementTolerance = 0.01;

// A hole drilled into solid: material at the plunge's axis (a crescent beside
// removed material has its axis in the hole beside, and its chips room to go).
// Deeper than the tool's peck depth, from the material's top at the axis, it is
// pecked: a stop every peck depth, the last one short of z by at least a tenth
// of a peck (a stop closer to the bottom clears nothing).
std::vector<double> pecksOf(const Plunge& p, const Tool& t, const HeightField& stock, const MotionOptions& in) {
  std::vector<double> pecks;
  const double top = stock.heightAt({p.x, p.y});
  if (!in.settings.peck || top <= p.z + kEngagementSkin) return pecks;
  const double peck = peckDepthOf(t);
  for (double z = top - peck; z > p.z + 0.1 * peck; z -= peck) pecks.push_back(z);
  return pecks;
}

// Each limit a plunge breaks: how many, the worst (most beyond it) and where.
struct Worst {
  BrokenLimit b;
  double excess = -1.0;
  bool start = false;  // the worst is a start
  void add(const Plunge& p, double value, double limit, double beyond) {
    ++b.count;
    if (beyond <= excess) return;
    excess = beyond;
    start = p.start;
    b.worst = value;
    b.asked = limit;
    b.at = {p.x, p.y};
  }
  // Said once with its count, the worst and why.
  void say(Said& said, const std::string& what, const char* why) {
    if (b.count == 0) return;
    std::ostringstream s;
    s << std::fixed << std::setprecision(2) << b.count << what << " (" << b.worst << " mm against " << b.asked
      << " mm)";
    b.why = why;
    said.limit(s.str(), b);
  }
};

// The plan's moves laid out in execution order on one simulation of the
// stock: heights, lead-outs and the limits' checks (planMotion).
class MotionPass {
 public:
  MotionPass(const Region& region, const DepthSolver& depths, const MotionOptions& in)
      : region_(region), depths_(depths), in_(in), stock_(stockOf(in.tools.all(), in.material, region)),
        cuts_(kEngagementSkin, in.material), touched_(in.tools.all().front().diameter, in.material),
        mount_{in.settings.holderClearance, dist(region.minCorner(), region.maxCorner())} {
    over_.b = {"max_engagement", 0, 0, {}, 0, ""};
    thin_.b = {"min_engagement", 0, 0, {}, 0, ""};
    core_.b = {"core_diameter", 0, 0, {}, 0, ""};
    deep_.b = {"flute_length", 0, 0, {}, 0, ""};
  }
  Motion run(std::vector<Plunge> plunges);

 private:
  // A rapid's way to the next plunge: its height and the points between.
  struct Way {
    double z;
    std::vector<Vec2> via;
  };
  // What a way around the wall band keeps from it (mm beyond the band).
  static constexpr double kBandMargin = 0.2;
  double measure(Plunge& p, const Tool& t);
  void retractBefore(Motion& m, size_t i);
  double heightAlong(const Plunge& q, const Plunge& p, const std::vector<Vec2>& path) const;
  Way wayTo(const Plunge& q, const Plunge& p, Vec2 from) const;
  void leadOut(Motion& m, size_t i, const Tool& t);
  void report(Motion& m);

  const Region& region_;
  const DepthSolver& depths_;
  const MotionOptions& in_;
  HeightField stock_;
  Cuts cuts_;  // the plunges alone (not their lead-outs) and the material before: the engagement as grown
  Touched touched_;
  HolderSettings mount_;  // what the holders keep clear along the moves
  Worst over_, thin_, core_, deep_;
};

Motion MotionPass::run(std::vector<Plunge> plunges) {
  Motion m;
  m.plunges = std::move(plunges);
  std::vector<Plunge>& ps = m.plunges;
  for (size_t i = 0; i < ps.size(); ++i) {
    in_.progress.tick(static_cast<double>(i) / ps.size());
    Plunge& p = ps[i];
    const Tool& t = in_.tools.byId(p.toolId);
    const double top = measure(p, t);
    p.approachZ = in_.settings.stockAwareHeights ? std::min(in_.safeZ, std::max(top, p.z) + in_.settings.rapidClearance) : in_.safeZ;
    if (i > 0) retractBefore(m, i);
    p.pecks = pecksOf(p, t, stock_, in_);
    if (!p.pecks.empty()) ++m.stats.peckedPlunges;
    const Cutter cutter = cutterOf(t);
    stock_.cut({p.x, p.y}, cutter, p.z);
    cuts_.add({p.x, p.y}, cutter, p.z);
    touched_.add({p.x, p.y}, cutter.radius, p.z + cornerHeight(t));
    leadOut(m, i, t);
    p.retractZ = in_.safeZ;
  }
  report(m);
  m.stats.estimatedMinutes = motionMinutes(m.plunges, in_, false);
  m.stats.minutesAtSafeHeight = motionMinutes(m.plunges, in_, true);
  return m;
}

// What the plunge meets: its engagement measured exactly (cuts.hpp), as the
// growth measured it, in the order posted, and the limits it breaks. Returns
// the highest stock under it.
double MotionPass::measure(Plunge& p, const Tool& t) {
  const Cutter cutter = cutterOf(t);
  const Vec2 c{p.x, p.y};
  const HeightField::Contact k = stock_.contact(c, cutter, p.z, coreRadius(t));
  p.engagement = k.materialCells > 0 ? cuts_.engagement(c, cutter, p.z) : 0.0;
  const double top = touched_.highestAlong(c, c, cutter.radius);
  const double tol = 1.5 * stock_.spacing();
  // A start is exempt where it drills: into solid, or (a tool that does not
  // cut at its centre) onto its start hole. A start the growth had to make
  // beside cut material (its fallback) is measured as any plunge.
  const bool drills = p.start && (k.solid || !t.centerCutting);
  if (!drills && t.maxEngagement && p.engagement > *t.maxEngagement + kEngagementTolerance)
    over_.add(p, p.engagement, *t.maxEngagement, p.engagement - *t.maxEngagement);
  if (!p.start && t.minEngagement && k.materialCells > 0 && p.engagement < *t.minEngagement - tol)
    thin_.add(p, p.engagement, *t.minEngagement, *t.minEngagement - p.engagement);
  if (!t.centerCutting && !k.coreClear) core_.add(p, k.deepest, t.coreDiameter, k.deepest);
  if (t.fluteLength && k.deepest + cornerHeight(t) > *t.fluteLength + 1e-6)
    deep_.add(p, k.deepest + cornerHeight(t), *t.fluteLength, k.deepest + cornerHeight(t) - *t.fluteLength);
  return top;
}

// The retract of the plunge before plunge i: as high as the stock along the
// move needs, straight or around (wayTo).
void MotionPass::retractBefore(Motion& m, size_t i) {
  const Plunge& p = m.plunges[i];
  Plunge& q = m.plunges[i - 1];
  const Vec2 c{p.x, p.y};
  const Vec2 from = q.leadOut ? *q.leadOut : Vec2{q.x, q.y};
  q.retractZ = in_.safeZ;
  q.via.clear();
  if (in_.settings.stockAwareHeights && q.toolId == p.toolId) {
    const Way w = wayTo(q, p, from);
    q.retractZ = w.z;
    q.via = w.via;
  }
  double length = 0.0;
  Vec2 at = from;
  for (Vec2 v : q.via) {
    length += dist(at, v);
    at = v;
  }
  m.stats.travelLength += length + dist(at, c);
}

// The height a rapid along `path` needs: rapid_clearance over the stock its
// tool sweeps, its holder and shank clear, no lower than the plunges' own.
double MotionPass::heightAlong(const Plunge& q, const Plunge& p, const std::vector<Vec2>& path) const {
  const Tool& t = in_.tools.byId(q.toolId);
  double z = std::max(p.approachZ, q.z + in_.settings.rapidClearance);
  for (size_t k = 0; k + 1 < path.size(); ++k)
    z = std::max({z, touched_.highestAlong(path[k], path[k + 1], 0.5 * q.diameter) + in_.settings.rapidClearance,
                  holderFloor(t, touched_, path[k], path[k + 1], mount_)});
  return std::min(in_.safeZ, z);
}

// The way from plunge q (its lead-out's end) to plunge p. Straight, or around:
// each end pushed away from its nearest wall until the swept tool clears the
// wall band the covering may leave standing (the cusps between plunges along
// a wall, up to the radial allowance and max_wall_stock from it), when
// climbing less makes up for the longer way (up and down at the retract rate,
// across at the rapid rate).
MotionPass::Way MotionPass::wayTo(const Plunge& q, const Plunge& p, Vec2 from) const {
  const Vec2 to{p.x, p.y};
  Way best{heightAlong(q, p, {from, to}), {}};
  const double low = std::max(p.approachZ, q.z + in_.settings.rapidClearance);
  if (best.z <= low + 1e-9) return best;
  const TimeModel& m = in_.settings.timeModel;
  auto minutes = [&](double z, const std::vector<Vec2>& path) {
    double length = 0.0;
    for (size_t k = 0; k + 1 < path.size(); ++k) length += dist(path[k], path[k + 1]);
    return 2.0 * z / m.retractRate + length / m.rapidRate;
  };
  double bestMinutes = minutes(best.z, {from, to});
  const double r = 0.5 * q.diameter;
  const double band = in_.radialAllowance + in_.maxWallStock + kBandMargin;
  // A point pushed away from its nearest wall (within reach of the band) by
  // `extra` beyond where its swept disk clears the band.
  // (Again from the point pushed, for a corner's second wall.)
  auto pushed = [&](Vec2 x, double extra) {
    for (int k = 0; k < 3; ++k) {
      Vec2 wall;
      double d = 0.0;
      if (!region_.nearestWallPoint(x, r + band + extra, wall, d) || d <= 1e-9 || d >= r + band - 1e-9) break;
      x = x + (x - wall) * ((r + band - d + (k == 0 ? extra : 0.0)) / d);
    }
    return x;
  };
  for (const double extra : {0.0, 0.5 * r}) {
    const Vec2 a = pushed(from, extra), b = pushed(to, extra);
    std::vector<Vec2> path{from};
    if (dist(a, from) > 1e-6) path.push_back(a);
    if (dist(b, to) > 1e-6) path.push_back(b);
    path.push_back(to);
    if (path.size() == 2) continue;
    const double z = heightAlong(q, p, path);
    const double t = minutes(z, path);
    if (z < best.z - 1e-9 && t < bestMinutes - 1e-12) {
      best = {z, std::vector<Vec2>(path.begin() + 1, path.end() - 1)};
      bestMinutes = t;
    }
  }
  return best;
}

// Plunge i's lead-out (lead_out.hpp), cut into the stock the next plunges meet.
void MotionPass::leadOut(Motion& m, size_t i, const Tool& t) {
  Plunge& p = m.plunges[i];
  const Cutter cutter = cutterOf(t);
  p.leadOut.reset();
  p.leadOutZ.reset();
  if (in_.settings.leadOut > 0.0) {
    // Back toward the plunge before, where the same tool just cut.
    std::optional<Plunge> back;
    if (i > 0 && m.plunges[i - 1].toolId == p.toolId) back = m.plunges[i - 1];
    LeadOut out = leadOutOf({in_, region_, depths_, stock_, touched_}, p, cutter, back);
    // None where the holder or shank, moved along with the tip, would meet the
    // stock (beside the walls of a deep pocket): no room at the walls.
    if (out.to && holderFloor(t, touched_, {p.x, p.y}, *out.to, mount_) > out.z.value_or(p.z) + 1e-9) {
      out.to.reset();
      out.z.reset();
      out.why = NoLeadOut::Walls;
    }
    p.leadOut = out.to;
    p.leadOutZ = out.z;
    if (out.why == NoLeadOut::Material) ++m.stats.noLeadOutMaterial;
    if (out.why == NoLeadOut::Walls) ++m.stats.noLeadOutWalls;
    if (p.leadOut) ++m.stats.leadOuts;
    if (p.leadOutZ) ++m.stats.raisedLeadOuts;
  }
  if (p.leadOut) {
    touched_.add(*p.leadOut, cutter.radius, p.leadOutZ.value_or(p.z) + cornerHeight(t));
    stock_.cut(*p.leadOut, cutter, p.leadOutZ.value_or(p.z));  // what the next plunges meet
  }
}

// What the limits could not keep, each said once with its count, the worst and why.
void MotionPass::report(Motion& m) {
  m.stats.overEngaged = over_.b.count;
  m.stats.thinCuts = thin_.b.count;
  over_.say(m.said, " plunges cut a wider band than their tool's max engagement",
            over_.start
                ? "a start the growth had to make beside cut material, where no path reached within the limit;"
                  " a smaller plunger there, or a larger max engagement, avoids it"
                : "uneven depths of a sculptured floor leave steps thicker than the limit there; a lower max floor"
                  " stock or a smaller plunger cuts them in thinner steps");
  thin_.say(m.said, " plunges cut a narrower band than their tool's min engagement",
            "the last slivers of their region, where the walls leave no wider cut, and the tool may deflect there; a"
            " smaller min engagement, or a smaller plunger for the slivers, avoids them");
  core_.say(m.said, " plunges of a non-centre-cutting tool have material under the core",
            "uneven floor depths leave material there that the core cannot cut; a centre-cutting plunger, or a lower"
            " max floor stock, clears it first");
  deep_.say(m.said, " plunges cut deeper than their tool's flute length",
            "the material there stands higher above the stop than the flutes reach; a plunger with longer flutes"
            " would cut it");
}

}  // namespace

Motion planMotion(const Region& region, const DepthSolver& depths, std::vector<Plunge> plunges,
                  const MotionOptions& in) {
  return MotionPass(region, depths, in).run(std::move(plunges));
}

double motionMinutes(const std::vector<Plunge>& plunges, const MotionOptions& in, bool atSafeHeight) {
  const TimeModel& m = in.settings.timeModel;
  double minutes = 0.0, z = in.safeZ;
  int changes = 0;
  for (size_t i = 0; i < plunges.size(); ++i) {
    const Plunge& p = plunges[i];
    const double feed = in.tools.byId(p.toolId).feed;
    if (i == 0 || plunges[i - 1].toolId != p.toolId) ++changes;
    if (i > 0) {
      const Plunge& q = plunges[i - 1];
      Vec2 at = q.leadOut ? *q.leadOut : Vec2{q.x, q.y};
      for (Vec2 v : atSafeHeight ? std::vector<Vec2>{} : q.via) {
        minutes += dist(at, v) / m.rapidRate;
        at = v;
      }
      minutes += dist(at, {p.x, p.y}) / m.rapidRate;
    }
    const double approach = atSafeHeight ? in.safeZ : p.approachZ;
    const double retract = atSafeHeight ? in.safeZ : p.retractZ;
    minutes += std::max(0.0, z - approach) / m.retractRate + (approach - p.z) / feed;
    // Each peck: up out of the hole and back to just above its depth, at rapid.
    for (double at : p.pecks) minutes += (2 * (approach - at) - in.settings.rapidClearance) / m.retractRate;
    if (!p.pecks.empty()) minutes += in.settings.peckDwell / 60.0;
    if (p.leadOut) minutes += (dist(*p.leadOut, {p.x, p.y}) + p.leadOutZ.value_or(p.z) - p.z) / feed;
    minutes += (retract - p.z) / m.retractRate;
    z = retract;
  }
  return minutes + changes * m.toolChangeSeconds / 60.0;
}

}  // namespace plunge
