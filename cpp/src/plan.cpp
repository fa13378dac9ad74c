#include "plunge/plan.hpp"

#include <algorithm>
#include <chrono>
#include <future>
#include <iomanip>
#include <cmath>
#include <set>
#include <sstream>

#include "plunge/covering.hpp"
#include "plunge/depth.hpp"
#include "plunge/error.hpp"
#include "plunge/floor.hpp"
#include "plunge/grid.hpp"
#include "plunge/packing.hpp"
#include "plunge/polygon.hpp"
#include "plunge/sequencing.hpp"

namespace plunge {

namespace {

void requireFinite(double v, const std::string& what) {
  if (!std::isfinite(v)) throw Error(what + " is not a finite number");
}

}  // namespace

void validate(PlanInput& in) {
  if (in.tools.empty()) throw Error(in.autoTools ? "tool_library: at least one tool is required"
                                                 : "tools: at least one tool is required");
  std::set<int> ids;
  std::set<double> diameters;
  for (size_t i = 0; i < in.tools.size(); ++i) {
    const Tool& t = in.tools[i];
    const std::string name = (in.autoTools ? "tool_library[" : "tools[") + std::to_string(i) + "]";
    requireFinite(t.diameter, name + ".diameter");
    if (t.diameter <= 0.0) throw Error(name + ".diameter must be > 0");
    requireFinite(t.feed, name + ".feed");
    if (t.feed <= 0.0) throw Error(name + ".feed must be > 0");
    if (t.id <= 0) throw Error(name + ".id must be a positive integer");
    if (!ids.insert(t.id).second) throw Error(name + ".id " + std::to_string(t.id) + " is used twice");
    if (!diameters.insert(t.diameter).second)
      throw Error(name + ".diameter " + std::to_string(t.diameter) + " is given twice");
    if (t.shape == CutterShape::Bull) {
      requireFinite(t.cornerRadius, name + ".corner_radius");
      if (!(t.cornerRadius > 0 && t.cornerRadius <= t.diameter / 2))
        throw Error(name + ".corner_radius must be > 0 and at most half the diameter");
    } else if (t.cornerRadius != 0.0) {
      throw Error(name + ".corner_radius is for bull-nose tools (\"shape\": \"bull\")");
    }
  }
  std::stable_sort(in.tools.begin(), in.tools.end(),
                   [](const Tool& a, const Tool& b) { return a.diameter > b.diameter; });
  requireFinite(in.topZ, "top_z");
  requireFinite(in.safeZ, "safe_z");
  requireFinite(in.radialAllowance, "allowance.radial");
  requireFinite(in.floorAllowance, "allowance.floor");
  if (in.radialAllowance < 0.0) throw Error("allowance.radial must be >= 0");
  if (in.floorAllowance < 0.0) throw Error("allowance.floor must be >= 0");
  if (in.safeZ <= in.topZ) throw Error("safe_z must be above top_z");
  if (in.floor.kind == Floor::Kind::Flat) {
    requireFinite(in.floor.z, "floor.z");
    if (in.floor.z + in.floorAllowance >= in.topZ)
      throw Error("floor.z plus the floor allowance must be below top_z");
  } else if (in.floor.kind == Floor::Kind::Expression && in.floor.expression.empty()) {
    throw Error("floor.expression is empty");
  } else if (in.floor.kind == Floor::Kind::Brep && in.floor.brep.empty()) {
    throw Error("floor.brep: no file name");
  }
  if (in.strategy != "packing" && in.strategy != "grid")
    throw Error("strategy: unknown strategy '" + in.strategy + "' (use \"packing\" or \"grid\")");
  gridPatternFromName(in.gridPattern);
  requireFinite(in.gridStep, "grid.step");
  if (!(in.gridStep >= 0.0 && in.gridStep <= 1.0)) throw Error("grid.step must be in (0, 1] (a fraction of the diameter)");
  for (double v : {in.timeModel.rapidRate, in.timeModel.retractRate})
    if (!std::isfinite(v) || v <= 0.0) throw Error("time_model: rapid_rate and retract_rate must be > 0");
  if (!std::isfinite(in.timeModel.toolChangeSeconds) || in.timeModel.toolChangeSeconds < 0.0)
    throw Error("time_model.tool_change_seconds must be >= 0");
  const SelectionOptions& so = in.selection;
  if (!std::isfinite(so.weightTime) || !std::isfinite(so.weightTools) || so.weightTime < 0 || so.weightTools < 0 ||
      so.weightTime + so.weightTools <= 0)
    throw Error("selection: weight_time and weight_tools must be >= 0, not both 0");
  if (!std::isfinite(so.riseFactor) || so.riseFactor <= 1.0) throw Error("selection.rise_factor must be > 1");
  if (in.packingOrder != "auto" && in.packingOrder != "hole_degree" && in.packingOrder != "lattice")
    throw Error("packing_order: unknown order '" + in.packingOrder + "' (use \"auto\", \"hole_degree\" or \"lattice\")");
  requireFinite(in.minCoverage, "min_coverage");
  if (!(in.minCoverage > 0.0 && in.minCoverage <= 1.0)) throw Error("min_coverage must be in (0, 1]");
  requireFinite(in.contactRatio, "contact_ratio");
  if (!(in.contactRatio >= 0.5 && in.contactRatio <= 1.0)) throw Error("contact_ratio must be in [0.5, 1]");
  tourMethodFromName(in.sequencing);  // throws for an unknown method
  if (in.start) {
    requireFinite(in.start->x, "start.x");
    requireFinite(in.start->y, "start.y");
  }
}

Plan plan(PlanInput in, const Progress& progress) {
  if (in.autoTools) return planWithToolSelection(in, progress);
  const auto t0 = std::chrono::steady_clock::now();
  progress.stage(0.0, "checking the pocket");
  validate(in);
  const Region region(in.boundary, in.islands);

  std::vector<double> radii;
  for (const Tool& t : in.tools) radii.push_back(0.5 * t.diameter);
  const double rMin = radii.back();

  Plan out;
  out.accessible = accessibleRegion(region, rMin, in.radialAllowance);
  if (poly::area(out.accessible) <= 0.0) {
    throw Error("no tool fits in the pocket: the smallest tool (diameter " + std::to_string(2 * rMin) +
                ") with the radial allowance does not fit anywhere");
  }

  // The floor: flat, an expression or BREP faces (checked before the long part).
  std::unique_ptr<FloorSurface> floor;
  if (in.floor.kind == Floor::Kind::Flat) {
    floor = makeFlatFloor(in.floor.z);
  } else if (in.floor.kind == Floor::Kind::Expression) {
    floor = makeExpressionFloor(in.floor.expression);
  } else {
    const std::string& f = in.floor.brep;
    floor = makeBrepFloor(f.front() == '/' || in.baseDir.empty() ? f : in.baseDir + "/" + f);
  }

  // Pack and cover with each packing order asked for (in parallel: "auto" tries
  // both) and keep the plan with the fewest plunges.
  auto packAndCover = [&](PackingOrder order) {
    PackingOptions po;
    po.allowance = in.radialAllowance;
    po.contactRatio = in.contactRatio;
    po.order = order;
    po.progress = progress;
    CoveringOptions co;
    co.allowance = in.radialAllowance;
    co.minCoverage = in.minCoverage;
    co.progress = progress;
    return coverRegion(region, radii, packMaxHoleDegree(region, radii, po), co);
  };
  CoverResult cover;
  progress.stage(0.05, "packing and covering");
  if (in.strategy == "grid") {
    GridOptions go;
    go.pattern = gridPatternFromName(in.gridPattern);
    go.step = in.gridStep;
    go.allowance = in.radialAllowance;
    go.progress = progress;
    cover = gridPlacements(region, radii, go);
  } else if (in.packingOrder == "hole_degree") {
    cover = packAndCover(PackingOrder::HoleDegree);
  } else if (in.packingOrder == "lattice") {
    cover = packAndCover(PackingOrder::Lattice);
  } else {
    auto lattice = std::async(std::launch::async, packAndCover, PackingOrder::Lattice);
    cover = packAndCover(PackingOrder::HoleDegree);
    CoverResult other = lattice.get();
    if (other.disks.size() < cover.disks.size()) cover = std::move(other);
  }

  // Execution order: tools largest first, each tool's plunges as a short open path
  // starting nearest to where the previous tool ended.
  // Depths (4.4): the floor's peaks once, then each plunge's disk.
  progress.stage(0.75, "ordering the plunges and their depths");
  const Vec2 lo = region.minCorner(), hi = region.maxCorner();
  const DepthSolver depths(*floor, lo, hi, std::max(0.5 * rMin, 1e-3 * dist(lo, hi)));
  Vec2 at = in.start ? *in.start : in.boundary.front();
  TourOptions to;
  to.method = tourMethodFromName(in.sequencing);
  to.seed = in.seed;
  for (size_t t = 0; t < in.tools.size(); ++t) {
    std::vector<Vec2> pts;
    for (const CoverDisk& d : cover.disks)
      if (d.tool == static_cast<int>(t)) pts.push_back(d.center);
    if (pts.empty()) continue;
    const Cutter cutter{in.tools[t].shape, 0.5 * in.tools[t].diameter,
                        in.tools[t].shape == CutterShape::Ball ? 0.5 * in.tools[t].diameter : in.tools[t].cornerRadius};
    for (int i : tour(pts, false, at, to)) {
      progress.tick(0.8 + 0.2 * static_cast<double>(out.plunges.size()) / cover.disks.size());
      const Vec2 p = pts[i];
      const double z = depths.stopHeight(p, cutter) + in.floorAllowance;
      if (z >= in.topZ) {
        std::ostringstream where;
        where << "(" << p.x << ", " << p.y << ")";
        throw Error("the floor rises to top_z or above under the plunge at " + where.str());
      }
      if (!out.plunges.empty()) out.stats.travelLength += dist({out.plunges.back().x, out.plunges.back().y}, p);
      out.plunges.push_back({p.x, p.y, in.tools[t].diameter, in.tools[t].id, z});
      at = p;
    }
    out.stats.perTool.push_back({in.tools[t].id, in.tools[t].diameter, static_cast<int>(pts.size())});
  }

  out.uncovered = cover.uncovered;
  out.stats.plungeCount = static_cast<int>(out.plunges.size());
  out.stats.regionArea = poly::area(allowedRegion(region, in.radialAllowance));
  out.stats.accessibleArea = cover.accessibleArea;
  out.stats.coveredArea = cover.coveredArea;
  out.stats.coverage = cover.accessibleArea > 0 ? cover.coveredArea / cover.accessibleArea : 0.0;
  out.stats.hexReferenceCount = cover.accessibleArea / (1.5 * std::sqrt(3.0) * radii.front() * radii.front());
  // Any strategy short of the coverage asked for says so: the grid's fixed
  // spacing usually is. Worded for users of every front end (no JSON key names).
  if (out.stats.coverage < in.minCoverage - 1e-3) {
    std::ostringstream w;
    w << std::fixed << std::setprecision(2) << "the plunges clear " << 100 * out.stats.coverage
      << " % of the reachable floor, less than the " << 100 * in.minCoverage
      << " % asked for: material stays along the walls";
    if (in.strategy == "grid") w << " (a grid's fixed spacing cannot reach it)";
    out.warnings.push_back(w.str());
  }
  out.stats.estimatedMinutes = estimateMinutes(out, in.tools, in.safeZ, in.timeModel);
  out.stats.planningSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace plunge
