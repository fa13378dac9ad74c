#include "limits.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "detail.hpp"
#include "covering.hpp"
#include "plunge/error.hpp"
#include "polygon.hpp"
#include "plunge/tools.hpp"

namespace plunge {

namespace {

std::string mm(double v) {
  std::ostringstream s;
  s.precision(v >= 1e5 || (v > 0 && v < 1e-3) ? 3 : 6);
  if (v >= 1e5 || (v > 0 && v < 1e-3)) s << std::scientific;
  s << v;
  return s.str();
}

void requireLength(double v, const std::string& what) {
  if (std::fabs(v) > kMaxLength)
    throw Error(what + " " + mm(v) + " mm is beyond the " + mm(kMaxLength) +
                " mm (100 m) any machine travels: is it in mm?");
}

void checkMaterial(const MaterialGrid& g) {
  if (g.nx * g.ny > kMaxMaterialCells)
    throw Error("material: " + std::to_string(g.nx) + " x " + std::to_string(g.ny) + " cells, more than " +
                std::to_string(kMaxMaterialCells) + ": a coarser spacing");
  if (g.nx == 0 || g.ny == 0 || g.top.size() != g.nx * g.ny)
    throw Error("material.top: " + std::to_string(g.top.size()) + " heights for " + std::to_string(g.nx) + " x " +
                std::to_string(g.ny) + " cells");
  requireLength(g.origin.x, "material.origin");
  requireLength(g.origin.y, "material.origin");
  if (!(g.spacing > 0.0) || g.spacing * static_cast<double>(std::max(g.nx, g.ny)) > 2 * kMaxLength)
    throw Error("material.spacing: " + mm(g.spacing) + " mm: expected a positive cell size");
  for (double v : g.top) {
    if (!std::isfinite(v)) throw Error("material.top: a height is not a number");
    requireLength(v, "material.top: a height of");
  }
}

double pocketArea(const PlanInput& in) {
  double a = std::fabs(signedArea(in.boundary));
  for (const Loop& l : in.islands) a -= std::fabs(signedArea(l));
  return std::max(a, 0.0);
}

}  // namespace

namespace {

// The largest tool with an engagement limit, which grows most of such a plan
// (engagement.hpp), or none.
const Tool* grownTool(const PlanInput& in) {
  for (const Tool& t : in.tools)  // largest first
    if (std::isfinite(engagementLimit(t))) return &t;
  return nullptr;
}

}  // namespace

double estimatedPlunges(const PlanInput& in) {
  const double area = pocketArea(in), r = 0.5 * in.tools.back().diameter;
  const double packed = area / (kPi * r * r);
  const Tool* g = grownTool(in);
  // A grown cut: rows about 0.87 D apart, a plunge every e along them.
  return g ? std::max(packed, kGrowthCost * area / (0.87 * g->diameter * std::min(engagementLimit(*g), g->diameter))) : packed;
}

void checkScale(const PlanInput& in) {
  size_t vertices = in.boundary.size();
  for (const Loop& l : in.islands) vertices += l.size();
  if (vertices > kMaxVertices)
    throw Error("boundary and islands have " + std::to_string(vertices) + " vertices, more than " +
                std::to_string(kMaxVertices) + ": export the face with a coarser tolerance");
  for (const Vec2& p : in.boundary) {
    requireLength(p.x, "boundary: coordinate");
    requireLength(p.y, "boundary: coordinate");
  }
  for (size_t i = 0; i < in.islands.size(); ++i)
    for (const Vec2& p : in.islands[i]) {
      requireLength(p.x, "island " + std::to_string(i + 1) + ": coordinate");
      requireLength(p.y, "island " + std::to_string(i + 1) + ": coordinate");
    }
  if (in.material) checkMaterial(*in.material);
  requireLength(in.topZ, "top_z");
  requireLength(in.safeZ, "safe_z");
  if (in.floor.surface.kind == Floor::Kind::Flat) requireLength(in.floor.surface.z, "floor.z");
  if (in.floor.finalDepth) requireLength(*in.floor.finalDepth, "final_depth");
  requireLength(in.radialAllowance, "allowance.radial");
  requireLength(in.floorAllowance, "allowance.floor");
  requireLength(in.covering.maxWallStock, "max_wall_stock");
  requireLength(in.floor.maxFloorStock, "max_floor_stock");
  requireLength(in.motion.leadOut, "lead_out");
  requireLength(in.motion.rapidClearance, "rapid_clearance");
  requireLength(in.motion.holderClearance, "holder_clearance");
  if (in.motion.start) {
    requireLength(in.motion.start->x, "start.x");
    requireLength(in.motion.start->y, "start.y");
  }
  for (const Tool& t : in.tools) {
    const std::string name = "tool " + std::to_string(t.id);
    if (t.diameter > kMaxToolDiameter)
      throw Error(name + ": a diameter of " + mm(t.diameter) + " mm is larger than any milling tool (" +
                  mm(kMaxToolDiameter) + " mm at most): is it in mm?");
    for (double v : {t.maxEngagement.value_or(0.0), t.minEngagement.value_or(0.0), t.coreDiameter,
                     t.fluteLength.value_or(0.0), t.cornerRadius, t.stickOut.value_or(0.0),
                     t.holderDiameter.value_or(0.0), t.shankDiameter.value_or(0.0)})
      requireLength(v, name + ": a length of");
  }
  if (!(in.maxPlunges >= 1.0)) throw Error("max_plunges must be at least 1");
  const double n = estimatedPlunges(in);
  if (!(n <= in.maxPlunges)) {
    detail::Bounds box;
    box.add(in.boundary);
    const Vec2 lo = box.lo, hi = box.hi;
    const double r = 0.5 * in.tools.back().diameter;
    const Tool* g = grownTool(in);
    const bool grown = g && n > pocketArea(in) / (kPi * r * r);
    const Tool& t = grown ? *g : in.tools.back();
    std::ostringstream m;
    m.precision(3);
    m << "tool " << t.id << " (diameter " << mm(t.diameter) << " mm";
    if (grown) m << ", engagement limit " << mm(engagementLimit(t)) << " mm";
    m << ") in a " << mm(hi.x - lo.x) << " x " << mm(hi.y - lo.y) << " mm pocket: about "
      << (std::isfinite(n) ? n : 1e308) << (grown ? " plunge-equivalents (grown within the limit), " : " plunges, ")
      << "more than max_plunges (" << std::fixed << std::setprecision(0) << in.maxPlunges << "): "
      << (grown ? "is the limit in mm, or too small for this pocket?" : "is the diameter in mm?");
    throw Error(m.str());
  }
}

PlanningRegion planningRegion(const PlanInput& in) {
  Region full(in.boundary, in.islands);
  double tolerance = 0.0;
  std::optional<Region> coarse = simplifiedRegion(full, kPlanningVertices, kMaxBoundaryTolerance, tolerance);
  return {coarse ? std::move(*coarse) : std::move(full), tolerance};
}

ToolsThatFit toolsThatFit(const std::vector<Tool>& tools, const Region& region, double radialAllowance) {
  ToolsThatFit out;
  std::string dropped;
  for (size_t i = 0; i < tools.size(); ++i) {
    const Tool& t = tools[i];
    if (i + 1 == tools.size() || poly::area(accessibleRegion(region, 0.5 * t.diameter, radialAllowance)) > 0.0) {
      out.tools.push_back(t);
      continue;
    }
    dropped += (dropped.empty() ? "" : ", ") + std::string("T") + std::to_string(t.id) + " (" +
               mm(t.diameter) + " mm)";
  }
  if (!dropped.empty()) out.warning = "tools too large for the pocket, not used: " + dropped;
  return out;
}

}  // namespace plunge
