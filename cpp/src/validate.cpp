#include "validate.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include "depth.hpp"
#include "plunge/error.hpp"
#include "grid.hpp"
#include "limits.hpp"
#include "mesh_floor.hpp"
#include "region.hpp"
#include "plunge/tools.hpp"

namespace plunge {

namespace {

void requireFinite(double v, const std::string& what) {
  if (!std::isfinite(v)) throw Error(what + " is not a finite number");
}

// A real plunge mill's limits (engagement.hpp, motion.hpp); absent is no limit.
void validateMill(const Tool& t, const std::string& name) {
  for (const std::optional<double>& v : {t.maxEngagement, t.minEngagement, t.fluteLength})
    if (v && !(std::isfinite(*v) && *v > 0.0))
      throw Error(name + ": max_engagement, min_engagement and flute_length must be > 0 (leave one out for no limit)");
  for (double v : {t.coreDiameter, t.peckDepth})
    if (!std::isfinite(v) || v < 0.0) throw Error(name + ": core_diameter and peck_depth must be >= 0");
  if (t.peckDepth > 0.0 && t.peckDepth < 0.1 * t.diameter)
    throw Error(name + ".peck_depth is below 10 % of the diameter: a hole would take too many pecks (is it in mm?)");
  if (t.maxEngagement && *t.maxEngagement < 0.05 * t.diameter)
    throw Error(name + ".max_engagement is below 5 % of the diameter: too many plunges to plan (is it in mm?)");
  if (t.minEngagement.value_or(0.0) >= t.diameter) throw Error(name + ".min_engagement must be below the diameter");
  if (t.maxEngagement && t.minEngagement.value_or(0.0) > *t.maxEngagement)
    throw Error(name + ".min_engagement is above its max_engagement");
  if (t.centerCutting && t.coreDiameter > 0.0)
    throw Error(name + ".core_diameter is for tools that do not cut at the centre (\"center_cutting\": false)");
  if (!t.centerCutting && !(t.coreDiameter > 0.0 && t.coreDiameter < 0.9 * t.diameter))
    throw Error(name + ": a tool that does not cut at the centre needs its core_diameter, above 0 and below 90 % of"
                       " the diameter");
  if (t.fluteLength && *t.fluteLength <= cutterProfile(cutterOf(t), 0.5 * t.diameter) + 0.1)
    throw Error(name + ".flute_length must exceed the corner radius by 0.1 mm or more");
  // What holds it (holder.hpp).
  for (const std::optional<double>& v : {t.stickOut, t.holderDiameter, t.shankDiameter})
    if (v && !(std::isfinite(*v) && *v > 0.0))
      throw Error(name + ": stick_out, holder_diameter and shank_diameter must be > 0 (leave one out if not known)");
  if ((t.holderDiameter || t.shankDiameter) && !t.stickOut)
    throw Error(name + ": holder_diameter and shank_diameter need the stick_out (mm from the tip to the holder's face)");
  if (t.stickOut && t.fluteLength && *t.stickOut < *t.fluteLength)
    throw Error(name + ".stick_out is shorter than its flute_length: the holder's face would be on the flutes");
  if (t.shankDiameter && *t.shankDiameter > t.diameter && !t.fluteLength)
    throw Error(name + ".shank_diameter is wider than the cutter: its flute_length must say where the shank starts");
}

// Each tool's numbers, then the tools sorted largest first.
void validateTools(PlanInput& in) {
  if (in.tools.empty()) throw Error(in.choice.automatic ? "tool_library: at least one tool is required"
                                                 : "tools: at least one tool is required");
  std::set<int> ids;
  std::set<double> diameters;
  for (size_t i = 0; i < in.tools.size(); ++i) {
    const Tool& t = in.tools[i];
    const std::string name = (in.choice.automatic ? "tool_library[" : "tools[") + std::to_string(i) + "]";
    requireFinite(t.diameter, name + ".diameter");
    if (t.diameter <= 0.0) throw Error(name + ".diameter must be > 0");
    requireFinite(t.feed, name + ".feed");
    if (t.feed <= 0.0) throw Error(name + ".feed must be > 0");
    if (t.id <= 0 || t.id > kMaxToolId)
      throw Error(name + ".id must be a positive integer up to " + std::to_string(kMaxToolId));
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
    validateMill(t, name);
  }
  std::stable_sort(in.tools.begin(), in.tools.end(),
                   [](const Tool& a, const Tool& b) { return a.diameter > b.diameter; });
  for (const Tool& t : in.tools)
    if (!t.centerCutting) startHoleTool(in.tools, t);  // throws naming the fix
}

// Heights and the floor.
void validateHeights(const PlanInput& in) {
  requireFinite(in.topZ, "top_z");
  requireFinite(in.safeZ, "safe_z");
  requireFinite(in.radialAllowance, "allowance.radial");
  requireFinite(in.floorAllowance, "allowance.floor");
  if (in.radialAllowance < 0.0) throw Error("allowance.radial must be >= 0");
  if (in.floorAllowance < 0.0) throw Error("allowance.floor must be >= 0");
  if (in.safeZ <= in.topZ) throw Error("safe_z must be above top_z");
  if (in.floor.surface.kind == Floor::Kind::Flat) {
    requireFinite(in.floor.surface.z, "floor.z");
    if (in.floor.surface.z + in.floorAllowance >= in.topZ)
      throw Error("floor.z plus the floor allowance must be below top_z");
  } else if (in.floor.surface.kind == Floor::Kind::Expression && in.floor.surface.expression.empty()) {
    throw Error("floor.expression is empty");
  } else if (in.floor.surface.kind == Floor::Kind::Brep && in.floor.surface.brep.empty()) {
    throw Error("floor.brep: no file name");
  }
  for (size_t k = 0; k < in.floor.sections.size(); ++k) {
    const std::string name = "sections[" + std::to_string(k) + "]";
    requireFinite(in.floor.sections[k].z, name + ".z");
    if (in.floor.sections[k].z >= in.topZ) throw Error(name + ".z must be below top_z");
    try {
      const Region check(in.floor.sections[k].boundary, in.floor.sections[k].islands);
    } catch (const Error& e) {
      throw Error(name + ": " + e.what());
    }
  }
  if (in.part) checkMesh(*in.part, "part.mesh");
  if (in.floor.finalDepth) {
    requireFinite(*in.floor.finalDepth, "final_depth");
    if (*in.floor.finalDepth + in.floorAllowance >= in.topZ)
      throw Error("final_depth plus the floor allowance must be below top_z");
  }
}

// The options of the tool choice, the time model, the grid, covering and stock.
void validateOptions(const PlanInput& in) {
  checkGridStep(in.packing.gridStep);
  for (double v : {in.motion.timeModel.rapidRate, in.motion.timeModel.retractRate})
    if (!std::isfinite(v) || v <= 0.0) throw Error("time_model: rapid_rate and retract_rate must be > 0");
  if (!std::isfinite(in.motion.timeModel.toolChangeSeconds) || in.motion.timeModel.toolChangeSeconds < 0.0)
    throw Error("time_model.tool_change_seconds must be >= 0");
  const SelectionOptions& so = in.choice.weights;
  if (!std::isfinite(so.weightTime) || !std::isfinite(so.weightTools) || so.weightTime < 0 || so.weightTools < 0 ||
      so.weightTime + so.weightTools <= 0)
    throw Error("selection: weight_time and weight_tools must be >= 0, not both 0");
  if (!std::isfinite(so.riseFactor) || so.riseFactor <= 1.0) throw Error("selection.rise_factor must be > 1");
  requireFinite(in.covering.minCoverage, "min_coverage");
  if (!(in.covering.minCoverage > 0.0 && in.covering.minCoverage <= 1.0)) throw Error("min_coverage must be in (0, 1]");
  requireFinite(in.packing.contactRatio, "contact_ratio");
  if (!(in.packing.contactRatio >= 0.5 && in.packing.contactRatio <= 1.0)) throw Error("contact_ratio must be in [0.5, 1]");
  requireFinite(in.covering.maxWallStock, "max_wall_stock");
  if (in.covering.maxWallStock < 0.0) throw Error("max_wall_stock must be >= 0 (0: cover down to min_coverage)");
  requireFinite(in.floor.maxFloorStock, "max_floor_stock");
  if (in.floor.maxFloorStock < 0.0) throw Error("max_floor_stock must be >= 0 (0: no floor-stock plunges)");
  requireFinite(in.motion.leadOut, "lead_out");
  if (in.motion.leadOut < 0.0) throw Error("lead_out must be >= 0 (0: retract straight up)");
  requireFinite(in.motion.rapidClearance, "rapid_clearance");
  if (in.motion.rapidClearance <= 0.0) throw Error("rapid_clearance must be > 0");
  requireFinite(in.motion.holderClearance, "holder_clearance");
  if (in.motion.holderClearance < 0.0) throw Error("holder_clearance must be >= 0");
  requireFinite(in.motion.peckDwell, "peck_dwell");
  if (in.motion.peckDwell < 0.0) throw Error("peck_dwell must be >= 0 (seconds; 0: no dwell)");
  if (in.motion.start) {
    requireFinite(in.motion.start->x, "start.x");
    requireFinite(in.motion.start->y, "start.y");
  }
  requireFinite(in.maxPlunges, "max_plunges");
}

}  // namespace

void validate(PlanInput& in) {
  validateTools(in);
  validateHeights(in);
  validateOptions(in);
  checkScale(in);
}

std::string resolveInputPath(const PlanInput& in, const std::string& path) {
  const std::filesystem::path p(path);
  if (p.is_absolute() || in.baseDir.empty()) return p.string();
  return (std::filesystem::path(in.baseDir) / p).string();
}

}  // namespace plunge
