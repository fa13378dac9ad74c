// The plan pipeline: input to plunges and statistics (docs/plan-format.md):
// region, packing, covering, sequencing, depths.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "plunge/depth.hpp"
#include "plunge/geometry.hpp"
#include "plunge/grid.hpp"
#include "plunge/packing.hpp"
#include "plunge/progress.hpp"
#include "plunge/region.hpp"
#include "plunge/selection.hpp"
#include "plunge/sequencing.hpp"

namespace plunge {

struct Tool {
  double diameter = 0.0;
  int id = 0;             // tool number in G-code
  double feed = 200.0;    // plunge feed, mm/min
  CutterShape shape = CutterShape::Flat;
  double cornerRadius = 0.0;  // bull nose only
  // A real plunge mill (engagement.hpp, motion.hpp); 0 means no limit.
  double maxEngagement = 0.0;  // "max_engagement": widest radial band one plunge may cut, mm
  double minEngagement = 0.0;  // "min_engagement": narrower cuts deflect the tool into the hole beside
  bool centerCutting = true;   // "center_cutting": false for indexable plunge cutters
  double coreDiameter = 0.0;   // "core_diameter": the part of a non-centre-cutting tool that does not cut
  double fluteLength = 0.0;    // "flute_length": deepest cut in one plunge, mm
};

// "strategy": pack and cover (the thesis) or a fixed grid (grid.hpp).
enum class Strategy { Packing, Grid };

struct Floor {
  enum class Kind { Flat, Expression, Brep } kind = Kind::Flat;
  double z = 0.0;
  std::string expression;
  std::string brep;  // a BREP file; a relative path starts at PlanInput::baseDir (resolveInputPath)
};

struct PlanInput {
  Loop boundary;
  std::vector<Loop> islands;
  std::vector<Tool> tools;  // sorted by decreasing diameter once validated
  double topZ = 0.0;
  double safeZ = 5.0;
  Floor floor;
  double radialAllowance = 0.0;
  double floorAllowance = 0.0;
  Strategy strategy = Strategy::Packing;
  std::uint64_t seed = 0;
  // Extensions beyond the contract (all optional in JSON):
  double minCoverage = 0.996;  // "min_coverage": stop covering wall material here
  double contactRatio = 0.86;  // "contact_ratio": packing tangency radius / tool radius
  // "packing_order": "hole_degree" (the thesis), "lattice", or "auto": both, keep the better plan.
  PackingOrder packingOrder = PackingOrder::Auto;
  std::optional<Vec2> start;   // "start": where the machine starts (default: first boundary point)
  TourMethod sequencing = TourMethod::LocalSearch;  // "sequencing": or "annealing" (the thesis)
  // Where a relative floor.brep path starts: the input file's folder when read
  // from a file (readPlanInput), otherwise (empty) the current directory.
  std::string baseDir;
  // "tools": "auto": the plungers are chosen from `library` ("tool_library").
  bool autoTools = false;
  std::vector<Tool> library;
  SelectionOptions selection;  // "selection": {"weight_time", "weight_tools", "rise_factor"}
  TimeModel timeModel;         // "time_model": {"rapid_rate", "retract_rate", "tool_change_seconds"}
  // "strategy": "grid" with "grid": {"pattern": "honeycomb" | "square", "step": fraction of the diameter}.
  GridPattern gridPattern = GridPattern::Honeycomb;
  double gridStep = 0.0;
  // Stock left for the finisher (stock.hpp): "max_wall_stock", mm beyond the
  // radial allowance: every point farther from the walls is cut (0: cover down
  // to min_coverage instead). "max_floor_stock", mm above floor + floor
  // allowance: plunges are added where a sculptured floor keeps more (0: none added).
  double maxWallStock = 1.0;
  double maxFloorStock = 1.0;
  // Motion of a real machine (motion.hpp). "lead_out": horizontal move toward
  // cleared space before each retract, mm (0: none). "stock_aware_heights":
  // rapid down to "rapid_clearance" above the stock still there and retract
  // only as high as the next move needs; false: every move at safe_z.
  double leadOut = 0.5;
  bool stockAwareHeights = true;
  double rapidClearance = 1.0;
  // "max_plunges": refuse inputs estimated to need more (limits.hpp).
  double maxPlunges = 200000;
  // "final_depth": no plunge stops below final_depth + the floor allowance
  // (FreeCAD: the operation's final depth; absent: the floor alone decides).
  std::optional<double> finalDepth;
};

struct Plunge {
  double x = 0.0, y = 0.0;
  double diameter = 0.0;
  int toolId = 0;
  double z = 0.0;
  // How the machine gets there and away (motion.hpp): rapid down to approachZ,
  // feed to z, feed to leadOut (if any), rapid up to retractZ and on to the next
  // plunge at that height.
  double approachZ = 0.0;
  double retractZ = 0.0;
  std::optional<Vec2> leadOut;
  bool startHole = false;   // a centre-cutting hole for a non-centre-cutting plunger
  bool start = false;       // into solid (centre-cutting) or a start hole: no engagement limit
  double engagement = 0.0;  // radial engagement met, mm (engagement.hpp)
  int level = 0;            // 0 for the first level (flute length, motion.hpp)
};

struct ToolCount {
  int toolId = 0;
  double diameter = 0.0;
  int count = 0;
};

struct PlanStats {
  int plungeCount = 0;
  std::vector<ToolCount> perTool;
  double regionArea = 0.0;      // pocket after the radial allowance
  double accessibleArea = 0.0;  // the part of it the smallest tool reaches
  double coveredArea = 0.0;
  double coverage = 0.0;
  double travelLength = 0.0;
  double planningSeconds = 0.0;
  // Reference: plunges of the largest tool a hexagonal covering of the
  // accessible area would need (area / (2.598 r^2)), a reference count, not a bound.
  double hexReferenceCount = 0.0;
  double estimatedMinutes = 0.0;  // the time model's estimate (selection.hpp)
  // Stock left (stock.hpp). The core: the accessible region farther than
  // allowance + max_wall_stock from the walls (all of it when the band is 0).
  double coreArea = 0.0;
  double coreCoverage = 0.0;
  double maxWallStockLeft = 0.0;   // thickest material left along the walls, beyond the allowance
  double maxFloorStockLeft = 0.0;  // highest stock above floor + allowance where plunges cut
  double meanFloorStock = 0.0;
  double volumeRemoved = 0.0;  // mm^3
  double volumeLeft = 0.0;     // mm^3: the pocket down to floor + allowance, minus what is removed
  int restPlunges = 0;         // plunges added by the rest step in Z
  // Real plunge mills (engagement.hpp, motion.hpp).
  int startHoles = 0;           // start holes drilled for non-centre-cutting plungers
  int overEngaged = 0;          // plunges (not starts) cutting wider than their tool's max_engagement
  int thinCuts = 0;             // plunges cutting narrower than their tool's min_engagement
  int leadOuts = 0;             // plunges with a lead-out (motion.hpp)
  int noLeadOutMaterial = 0;    // without one: every way out bites deeper than half the lead-out, or the floor rises
  int noLeadOutWalls = 0;       // without one: no way out keeps the allowance to walls and islands
  int levels = 1;               // most levels any tool needs for its flute length
  double minutesAtSafeHeight = 0.0;  // the time model with every move at safe_z
  double boundaryTolerance = 0.0;  // mm the walls were simplified by (limits.hpp), added to the radial allowance
};

// The floor stock left, sampled on a raster (for the plan's picture).
struct StockMap {
  Vec2 origin;
  double spacing = 0.0;
  size_t nx = 0, ny = 0;
  std::vector<float> stock;  // row-major; NaN where nothing was cut
};

struct Plan {
  std::vector<Plunge> plunges;  // execution order: tools largest first
  PlanStats stats;
  // For drawing: the accessible region and what the plunges leave uncovered.
  Polygons accessible;
  Polygons uncovered;
  std::optional<ToolSelection> selection;  // with "tools": "auto"
  // What the user should know about a plan that is valid but short of what was
  // asked (for example coverage below min_coverage); JSON "warnings".
  std::vector<std::string> warnings;
  std::optional<StockMap> stockMap;  // sculptured floors only
};

// The cutter shape of a tool (depth.hpp).
Cutter cutterOf(const Tool& tool);
// A plunge of the tool at c stopping at z.
Plunge plungeOf(const Tool& tool, Vec2 c, double z);

// Checks every number of the input (its options are enums, parsed by io.hpp)
// and sorts the tools largest first; throws plunge::Error naming the problem.
void validate(PlanInput& input);

// A path of the input (floor.brep) as the planner opens it: absolute, or relative
// to input.baseDir (the current directory when that is empty).
std::string resolveInputPath(const PlanInput& input, const std::string& path);

// The whole pipeline: validate, then the automatic tool choice (selection.hpp)
// or planWithTools. progress: told how far planning got, and able to cancel it
// (progress.hpp).
Plan plan(PlanInput input, const Progress& progress = Progress());

// The plan of a validated input with its tools given (tools, not "auto"):
// region, packing and covering (or the grid), depths, rest step, sequencing,
// engagement limits, levels, motion and the stock left.
Plan planWithTools(PlanInput input, const Progress& progress = Progress());

}  // namespace plunge
