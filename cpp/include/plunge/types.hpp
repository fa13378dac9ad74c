// The data model every layer shares (docs/plan-format.md): tools, the floor,
// the plan's input and options, plunges, statistics and the plan. Plain values
// with no behaviour; it depends on geometry alone, so that every module can take
// these types without including the pipeline (plan.hpp).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "plunge/geometry.hpp"

namespace plunge {

// --- tools ---------------------------------------------------------------------

enum class CutterShape { Flat, Ball, Bull };

struct Cutter {
  CutterShape shape = CutterShape::Flat;
  double radius = 0.0;
  double cornerRadius = 0.0;  // bull nose; a ball's is its radius, a flat one's 0
};

struct Tool {
  double diameter = 0.0;
  int id = 0;             // tool number in G-code
  double feed = 200.0;    // plunge feed, mm/min
  // "spindle_speed": rev/min, written as S (G-code only; absent: from
  // kDefaultCuttingSpeed, tools.hpp spindleSpeedOf).
  std::optional<double> spindleSpeed = std::nullopt;
  CutterShape shape = CutterShape::Flat;
  double cornerRadius = 0.0;  // bull nose only
  // A real plunge mill (engagement.hpp, motion.hpp); no limit is an absent value.
  std::optional<double> maxEngagement = std::nullopt;  // "max_engagement": widest radial band one plunge may cut, mm
  std::optional<double> minEngagement = std::nullopt;  // "min_engagement": narrower cuts deflect the tool into the hole beside
  bool centerCutting = true;   // "center_cutting": false for indexable plunge cutters
  double coreDiameter = 0.0;   // "core_diameter": the part of a non-centre-cutting tool that does not cut
  std::optional<double> fluteLength = std::nullopt;  // "flute_length": deepest cut in one plunge, mm
  // "peck_depth": a hole drilled into solid deeper than this is pecked, mm
  // (0: three diameters, what plunge-mill makers advise; tools.hpp peckDepthOf).
  double peckDepth = 0.0;
  // What holds it (holder.hpp): "stick_out", mm from the tip to the holder's
  // face (absent: not checked); "holder_diameter" (absent with a stick-out:
  // as wide as the pocket); "shank_diameter", from the flutes' top to the
  // holder (absent: the cutting diameter).
  std::optional<double> stickOut = std::nullopt;
  std::optional<double> holderDiameter = std::nullopt;
  std::optional<double> shankDiameter = std::nullopt;
};

// --- the input's options ------------------------------------------------------

// "strategy": pack and cover (the thesis) or a fixed grid (grid.hpp).
enum class Strategy { Packing, Grid };

// Which corner placement comes next.
enum class PackingOrder {
  // The thesis: maximum hole degree, ties by lowest y then x.
  HoleDegree,
  // Placements on one hexagonal lattice (spacing 2 x contact radius, anchored at
  // the first circle and aligned with its longer wall) first, then maximum hole
  // degree. Fronts growing around islands stay in phase, so the interior stays
  // the thinnest covering lattice instead of breaking into patches whose holes
  // each cost a gap plunge.
  Lattice,
  // Both, in parallel, keeping the plan with fewer plunges: a choice of the plan
  // pipeline (plan.cpp); packMaxHoleDegree itself takes HoleDegree or Lattice.
  Auto,
};

// What an engagement-limited tool grows along inside its contour (engagement.hpp).
enum class GrowthPattern {
  Rows,     // rows along the region's long axis (what plunge-mill makers prescribe)
  Offsets,  // offsets of the contour, loopSpacing apart, each entered by a bridge
  // Both, keeping for each tool the one with fewer plunges (a start into solid
  // counted twice): a choice of the growth (engagement.cpp).
  Auto,
};

enum class TourMethod {
  LocalSearch,  // construction + 2-opt/Or-opt + iterated local search (default)
  Annealing,    // the thesis: simulated annealing on 2-opt moves
};


enum class GridPattern { Square, Honeycomb };

// The time model behind the tool choice and the plan's estimate (selection.hpp,
// motion.hpp), and the choice's weights.
struct TimeModel {
  double rapidRate = 10000.0;       // mm/min, XY moves between plunges
  double retractRate = 5000.0;      // mm/min, back up to the safe height
  double toolChangeSeconds = 20.0;  // per tool used
};

struct SelectionOptions {
  double weightTime = 1.0;   // weights of the thesis's weighted time (minutes)
  double weightTools = 0.0;  // ... and of the number of tools
  double riseFactor = 1.5;   // neck: clearance rises this much on both sides
};

// --- the input -----------------------------------------------------------------

// Faces given as triangles (the FreeCAD addon's tessellation): the floor's
// ("floor": {"mesh"}) or the part's around the pocket ("part": {"mesh"}).
// Vertices (x, y, z), triangles as three vertex indices, and how far the true
// surface may lie from them: one distance for every triangle, or one per
// triangle. Every stop is kept that much further off (mesh_floor.hpp).
struct TriangleMesh {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<double> deviation{0.0};
};

struct Floor {
  enum class Kind { Flat, Expression, Brep, Mesh } kind = Kind::Flat;
  double z = 0.0;
  std::string expression;
  std::string brep;  // a BREP file; a relative path starts at PlanInput::baseDir (resolveInputPath)
  TriangleMesh mesh;
};

// The pocket's cross-section at a height above its floor, where it is wider
// than the floor's outline (fillets and corner blends left to the finisher,
// drafted walls): "sections" (plan.cpp, wallBandAbove).
struct Section {
  double z = 0.0;
  Loop boundary;
  std::vector<Loop> islands;
};

// The input's options, one group per stage (docs/plan-format.md names each
// key). PlanInput holds them whole; a stage reads its own group and the job.

// Where plunges go: "strategy", "packing_order", "contact_ratio", "grid".
struct PackingSettings {
  Strategy strategy = Strategy::Packing;
  // "hole_degree" (the thesis), "lattice", or "auto": both, keep the better plan.
  PackingOrder order = PackingOrder::Auto;
  double contactRatio = 0.86;  // packing tangency radius / tool radius
  // "grid": {"pattern": "honeycomb" | "square", "step": fraction of the diameter}.
  GridPattern gridPattern = GridPattern::Honeycomb;
  double gridStep = 0.0;
};

// What must be cut (stock.hpp): "max_wall_stock", mm beyond the radial
// allowance: every point farther from the walls is cut (0: cover down to
// "min_coverage" instead).
struct CoveringSettings {
  double maxWallStock = 1.0;
  double minCoverage = 0.996;
};

// "growth_pattern": what a limited tool grows along, "rows", "offsets" or
// "auto": both, per tool the better (engagement.hpp).
struct EngagementSettings {
  GrowthPattern pattern = GrowthPattern::Auto;
};

// The machine's moves (motion.hpp, sequencing.hpp). "lead_out": horizontal
// move toward cleared space before each retract, mm (0: none).
// "stock_aware_heights": rapid down to "rapid_clearance" above the stock
// still there and retract only as high as the next move needs; false: every
// move at safe_z. "peck": holes into solid deeper than their tool's peck
// depth are pecked; "peck_dwell": seconds at the bottom of each.
// "coolant": "off", "flood" (M8) or "mist" (M7), on with the spindle.
enum class Coolant { Off, Flood, Mist };

struct MotionSettings {
  double leadOut = 0.5;
  bool stockAwareHeights = true;
  double rapidClearance = 1.0;
  double holderClearance = 1.0;  // "holder_clearance": what a shank or holder keeps from the stock (holder.hpp)
  bool peck = true;
  double peckDwell = 0.0;
  TourMethod sequencing = TourMethod::LocalSearch;  // "sequencing": or "annealing" (the thesis)
  std::optional<Vec2> start;  // "start": where the machine starts (default: first boundary point)
  TimeModel timeModel;        // "time_model": {"rapid_rate", "retract_rate", "tool_change_seconds"}
  Coolant coolant = Coolant::Off;  // "coolant": written with the spindle (G-code only)
};

// The floor and what stays on it (floor.hpp, stock.hpp). "max_floor_stock",
// mm above floor + floor allowance: plunges are added where a sculptured
// floor keeps more (0: none added). "final_depth": no plunge stops below it
// + the floor allowance (FreeCAD: the operation's final depth; absent: the
// floor alone decides). "sections": the pocket wider above its floor; at each
// the wall band is kept too, by plunges stopping at that height.
struct FloorSettings {
  Floor surface;
  double maxFloorStock = 1.0;
  std::optional<double> finalDepth;
  std::vector<Section> sections;
};

// "tools": "auto": the plungers are chosen from "tool_library" (selection.hpp).
struct ToolChoice {
  bool automatic = false;
  std::vector<Tool> library;
  SelectionOptions weights;  // "selection": {"weight_time", "weight_tools", "rise_factor"}
};

// The material before this operation, for rest plunging ("material" in the
// plan input): the top of the material over a raster in the plan's
// coordinates, each cell holding the material at its centre. Cell
// (i, j) is the square from origin + (i, j) spacing to origin + (i + 1, j + 1)
// spacing; `top` is row-major (i fastest, nx * ny values). Beyond the raster,
// and wherever it is higher, the material stands at top_z. Absent: the stock
// is solid up to top_z everywhere.
struct MaterialGrid {
  Vec2 origin;
  double spacing = 0.0;
  size_t nx = 0, ny = 0;
  std::vector<double> top;
};

struct PlanInput {
  // The job every stage reads: the pocket, its heights and allowances.
  Loop boundary;
  std::vector<Loop> islands;
  double topZ = 0.0;
  std::optional<MaterialGrid> material;  // what the operations before left (material.hpp)
  // "part": {"mesh"}: the part's faces within reach of the pocket (part.hpp):
  // no stop enters them, and what of them overhangs the floor no plunge goes under.
  std::optional<TriangleMesh> part;
  double safeZ = 5.0;
  double radialAllowance = 0.0;
  double floorAllowance = 0.0;
  std::uint64_t seed = 0;
  double maxPlunges = 200000;  // "max_plunges": refuse inputs estimated to need more (limits.hpp)
  // Where a relative floor.brep path starts: the input file's folder when read
  // from a file (readPlanInput), otherwise (empty) the current directory.
  std::string baseDir;
  // What reading the input migrated from an old spelling: the plan's first warnings.
  std::vector<std::string> notes;
  std::vector<Tool> tools;  // sorted by decreasing diameter once validated
  // Each stage's own options.
  ToolChoice choice;
  PackingSettings packing;
  CoveringSettings covering;
  EngagementSettings engagement;
  FloorSettings floor;
  MotionSettings motion;
};

// --- the plan --------------------------------------------------------------------

struct Plunge {
  double x = 0.0, y = 0.0;
  double diameter = 0.0;
  int toolId = 0;
  double z = 0.0;
  // How the machine gets there and away (motion.hpp): rapid down to approachZ,
  // feed to z, feed to leadOut (if any), rapid up to retractZ and on to the next
  // plunge at that height (through `via`). A plunge deeper than those around it (a hollow of a
  // sculptured floor) first feeds up to leadOutZ, where its way out clears their
  // steps and the floor.
  double approachZ = 0.0;
  double retractZ = 0.0;
  std::optional<Vec2> leadOut;
  std::optional<double> leadOutZ;  // above z, or none: the lead-out is at z
  // The way to the next plunge at retractZ, when going around standing
  // material (a wall's cusps) is quicker than climbing over it: the points
  // between, in order (none: straight).
  std::vector<Vec2> via;
  bool startHole = false;   // a centre-cutting hole for a non-centre-cutting plunger
  bool start = false;       // into solid (centre-cutting) or a start hole: no engagement limit
  double engagement = 0.0;  // radial engagement met, mm (engagement.hpp)
  int level = 0;            // 0 for the first level (flute length, motion.hpp)
  // A hole drilled into solid deeper than its tool's peck depth: the depths
  // (above z, deepest last) where the tool stops, rapids up out of the hole to
  // clear the chips and rapids back to just above that depth (motion.hpp).
  std::vector<double> pecks;
  bool forFloorStock = false;  // added by the floor-stock step (stats.floor_stock_plunges; not in the JSON)
  bool holderLimited = false;  // stopped above its depth where the holder or shank clears (holder.hpp)
};

struct ToolCount {
  int toolId = 0;
  double diameter = 0.0;
  int count = 0;
  double peckDepth = 0.0;  // its holes into solid are pecked this deep (tools.hpp peckDepthOf)
  // The tool as mounted, as the plan used it (Tool's fields of the same names).
  std::optional<double> stickOut, holderDiameter, shankDiameter;
  int holderLimited = 0;  // its plunges stopped above their depth by the holder or shank
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
  // With "material": what the operations before left in the pocket (down to
  // floor + allowance), and the plunges the covering placed that would have cut
  // none of it (not made; their disks count as covered).
  double volumeBefore = 0.0;  // mm^3
  int airPlunges = 0;
  bool restMaterial = false;  // planned from a "material" input
  int floorStockPlunges = 0;  // plunges of the plan the floor-stock step added (a limited tool's growth replaces them)
  // Real plunge mills (engagement.hpp, motion.hpp).
  int startHoles = 0;           // start holes drilled for non-centre-cutting plungers
  int overEngaged = 0;          // plunges (not starts) cutting wider than their tool's max_engagement
  int thinCuts = 0;             // plunges cutting narrower than their tool's min_engagement
  int leadOuts = 0;             // plunges with a lead-out (motion.hpp)
  int raisedLeadOuts = 0;       // of them, fed up to leadOutZ first (in a ring of steps, motion.hpp)
  int noLeadOutMaterial = 0;    // without one: every way out bites deeper than half the lead-out, or the floor rises
  int noLeadOutWalls = 0;       // without one: no way out keeps the allowance to walls and islands
  int levels = 1;               // most levels any tool needs for its flute length
  double minutesAtSafeHeight = 0.0;  // the time model with every move at safe_z
  double boundaryTolerance = 0.0;  // mm the walls were simplified by (limits.hpp), added to the radial allowance
  // The floor as the planner read it: "flat", "expression", "brep" (faces) or
  // "mesh" (the bundles' program gets a floor of faces as the addon's mesh).
  std::string floorKind;
  int peckedPlunges = 0;   // holes into solid pecked (motion.hpp)
  int depthFallbacks = 0;  // floor faces, edges or plunges whose depth search ran out of budget: sampled densely (depth.hpp)
};

// The floor stock left, sampled on a raster (for the plan's picture).
struct StockMap {
  Vec2 origin;
  double spacing = 0.0;
  size_t nx = 0, ny = 0;
  std::vector<float> stock;  // row-major; NaN where nothing was cut
};

// The automatic tool choice's report (selection.hpp): the pocket's necks and
// sub-regions (medial.hpp) and every tool set tried.
struct Neck {
  Vec2 center;    // the medial node
  double width;   // 2 x its clearance
  Vec2 a, b;      // the neck line: the two nearest wall points
  bool island;    // one end on an island
};

struct SubRegion {
  Polygons shape;
  double area = 0.0;
  Circle inscribed;                 // largest disk inside it
  std::vector<int> necks;           // indices of the necks on its border
};

struct ToolSetResult {
  std::vector<double> diameters;
  bool evaluated = false;  // planned in full; otherwise estimated (plunges > 0) or pruned by its bound
  bool subtree = false;    // pruned with every set that adds smaller candidates to it
  int plunges = 0;          // of the plan, or the positions placed for the estimate
  double coverage = 0.0;
  double minutes = 0.0;     // planned time, the estimate (5.3) when only placed, the lower bound when pruned
  double estimate = 0.0;    // the estimate of a set then planned (evaluated)
  double weighted = 0.0;
  double bound = 0.0;       // the branch and bound's lower bound on `weighted`
  std::string refused;      // why this set cannot be planned (not evaluated, not pruned)
};

struct ToolSelection {
  Circle inscribed;
  std::vector<Neck> necks;
  std::vector<SubRegion> parts;
  std::vector<int> order;  // sub-region visiting order (MST)
  std::vector<double> candidates;
  std::vector<ToolSetResult> sets;
  std::vector<double> chosen;
  std::vector<std::string> reasoning;
};

// A limit the user set that the plan cannot keep: which, how far, where and
// why (docs/plan-format.md, "broken_limits"). Each is a warning too.
struct BrokenLimit {
  // The input's key: "max_wall_stock", "max_floor_stock", "min_coverage",
  // "max_engagement", "min_engagement", "core_diameter" or "flute_length".
  std::string limit;
  double asked = 0.0;  // the limit (mm; min_coverage a fraction)
  double worst = 0.0;  // the worst the plan comes to, in the same unit
  Vec2 at;             // where that is
  int count = 1;       // plunges (or places) beyond the limit
  std::string why;     // what stops the plan keeping it, and what would
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
  std::vector<BrokenLimit> broken;   // the limits it could not keep (each also a warning)
  std::optional<StockMap> stockMap;  // sculptured floors only
};

}  // namespace plunge
