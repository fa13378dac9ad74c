#include "motion.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "broken.hpp"
#include "cuts.hpp"
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

HeightField stockOf(const std::vector<Tool>& tools, double topZ, const Region& region) {
  double rMin = 0.5 * tools.back().diameter, limit = rMin;
  for (const Tool& t : tools) {
    rMin = std::min(rMin, 0.5 * t.diameter);
    if (t.minEngagement > 0) limit = std::min(limit, t.minEngagement);
    if (t.maxEngagement > 0) limit = std::min(limit, t.maxEngagement);
  }
  const double rMax = 0.5 * tools.front().diameter;
  const Vec2 lo = region.minCorner() - Vec2{rMax, rMax}, hi = region.maxCorner() + Vec2{rMax, rMax};
  return HeightField(lo, hi, heightFieldSpacing(lo, hi, rMin, limit), topZ);
}

std::vector<Plunge> splitIntoLevels(const std::vector<Plunge>& ordered, const MotionOptions& in, PlanStats& stats) {
  Touched touched(in.tools.all().front().diameter, in.topZ);
  std::vector<Plunge> out;
  stats.levels = 1;
  forEachGroup(ordered, [&](size_t i, size_t j) {
    const Tool& t = in.tools.byId(ordered[i].toolId);
    const Cutter cutter = cutterOf(t);
    std::vector<double> top;
    int levels = 1;
    const double step = t.fluteLength - cornerHeight(t);
    for (size_t k = i; k < j; ++k) {
      const Vec2 c{ordered[k].x, ordered[k].y};
      top.push_back(touched.highestAlong(c, c, cutter.radius));
      if (t.fluteLength > 0.0)
        levels = std::max(levels, static_cast<int>(std::ceil((top.back() - ordered[k].z) / step - 1e-9)));
    }
    stats.levels = std::max(stats.levels, levels);
    for (int level = 1; level <= levels; ++level)
      for (size_t k = i; k < j; ++k) {
        Plunge p = ordered[k];
        p.z = level == levels ? p.z : std::max(p.z, top[k - i] - level * step);
        // Already at its depth on an earlier level.
        if (level > 1 && std::max(ordered[k].z, top[k - i] - (level - 1) * step) <= ordered[k].z) continue;
        p.level = level - 1;
        out.push_back(p);
        touched.add({p.x, p.y}, cutter.radius, p.z + cornerHeight(t));
      }
  });
  return out;
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
  if (!in.peck || top <= p.z + kEngagementSkin) return pecks;
  const double peck = peckDepthOf(t);
  for (double z = top - peck; z > p.z + 0.1 * peck; z -= peck) pecks.push_back(z);
  return pecks;
}

}  // namespace

void planMotion(const Region& region, const DepthSolver& depths, Plan& plan, const MotionOptions& in) {
  HeightField stock = stockOf(in.tools.all(), in.topZ, region);
  Cuts cuts(kEngagementSkin);  // the plunges alone (not their lead-outs): the engagement as grown
  std::vector<Plunge>& ps = plan.plunges;
  Touched touched(in.tools.all().front().diameter, in.topZ);
  auto highestAlong = [&](Vec2 a, Vec2 b, double r) { return touched.highestAlong(a, b, r); };
  const double tol = 1.5 * stock.spacing();
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
  };
  Worst over, thin, core, deep;
  over.b = {"max_engagement", 0, 0, {}, 0, ""};
  thin.b = {"min_engagement", 0, 0, {}, 0, ""};
  core.b = {"core_diameter", 0, 0, {}, 0, ""};
  deep.b = {"flute_length", 0, 0, {}, 0, ""};
  plan.stats.overEngaged = plan.stats.thinCuts = 0;
  plan.stats.leadOuts = plan.stats.raisedLeadOuts = plan.stats.noLeadOutMaterial = plan.stats.noLeadOutWalls = 0;
  plan.stats.travelLength = 0.0;
  plan.stats.peckedPlunges = 0;
  for (size_t i = 0; i < ps.size(); ++i) {
    in.progress.tick(static_cast<double>(i) / ps.size());
    Plunge& p = ps[i];
    const Tool& t = in.tools.byId(p.toolId);
    const Cutter cutter = cutterOf(t);
    const Vec2 c{p.x, p.y};
    const double r = cutter.radius;
    // What the plunge meets: its engagement measured exactly (cuts.hpp), as
    // the growth measured it, in the order posted.
    const HeightField::Contact k = stock.contact(c, cutter, p.z, coreRadius(t));
    p.engagement = k.materialCells > 0 ? cuts.engagement(c, cutter, p.z) : 0.0;
    const double top = highestAlong(c, c, r);
    // A start is exempt where it drills: into solid, or (a tool that does not
    // cut at its centre) onto its start hole. A start the growth had to make
    // beside cut material (its fallback) is measured as any plunge.
    const bool drills = p.start && (k.solid || !t.centerCutting);
    if (!drills && t.maxEngagement > 0 && p.engagement > t.maxEngagement + kEngagementTolerance)
      over.add(p, p.engagement, t.maxEngagement, p.engagement - t.maxEngagement);
    if (!p.start && t.minEngagement > 0 && k.materialCells > 0 && p.engagement < t.minEngagement - tol)
      thin.add(p, p.engagement, t.minEngagement, t.minEngagement - p.engagement);
    if (!t.centerCutting && !k.coreClear) core.add(p, k.deepest, t.coreDiameter, k.deepest);
    if (t.fluteLength > 0 && k.deepest + cornerHeight(t) > t.fluteLength + 1e-6)
      deep.add(p, k.deepest + cornerHeight(t), t.fluteLength, k.deepest + cornerHeight(t) - t.fluteLength);
    p.approachZ = in.stockAwareHeights ? std::min(in.safeZ, std::max(top, p.z) + in.rapidClearance) : in.safeZ;
    // The retract of the plunge before: as high as the stock along the move.
    if (i > 0) {
      Plunge& q = ps[i - 1];
      const Vec2 from = q.leadOut ? *q.leadOut : Vec2{q.x, q.y};
      plan.stats.travelLength += dist(from, c);
      q.retractZ = in.safeZ;
      if (in.stockAwareHeights && q.toolId == p.toolId)
        q.retractZ = std::min(in.safeZ, std::max({highestAlong(from, c, 0.5 * q.diameter) + in.rapidClearance,
                                                  p.approachZ, q.z + in.rapidClearance}));
    }
    p.pecks = pecksOf(p, t, stock, in);
    if (!p.pecks.empty()) ++plan.stats.peckedPlunges;
    stock.cut(c, cutter, p.z);
    cuts.add(c, cutter, p.z);
    touched.add(c, r, p.z + cornerHeight(t));
    p.leadOut.reset();
    p.leadOutZ.reset();
    if (in.leadOut > 0.0) {
      // Back toward the plunge before, where the same tool just cut.
      std::optional<Plunge> back;
      if (i > 0 && ps[i - 1].toolId == p.toolId) back = ps[i - 1];
      const LeadOut out = leadOutOf({in, region, depths, stock, touched}, p, cutter, back);
      p.leadOut = out.to;
      p.leadOutZ = out.z;
      if (out.why == NoLeadOut::Material) ++plan.stats.noLeadOutMaterial;
      if (out.why == NoLeadOut::Walls) ++plan.stats.noLeadOutWalls;
      if (p.leadOut) ++plan.stats.leadOuts;
      if (p.leadOutZ) ++plan.stats.raisedLeadOuts;
    }
    if (p.leadOut) {
      touched.add(*p.leadOut, r, p.leadOutZ.value_or(p.z) + cornerHeight(t));
      stock.cut(*p.leadOut, cutter, p.leadOutZ.value_or(p.z));  // what the next plunges meet
    }
    p.retractZ = in.safeZ;
  }
  // What the limits could not keep, each said once with its count, the worst and why.
  plan.stats.overEngaged = over.b.count;
  plan.stats.thinCuts = thin.b.count;
  auto say = [&](Worst& w, const std::string& what, const char* why) {
    if (w.b.count == 0) return;
    std::ostringstream s;
    s << std::fixed << std::setprecision(2) << w.b.count << what << " (" << w.b.worst << " mm against "
      << w.b.asked << " mm)";
    w.b.why = why;
    sayBroken(plan, s.str(), w.b);
  };
  say(over, " plunges cut a wider band than their tool's max engagement",
      over.start ? "a start the growth had to make beside cut material, where no path reached within the limit;"
                   " a smaller plunger there, or a larger max engagement, avoids it"
                 : "uneven depths of a sculptured floor leave steps thicker than the limit there; a lower max floor"
                   " stock or a smaller plunger cuts them in thinner steps");
  say(thin, " plunges cut a narrower band than their tool's min engagement",
      "the last slivers of their region, where the walls leave no wider cut, and the tool may deflect there; a"
      " smaller min engagement, or a smaller plunger for the slivers, avoids them");
  say(core, " plunges of a non-centre-cutting tool have material under the core",
      "uneven floor depths leave material there that the core cannot cut; a centre-cutting plunger, or a lower max"
      " floor stock, clears it first");
  say(deep, " plunges cut deeper than their tool's flute length",
      "the material there stands higher above the stop than the flutes reach; a plunger with longer flutes would"
      " cut it");
  plan.stats.estimatedMinutes = motionMinutes(plan, in, false);
  plan.stats.minutesAtSafeHeight = motionMinutes(plan, in, true);
}

double motionMinutes(const Plan& plan, const MotionOptions& in, bool atSafeHeight) {
  const TimeModel& m = in.timeModel;
  double minutes = 0.0, z = in.safeZ;
  int changes = 0;
  for (size_t i = 0; i < plan.plunges.size(); ++i) {
    const Plunge& p = plan.plunges[i];
    const double feed = in.tools.byId(p.toolId).feed;
    if (i == 0 || plan.plunges[i - 1].toolId != p.toolId) ++changes;
    if (i > 0) {
      const Plunge& q = plan.plunges[i - 1];
      minutes += dist(q.leadOut ? *q.leadOut : Vec2{q.x, q.y}, {p.x, p.y}) / m.rapidRate;
    }
    const double approach = atSafeHeight ? in.safeZ : p.approachZ;
    const double retract = atSafeHeight ? in.safeZ : p.retractZ;
    minutes += std::max(0.0, z - approach) / m.retractRate + (approach - p.z) / feed;
    // Each peck: up out of the hole and back to just above its depth, at rapid.
    for (double at : p.pecks) minutes += (2 * (approach - at) - in.rapidClearance) / m.retractRate;
    if (!p.pecks.empty()) minutes += in.peckDwell / 60.0;
    if (p.leadOut) minutes += (dist(*p.leadOut, {p.x, p.y}) + p.leadOutZ.value_or(p.z) - p.z) / feed;
    minutes += (retract - p.z) / m.retractRate;
    z = retract;
  }
  return minutes + changes * m.toolChangeSeconds / 60.0;
}

}  // namespace plunge
