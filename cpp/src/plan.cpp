#include "plunge/plan.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <future>
#include <limits>
#include <memory>
#include <optional>
#include <iomanip>
#include <cmath>
#include <set>
#include <sstream>
#include <tuple>

#include "detail.hpp"
#include "covering.hpp"
#include "depth.hpp"
#include "engagement.hpp"
#include "heightfield.hpp"
#include "holder.hpp"
#include "limits.hpp"
#include "motion.hpp"
#include "plunge/error.hpp"
#include "floor.hpp"
#include "grid.hpp"
#include "mesh_floor.hpp"
#include "packing.hpp"
#include "part.hpp"
#include "part_stock.hpp"
#include "polygon.hpp"
#include "region.hpp"
#include "selection.hpp"
#include "plunge/sequencing.hpp"
#include "stock.hpp"
#include "broken.hpp"
#include "plunge/tools.hpp"
#include "validate.hpp"

namespace plunge {

namespace {

Plan planPlaced(const PlanInput& given, std::optional<CoverResult> positions, const Progress& progress);

// Where each stage of a plan starts on the progress bar: one table, in the
// order planPlaced runs them, so the fraction only rises.
namespace share {
constexpr double kCheck = 0.0, kFloor = 0.02, kPlace = 0.05, kDepths = 0.75, kFloorStock = 0.8, kWallBand = 0.86,
                 kOrder = 0.9, kGrow = 0.92, kReach = 0.93, kMotion = 0.95, kMeasure = 0.98;
}  // namespace share

struct Pocket {
  Region region;
  Polygons accessible;
  Polygons core;  // empty without a wall band
};

// What every stage of planPlaced reads and none changes: the job (as planned:
// pocketOf), its tools, pocket, floor and depths, the material the operations
// before left, the progress, and the area the plunges may cut.
struct Stages {
  const PlanInput& in;
  const ToolTable& tools;
  const Pocket& pocket;
  const FloorSurface& floor;
  const DepthSolver& depths;
  const Material& material;
  const Progress& progress;
  double regionArea;
};

// Plunge positions and their stop heights (placeAndDepth).
struct Placed {
  std::vector<CutDisk> disks;
  bool finalDepthHeld = false;  // the final depth raised a plunge above the floor
  bool floorStockOutOfBudget = false;  // the floor-stock step stopped at its budget (stock.hpp)
};

// The tools' radii, in the tools' order: what packing and covering pack (they
// answer with an index into it).
std::vector<double> radiiOf(const std::vector<Tool>& tools) {
  std::vector<double> radii;
  for (const Tool& t : tools) radii.push_back(0.5 * t.diameter);
  return radii;
}

// The covering's options from the input, filled in one place. Every covering
// of a plan adds disks to measure them later on the final plunges (coverOf):
// none measures its own core.
CoveringOptions coveringOptions(const PlanInput& in, const Progress& progress) {
  CoveringOptions co;
  co.allowance = in.radialAllowance;
  co.minCoverage = in.covering.minCoverage;
  co.maxWallStock = in.covering.maxWallStock;
  co.measureCore = false;
  co.progress = progress;
  return co;
}

std::unique_ptr<FloorSurface> makeFloor(const PlanInput& in) {
  if (in.floor.surface.kind == Floor::Kind::Flat) return makeFlatFloor(in.floor.surface.z);
  if (in.floor.surface.kind == Floor::Kind::Expression) return makeExpressionFloor(in.floor.surface.expression);
  if (in.floor.surface.kind == Floor::Kind::Mesh) return makeMeshFloor(in.floor.surface.mesh);
  return makeBrepFloor(resolveInputPath(in, in.floor.surface.brep));
}

// The floor kind's name in the plan (PlanStats::floorKind).
const char* floorKindName(Floor::Kind kind) {
  switch (kind) {
    case Floor::Kind::Flat: return "flat";
    case Floor::Kind::Expression: return "expression";
    case Floor::Kind::Brep: return "brep";
    case Floor::Kind::Mesh: return "mesh";
  }
  return "";
}

// A floor or a plunger that is not flat: plunges stop at different heights.
bool isSculptured(const PlanInput& in, const FloorSurface& floor) {
  return !floor.isFlat() || std::any_of(in.tools.begin(), in.tools.end(),
                                        [](const Tool& t) { return t.shape != CutterShape::Flat; });
}

// See placePlunges: more of the core out of the packed tool's reach than this
// many disks of the next tool means packing that one instead (a 150 mm plunger
// in the 600 x 400 mm benchmark leaves 650 disks of its 12 mm one, a 100 mm
// one 110, a 10 mm one in an 80 x 60 mm pocket 2 of its 1 mm one).
constexpr double kGreedyDisks = 200.0;

// The depth solver's cells (depth.hpp): a quarter of the smallest tool's
// diameter, but no finer than this fraction of the pocket's diagonal.
constexpr double kDepthCellFraction = 1e-3;
// Coverage short of min_coverage by less than this is rounding, not worth a warning.
constexpr double kCoverageSlack = 1e-3;
// Uncovered pieces smaller than this (mm^2) are the polygons' chords, not stock (stock.hpp wallStockLeft).
constexpr double kSliverArea = 0.01;
// Wall stock over max_wall_stock by less than this is the polygons' arcs.
constexpr double kWallStockSlack = 0.01;
// "Just below" a section, where the part standing in the pocket is looked for
// (mm): a hair below the 0.02 mm the addon takes a section above an island's
// top, and no lower (the walls that lean in are measured from there).
constexpr double kJustBelow = 0.0201;

// The area of the core that neither the packed disks cut nor a tool of radius
// r can reach (what smaller tools must cover).
double coreOutOfReach(const Region& region, double r, double allowance, const Polygons& core,
                      const std::vector<PackedDisk>& packed) {
  std::vector<Circle> disks;
  for (const PackedDisk& d : packed) disks.push_back({d.center, d.radius});
  return poly::area(poly::subtract(poly::subtract(core, poly::unionOfDisks(disks, 0.05)),
                                   accessibleRegion(region, r, allowance)));
}

// Packing and covering, or the grid: the plunge positions of every tool.
CoverResult placePlunges(const PlanInput& in, const Region& region, const std::vector<double>& radii,
                         const Polygons& core, const Progress& progress) {
  if (in.packing.strategy == Strategy::Grid) {
    GridOptions go;
    go.pattern = in.packing.gridPattern;
    go.step = in.packing.gridStep;
    go.allowance = in.radialAllowance;
    go.progress = progress;
    return gridPlacements(region, radii, go);
  }
  // Pack and cover with each packing order asked for (in parallel: "auto" tries
  // both) and keep the plan with the fewest plunges.
  auto packAndCover = [&](PackingOrder order) {
    PackingOptions po;
    po.allowance = in.radialAllowance;
    po.contactRatio = in.packing.contactRatio;
    po.order = order;
    po.maxWallStock = in.covering.maxWallStock;
    po.progress = progress;
    const CoveringOptions co = coveringOptions(in, progress);
    if (in.covering.maxWallStock <= 0.0) return coverRegion(region, radii, packMaxHoleDegree(region, radii, po), co);
    // With a wall band, only the largest tool is packed: the covering then uses a
    // smaller plunger only where the larger ones cannot reach the core. Unless
    // the largest leaves more of the core out of its reach than kGreedyDisks
    // disks of the next (a tool nearly as large as the pocket): then the next is
    // packed instead, or the covering would place thousands of plunges one
    // greedy step at a time. (Not the whole core left: the largest tool covers
    // what it reaches in few steps, and a much smaller next tool must not take
    // over the pocket.)
    std::vector<PackedDisk> packed;
    for (size_t k = 0; k < radii.size(); ++k) {
      packed = packWithWallBand(region, radii[k], po);
      for (PackedDisk& d : packed) d.tool = static_cast<int>(k);
      if (k + 1 == radii.size() ||
          coreOutOfReach(region, radii[k], in.radialAllowance, core, packed) <=
              kGreedyDisks * kPi * radii[k + 1] * radii[k + 1])
        break;
    }
    return coverRegion(region, radii, packed, co);
  };
  if (in.packing.order != PackingOrder::Auto) return packAndCover(in.packing.order);
  auto lattice = std::async(std::launch::async, packAndCover, PackingOrder::Lattice);
  CoverResult cover = packAndCover(PackingOrder::HoleDegree);
  CoverResult other = progress.await(lattice);
  if (other.disks.size() < cover.disks.size()) cover = std::move(other);
  return cover;
}

// Each plunge's stop height (4.4): the floor's peaks once, then each disk.
std::vector<CutDisk> depthsOf(const PlanInput& in, const CoverResult& cover, const DepthSolver& depths,
                              const Progress& progress) {
  std::vector<CutDisk> out;
  for (const CoverDisk& d : cover.disks) {
    progress.tick(share::kDepths + (share::kFloorStock - share::kDepths) * out.size() / cover.disks.size());
    // The packing and covering answer with an index into the radii they were
    // given (the tools in order); from here on a plunge knows its tool by id.
    const Tool& tool = in.tools[d.tool];
    const double z = depths.plungeHeight(d.center, cutterOf(tool), in.floorAllowance, in.radialAllowance);
    if (z >= in.topZ)
      throw Error("the floor rises to top_z or above under the plunge at " + detail::formatPoint(d.center));
    out.push_back({d.center, tool.id, z});
  }
  return out;
}

// Execution order: tools largest first, each tool's plunges as a short open path
// starting nearest to where the previous tool ended.
std::vector<Plunge> sequence(const Stages& job, const std::vector<CutDisk>& disks) {
  const PlanInput& in = job.in;
  const Progress& progress = job.progress;  // (a lambda captures it: no structured binding)
  std::vector<Plunge> out;
  Vec2 at = in.motion.start ? *in.motion.start : in.boundary.front();
  TourOptions to;
  to.method = in.motion.sequencing;
  to.seed = in.seed;
  to.poll = [&progress] { progress.tick(); };
  for (const Tool& tool : job.tools.all()) {
    std::vector<const CutDisk*> mine;
    std::vector<Vec2> pts;
    for (const CutDisk& d : disks)
      if (d.toolId == tool.id) {
        mine.push_back(&d);
        pts.push_back(d.center);
      }
    if (pts.empty()) continue;
    for (int i : tour(pts, false, at, to)) {
      const Vec2 p = pts[i];
      out.push_back(plungeOf(tool, p, mine[i]->z));
      out.back().forFloorStock = mine[i]->forFloorStock;
      at = p;
    }
  }
  return out;
}

// The floor-stock step: plunges added where a sculptured floor keeps more stock
// than asked for (stock.hpp).
// The stock samples of the pocket, with the wall band along steps in the floor
// (a rise of the limit and two sample steps between neighbours: no floor slope).
// (floor: the job's, or a clone of it on another thread.)
StockGrid stockGrid(const Stages& job, const FloorSurface& floor) {
  const PlanInput& in = job.in;
  const double spacing = stockSpacing(job.regionArea, 0.5 * job.tools.all().back().diameter);
  StockGrid grid(job.pocket.region, floor, {in.radialAllowance, in.floorAllowance, in.covering.maxWallStock, spacing},
                 job.progress);
  grid.bandFloorSteps(std::max(in.floor.maxFloorStock, 0.0) + 2.0 * spacing, in.radialAllowance + in.covering.maxWallStock);
  return grid;
}

FloorStockResult floorStockStep(const Stages& job, const std::vector<CutDisk>& disks) {
  const auto& [in, tools, pocket, floor, depths, material, progress, regionArea] = job;
  const Region& region = pocket.region;
  if (!isSculptured(in, floor) || in.floor.maxFloorStock <= 0.0) return {};
  StockGrid grid = stockGrid(job, floor);
  for (const CutDisk& d : disks) grid.cut(d, cutterOf(tools.byId(d.toolId)));
  progress.stage(share::kFloorStock, "plunges for the floor stock");
  FloorStockOptions ro;
  ro.maxFloorStock = in.floor.maxFloorStock;
  ro.radialAllowance = in.radialAllowance;
  ro.floorAllowance = in.floorAllowance;
  ro.topZ = in.topZ;
  ro.progress = progress;
  return plungeFloorStock(region, depths, tools, grid, ro);
}

// The stock the plan's plunges leave on the floor, and the volumes: measured
// (pure, so it runs beside the motion), then reported.
struct FloorStockMeasure {
  StockReport report;
  std::optional<StockMap> map;  // sculptured floors only
};

// (floor: a clone of the job's, for the thread this runs on.)
FloorStockMeasure measureFloorStock(const Stages& job, const FloorSurface& floor, const std::vector<Plunge>& plunges) {
  const auto& [in, tools, pocket, jobFloor, depths, material, progress, regionArea] = job;
  StockGrid grid = stockGrid(job, floor);
  for (const Plunge& p : plunges) grid.cut({{p.x, p.y}, p.toolId, p.z}, cutterOf(tools.byId(p.toolId)));
  FloorStockMeasure out;
  out.report = measureStock(grid, material);
  if (!isSculptured(in, floor)) return out;
  // The picture's map: at most about 160 x 160 cells, each the highest stock in it.
  StockMap m;
  const size_t f = std::max<size_t>(1, std::max(grid.nx(), grid.ny()) / 160 + 1);
  m.spacing = grid.spacing() * f;
  m.origin = grid.origin() + Vec2{0.5 * (f - 1) * grid.spacing(), 0.5 * (f - 1) * grid.spacing()};
  m.nx = (grid.nx() + f - 1) / f;
  m.ny = (grid.ny() + f - 1) / f;
  m.stock.assign(m.nx * m.ny, std::numeric_limits<float>::quiet_NaN());
  for (size_t k = 0; k < grid.size(); ++k) {
    const double s = grid.stock(k);
    if (std::isnan(s)) continue;
    float& cell = m.stock[(k / grid.nx() / f) * m.nx + (k % grid.nx()) / f];
    if (std::isnan(cell) || s > cell) cell = static_cast<float>(s);
  }
  out.map = std::move(m);
  return out;
}

// Why the floor stock stays over the limit: the plunges the final depth held
// above the floor, the floor-stock step's budget, or no plunger of the job.
std::string floorStockWhy(const Placed& placed) {
  if (placed.finalDepthHeld) return "the final depth stops plunges above the floor (a lower final depth would cut it)";
  if (placed.floorStockOutOfBudget)
    return "the floor rises and falls faster than the plungers follow: the floor-stock step stopped after " +
           std::to_string(kFloorStockSearches) +
           " depth searches, so the plan stays within its minute (a smoother floor, or a larger max floor stock,"
           " plans in full)";
  return "no plunger of the job reaches lower there (a smaller or ball-end plunger would)";
}

// The floor stock over max_floor_stock on a sculptured floor, said with why.
Said floorStockSaid(const PlanInput& in, const FloorStockMeasure& m, const std::string& why) {
  Said said;
  const StockReport& r = m.report;
  if (m.map && in.floor.maxFloorStock > 0.0 && r.maxFloorStock > in.floor.maxFloorStock + 1e-6) {
    std::ostringstream w;
    w << std::fixed << std::setprecision(2) << "up to " << r.maxFloorStock
      << " mm of stock stay above the floor, more than the " << in.floor.maxFloorStock << " mm asked for";
    said.limit(w.str(), {"max_floor_stock", in.floor.maxFloorStock, r.maxFloorStock, r.maxFloorStockAt, 1, why});
  }
  return said;
}

// What the final plunges cut, as a covering's result: the stats describe the
// plan as made (floor-stock plunges, growth within the limits and levels included).
CoverResult coverOf(const std::vector<Plunge>& plunges, const Polygons& accessible, const Polygons& core) {
  CoverResult c;
  std::vector<Circle> circles;
  for (const Plunge& p : plunges) circles.push_back({{p.x, p.y}, 0.5 * p.diameter});
  c.accessibleArea = poly::area(accessible);
  c.uncovered = uncoveredRegion(accessible, circles);
  c.coveredArea = c.accessibleArea - poly::area(c.uncovered);
  c.coreArea = poly::area(core);
  c.coreUncovered = uncoveredRegion(core, circles);
  return c;
}

// Plunges per tool (largest first), start holes and the floor-stock step's.
struct PlungeCounts {
  std::vector<ToolCount> perTool;
  int plungeCount = 0, startHoles = 0, floorStockPlunges = 0;
};

PlungeCounts countPlunges(const PlanInput& in, const std::vector<Plunge>& plunges) {
  PlungeCounts out;
  auto count = [&](auto&& f) { return static_cast<int>(std::count_if(plunges.begin(), plunges.end(), f)); };
  for (const Tool& t : in.tools) {
    const int n = count([&](const Plunge& p) { return p.toolId == t.id; });
    if (n == 0) continue;
    ToolCount c;
    c.toolId = t.id;
    c.diameter = t.diameter;
    c.count = n;
    c.peckDepth = peckDepthOf(t);
    c.stickOut = t.stickOut;
    c.holderDiameter = t.holderDiameter;
    c.shankDiameter = t.shankDiameter;
    c.holderLimited = count([&](const Plunge& p) { return p.toolId == t.id && p.holderLimited; });
    out.perTool.push_back(c);
  }
  out.startHoles = count([](const Plunge& p) { return p.startHole; });
  out.plungeCount = static_cast<int>(plunges.size());
  out.floorStockPlunges = count([](const Plunge& p) { return p.forFloorStock && p.level == 0; });
  return out;
}

// The radius a plunge of `cutter` with its tip at z cuts at height `at`: all
// of it for a flat one; a ball or bull nose only where its profile is below.
double radiusCutAt(const Cutter& cutter, double z, double at) {
  const double rise = at - z;
  const double rc = cutter.shape == CutterShape::Ball ? cutter.radius
                    : cutter.shape == CutterShape::Bull ? cutter.cornerRadius : 0.0;
  if (rise >= rc) return cutter.radius;
  if (rise <= 0) return cutter.radius - rc;
  return cutter.radius - rc + std::sqrt(rc * rc - (rc - rise) * (rc - rise));
}

// Why the plunges leave stock at p near the walls: the smallest plunger does
// not fit there (one as wide as the room at p would).
std::string reachWhy(const Region& region, const PlanInput& in, Vec2 p) {
  const double room = 2.0 * (region.wallDistance(p, 1e9) - in.radialAllowance);
  std::ostringstream s;
  s << std::fixed << std::setprecision(2) << "no plunger of the job reaches there: the smallest ("
    << in.tools.back().diameter << " mm) does not fit with the radial allowance (a plunger of " << room
    << " mm or less would)";
  return s.str();
}

// The stock no plunger of the job can reach: corners and gaps of the pocket
// narrower than the smallest plunger (the allowed region less what it reaches).
WallStock outOfReach(const Region& region, const PlanInput& in, const Polygons& accessible) {
  const Polygons beyond = poly::subtract(allowedRegion(region, in.radialAllowance), accessible);
  return wallStockLeft(region, beyond, {}, in.radialAllowance);
}

// Coverage, the core beyond the wall band and the wall stock, from what the
// plan's plunges cut (coverOf), and the limits they break.
struct Coverage {
  double coverage = 0.0, hexReferenceCount = 0.0, coreArea = 0.0, coreCoverage = 0.0, maxWallStockLeft = 0.0;
  Said said;
};

Coverage coverageOf(const Stages& job, const CoverResult& cover) {
  const PlanInput& in = job.in;
  const Region& region = job.pocket.region;
  const Polygons& accessible = job.pocket.accessible;
  Coverage out;
  const double rMax = 0.5 * in.tools.front().diameter;
  out.coverage = cover.accessibleArea > 0 ? cover.coveredArea / cover.accessibleArea : 0.0;
  out.hexReferenceCount = cover.accessibleArea / (detail::kHexCellArea * rMax * rMax);
  // The core beyond the wall band; without a band, the whole accessible region.
  Polygons coreLeft = cover.coreUncovered;
  out.coreArea = cover.coreArea;
  if (in.covering.maxWallStock <= 0.0) {
    out.coreArea = cover.accessibleArea;
    coreLeft = cover.uncovered;
  }
  out.coreCoverage = out.coreArea > 0 ? 1.0 - poly::area(coreLeft) / out.coreArea : 1.0;
  // Said only of pieces larger than a sliver: those are the disks' chords
  // meeting, not stock (wallStockLeft skips them too: they have no place to report).
  coreLeft.erase(std::remove_if(coreLeft.begin(), coreLeft.end(),
                                [](const Loop& L) { return std::fabs(signedArea(L)) < kSliverArea; }),
                 coreLeft.end());
  const WallStock wall = wallStockLeft(region, cover.uncovered, accessible, in.radialAllowance);
  out.maxWallStockLeft = wall.thickest;
  // Any strategy short of what was asked for says so: the grid's fixed spacing
  // usually is. Worded for users of every front end (no JSON key names).
  std::ostringstream w;
  w << std::fixed << std::setprecision(2);
  const std::string grid = "a grid's fixed spacing cannot reach it (the packing strategy would)";
  if (in.covering.maxWallStock > 0.0 && poly::area(coreLeft) > 0.01) {
    w << "the plunges leave " << poly::area(coreLeft) << " mm^2 farther than " << in.covering.maxWallStock
      << " mm from the walls uncut (" << 100 * out.coreCoverage << " % of it cut)";
    const WallStock core = wallStockLeft(region, coreLeft, accessible, in.radialAllowance);
    out.said.limit(w.str(),
              {"max_wall_stock", in.covering.maxWallStock, std::max(core.thickest, wall.thickest), core.at, 1,
               in.packing.strategy == Strategy::Grid ? grid : "slivers between the plunges that no plunge of the plan cut"});
  } else if (const WallStock corner = outOfReach(region, in, accessible);
             in.covering.maxWallStock > 0.0 && std::max(wall.thickest, corner.thickest) > in.covering.maxWallStock + kWallStockSlack) {
    const WallStock& worst = corner.thickest > wall.thickest ? corner : wall;
    w << "up to " << worst.thickest << " mm of stock stay on the walls, more than the " << in.covering.maxWallStock
      << " mm asked for";
    out.said.limit(w.str(), {"max_wall_stock", in.covering.maxWallStock, worst.thickest, worst.at, 1,
                             corner.thickest > wall.thickest ? reachWhy(region, in, worst.at)
                                                             : "slivers between the plunges along the walls"});
  } else if (in.covering.maxWallStock <= 0.0 && out.coverage < in.covering.minCoverage - kCoverageSlack) {
    w << "the plunges clear " << 100 * out.coverage << " % of the reachable floor, less than the "
      << 100 * in.covering.minCoverage << " % asked for";
    out.said.limit(w.str(),
              {"min_coverage", in.covering.minCoverage, out.coverage, wall.at, 1,
               in.packing.strategy == Strategy::Grid ? grid : "material stays along the walls between the plunges"});
  }
  return out;
}

// The wall band at each section's height, measured on the final plunges: what
// of the section's core no plunge through that height cut, and what no
// plunger can reach there, each said where it is thicker than the band. Also
// just below each section, where it is worst: the walls lean in below a
// section (fillets and blends left as walls, drafts), so the pocket there is
// nearly as wide as the section, but only the plunges stopping lower cut it.
// The worst of all is said, at its height.
Said wallBandAboveSaid(const Stages& job, const std::vector<Plunge>& plunges) {
  const PlanInput& in = job.in;
  Said said;
  if (in.covering.maxWallStock <= 0.0) return said;
  struct Worst {
    WallStock band;
    double z = 0.0;
    bool below = false, corner = false;
    const Region* region = nullptr;
  };
  std::optional<Worst> worst;
  std::vector<Region> regions;
  regions.reserve(2 * in.floor.sections.size());  // each section's, and the pocket just below it
  for (const Section& s : in.floor.sections) {
    const double stop = s.z + in.floorAllowance;
    const Region& region = regions.emplace_back(s.boundary, s.islands);
    const Polygons accessible = accessibleRegion(region, 0.5 * in.tools.back().diameter, in.radialAllowance);
    const Polygons core = coreRegion(region, accessible, in.radialAllowance, in.covering.maxWallStock);
    // The plunges that cut at height `at`, each at its radius there.
    auto cutAt = [&](double at) {
      std::vector<Circle> through;
      for (const Plunge& p : plunges) {
        if (p.z > at + 1e-9) continue;
        const double r = radiusCutAt(cutterOf(job.tools.byId(p.toolId)), p.z, at);
        if (r > 0) through.push_back({{p.x, p.y}, r});
      }
      return through;
    };
    const WallStock uncut = wallStockLeft(region, uncoveredRegion(core, cutAt(stop)), {}, in.radialAllowance);
    // Just below the section the pocket is as wide as the section (the walls
    // lean in there), less what of the part stands in it there (an island's
    // or a dome's top under the section: part.hpp), whose walls the band is
    // measured from too.
    std::optional<Region> stands = in.part ? pocketBelow(*in.part, region, s.z - kJustBelow) : std::nullopt;
    const Region& below = stands ? regions.emplace_back(std::move(*stands)) : region;
    const Polygons coreBelow =
        stands ? coreRegion(below, accessibleRegion(below, 0.5 * in.tools.back().diameter, in.radialAllowance),
                            in.radialAllowance, in.covering.maxWallStock)
               : core;
    const WallStock under =
        wallStockLeft(below, uncoveredRegion(coreBelow, cutAt(stop - 1e-6)), {}, in.radialAllowance);
    const WallStock corner = outOfReach(region, in, accessible);
    for (const Worst w : {Worst{uncut, s.z, false, false, &region}, Worst{under, s.z, true, false, &below},
                          Worst{corner, s.z, false, true, &region}})
      if (w.band.thickest > in.covering.maxWallStock + kWallStockSlack &&
          (!worst || w.band.thickest > worst->band.thickest + 1e-9))
        worst = w;
  }
  if (!worst) return said;
  std::ostringstream w;
  w << std::fixed << std::setprecision(2) << (worst->below ? "just below " : "at ") << worst->z
    << " mm, above the floor, up to " << worst->band.thickest << " mm of stock stay on the walls, more than the "
    << in.covering.maxWallStock << " mm asked for";
  said.limit(w.str(),
            {"max_wall_stock", in.covering.maxWallStock, worst->band.thickest, worst->band.at, 1,
             worst->corner  ? reachWhy(*worst->region, in, worst->band.at)
             : worst->below ? "the walls lean in below that height (fillets or blends left as walls, drafts): "
                              "plunges stop at the heights where the pocket widens, and below each the pocket "
                              "is wider than the plunges beneath cut (fillets included in the floor are plunged "
                              "at their own heights)"
                            : "no plunger of the job fits there down to that height"});
  return said;
}

// The job as planned, a value derived from the given input, which stays as
// given: the tools that fit somewhere (the others named in a warning), and
// on boundaries of many thousand vertices walls simplified within a few um,
// that tolerance added to the radial allowance (limits.hpp). Its pocket: the
// region, what the smallest tool reaches, and the core beyond the wall band.
struct Planned {
  PlanInput in;
  Pocket pocket;
  double tolerance = 0.0;  // stats.boundary_tolerance
  Said said;
};

Planned pocketOf(const PlanInput& given) {
  PlanningRegion walls = planningRegion(given);
  Planned out{given, {std::move(walls.region), {}, {}}, walls.tolerance, {}};
  PlanInput& in = out.in;
  Pocket& pocket = out.pocket;
  in.radialAllowance += walls.tolerance;
  ToolsThatFit fit = toolsThatFit(in.tools, pocket.region, in.radialAllowance);
  in.tools = std::move(fit.tools);
  if (!fit.warning.empty()) out.said.warn(fit.warning);
  const double rMin = 0.5 * in.tools.back().diameter;
  pocket.accessible = accessibleRegion(pocket.region, rMin, in.radialAllowance);
  if (poly::area(pocket.accessible) <= 0.0) {
    throw Error("no tool fits in the pocket: the smallest tool (diameter " + std::to_string(2 * rMin) +
                ") with the radial allowance does not fit anywhere");
  }
  if (in.covering.maxWallStock <= 0.0) return out;
  // A band wider than half the pocket's extent leaves no core (and is no offset to compute).
  if (in.covering.maxWallStock < 0.5 * dist(pocket.region.minCorner(), pocket.region.maxCorner()))
    pocket.core = coreRegion(pocket.region, pocket.accessible, in.radialAllowance, in.covering.maxWallStock);
  if (poly::area(pocket.core) <= 0.0) {
    std::ostringstream m;
    m << "max_wall_stock: a band of " << in.covering.maxWallStock
      << " mm along the walls is the whole pocket, nothing would be cut (use a smaller band, or 0 to cover the"
         " reachable floor)";
    throw Error(m.str());
  }
  return out;
}

// The part's triangles within reach of the pocket (part.hpp), as a surface
// the depths read: over its region and its sections (wider above the floor,
// where the section's plunges go); none when no triangle reaches in.
std::shared_ptr<const FloorSurface> partSurface(const PlanInput& in, const Region& region) {
  Polygons reach = region.polygons();
  for (const Section& s : in.floor.sections) reach = poly::unite(reach, Region(s.boundary, s.islands).polygons());
  return makeMeshSurface(partInReach(*in.part, reach, partMargin(*in.part)));
}

// The wall band above the floor: where the pocket is wider at a height than
// at its floor (sections: fillets and corner blends that are walls, drafted
// walls), the plunges through that height are covered up to the section's
// walls, as the floor's outline is: every point farther than the allowance
// and the band from them is cut. The new plunges stop at the section's height
// plus the floor allowance (higher where the floor under them is): the
// section holds the disk and the allowance, and the walls do not overhang, so
// nothing of the part is nearer below. Lowest section first: its plunges cut
// through the higher ones too.
std::vector<CutDisk> wallBandAbove(const Stages& job, std::vector<CutDisk> disks) {
  const auto& [in, tools, pocket, floor, depths, material, progress, regionArea] = job;
  const size_t before = disks.size();
  if (in.covering.maxWallStock <= 0.0 || in.floor.sections.empty()) return {};
  std::vector<const Section*> order;
  for (const Section& s : in.floor.sections) order.push_back(&s);
  std::stable_sort(order.begin(), order.end(), [](const Section* a, const Section* b) { return a->z < b->z; });
  const std::vector<double> radii = radiiOf(in.tools);
  progress.stage(share::kWallBand, "the wall band above the floor");
  for (const Section* s : order) {
    const double stop = s->z + in.floorAllowance;
    if (stop >= in.topZ) continue;
    const Region region(s->boundary, s->islands);
    std::vector<PackedDisk> through;  // what the plunges so far cut at this height
    for (const CutDisk& d : disks) {
      if (d.z > stop + 1e-9) continue;
      const double r = radiusCutAt(cutterOf(tools.byId(d.toolId)), d.z, stop);
      // The covering's disks know their tool by its place in `radii`.
      if (r > 0) through.push_back({d.center, r, r, static_cast<int>(tools.indexOf(d.toolId))});
    }
    const CoveringOptions co = coveringOptions(in, progress);
    const CoverResult cover = coverRegion(region, radii, through, co);
    for (size_t k = through.size(); k < cover.disks.size(); ++k) {
      const CoverDisk& n = cover.disks[k];
      double z = stop;
      try {  // over the floor and the part, no lower than they allow
        z = std::max(z, depths.plungeHeight(n.center, cutterOf(tools.all()[n.tool]), in.floorAllowance,
                                            in.radialAllowance));
      } catch (const Error&) {
        // no floor (nor part) under it: the section's height holds it
      }
      if (z < in.topZ) disks.push_back({n.center, tools.all()[n.tool].id, z});
    }
  }
  return {disks.begin() + static_cast<std::ptrdiff_t>(before), disks.end()};
}

// Plunge positions and their stop heights: packing and covering (or the grid),
// the depth of each (4.4), the floor-stock step, then no plunge below final_depth
// (held: whether that raised any plunge above the floor).
// (positions: where the tool choice has placed the plunges already.)
Placed placeAndDepth(const Stages& job, std::optional<CoverResult> positions) {
  const auto& [in, tools, pocket, floor, depths, material, progress, regionArea] = job;
  progress.stage(share::kPlace, "packing and covering");
  const CoverResult cover =
      positions ? std::move(*positions) : placePlunges(in, pocket.region, radiiOf(in.tools), pocket.core, progress);
  progress.stage(share::kDepths, "plunge depths");
  Placed out{depthsOf(in, cover, depths, progress)};
  const FloorStockResult floorStock = floorStockStep(job, out.disks);
  out.disks.insert(out.disks.end(), floorStock.added.begin(), floorStock.added.end());
  out.floorStockOutOfBudget = floorStock.outOfBudget;
  for (const CutDisk& d : wallBandAbove(job, out.disks)) out.disks.push_back(d);
  if (in.floor.finalDepth)
    for (CutDisk& d : out.disks) {
      const double lowest = *in.floor.finalDepth + in.floorAllowance;
      out.finalDepthHeld = out.finalDepthHeld || d.z < lowest - 1e-9;
      d.z = std::max(d.z, lowest);
    }
  return out;
}

// Rest plunging: the plunges that would cut none of the material the
// operations before left, beyond the wall band the plan may leave (a second
// pass leaves the first's scallops there, as the first did), are left out
// (inAir, with their tools' shapes and depths, to be counted as cut).
struct AirSplit {
  std::vector<CutDisk> cutting;
  std::vector<Plunge> inAir;
};

AirSplit dropAirPlunges(const Stages& job, const std::vector<CutDisk>& disks) {
  const auto& [in, tools, pocket, floor, depths, material, progress, regionArea] = job;
  if (!material.known()) return {disks, {}};
  const double band = in.radialAllowance + in.covering.maxWallStock;
  const Region& region = pocket.region;  // (the lambda captures it: no structured binding)
  auto counts = [&region, band](Vec2 p) { return region.contains(p) && region.wallDistance(p, band) >= band; };
  AirSplit out;
  for (const CutDisk& d : disks) {
    if (material.cutsAny(d.center, cutterOf(tools.byId(d.toolId)), d.z, counts))
      out.cutting.push_back(d);
    else
      out.inAir.push_back(plungeOf(tools.byId(d.toolId), d.center, d.z));
  }
  return out;
}

// The tool that reaches (holder.hpp): the area the stopped plunges were to
// cut, covered by the tools no holder stopped anywhere, as the covering covers
// gaps (every plunge that reached its depth counts as cut). Each new plunge
// stops on the floor as any other; machined after the larger tools, it meets
// the material they left, and the replay checks its own holder.
std::vector<CutDisk> reachWhereHeld(const Stages& job, const HolderClearance& held) {
  const auto& [in, tools, pocket, floor, depths, material, progress, regionArea] = job;
  std::set<std::tuple<int, double, double>> stopped;
  std::set<int> stoppedTools;
  for (const HolderStop& s : held.stops) {
    stopped.insert({s.toolId, s.at.x, s.at.y});
    stoppedTools.insert(s.toolId);
  }
  std::vector<const Tool*> reaching;
  std::vector<double> radii;
  for (const Tool& t : tools.all())
    if (!stoppedTools.count(t.id)) {
      reaching.push_back(&t);
      radii.push_back(0.5 * t.diameter);
    }
  std::vector<CutDisk> out;
  if (reaching.empty()) return out;
  std::set<std::tuple<int, double, double>> seen;
  std::vector<PackedDisk> through;  // the tool index is not read for these
  for (const Plunge& p : held.plunges) {
    const auto key = std::make_tuple(p.toolId, p.x, p.y);
    if (stopped.count(key) || !seen.insert(key).second) continue;
    const double r = 0.5 * tools.byId(p.toolId).diameter;
    through.push_back({{p.x, p.y}, r, r, -1});
  }
  const CoverResult cover = coverRegion(pocket.region, radii, through, coveringOptions(in, progress));
  const double lowest = in.floor.finalDepth ? *in.floor.finalDepth + in.floorAllowance : -std::numeric_limits<double>::infinity();
  for (size_t k = through.size(); k < cover.disks.size(); ++k) {
    const CoverDisk& n = cover.disks[k];
    const Tool& t = *reaching[n.tool];
    double z = lowest;
    try {
      z = std::max(z, depths.plungeHeight(n.center, cutterOf(t), in.floorAllowance, in.radialAllowance));
    } catch (const Error&) {
      continue;  // no floor under it
    }
    if (z < in.topZ) out.push_back({n.center, t.id, z});
  }
  return out;
}

// The stops no plunge of another tool made up for: some of the disk the
// stopped plunge was to cut (within the core, or the accessible area without
// a wall band) is cut to depth by none of the plunges that reached theirs.
std::vector<HolderStop> stillHeld(const Pocket& pocket, const ToolTable& tools,
                                  const std::vector<HolderStop>& stops, const std::vector<Plunge>& plunges) {
  std::set<std::tuple<int, double, double>> stopped;
  for (const HolderStop& s : stops) stopped.insert({s.toolId, s.at.x, s.at.y});
  std::vector<Circle> reached;
  for (const Plunge& p : plunges)
    if (!stopped.count({p.toolId, p.x, p.y})) reached.push_back({{p.x, p.y}, 0.5 * p.diameter});
  const Polygons& area = pocket.core.empty() ? pocket.accessible : pocket.core;
  std::vector<HolderStop> out;
  for (const HolderStop& s : stops) {
    const double r = 0.5 * tools.byId(s.toolId).diameter;
    std::vector<Circle> near;
    for (const Circle& c : reached)
      if (dist(c.c, s.at) < c.r + r) near.push_back(c);
    const Polygons mine = poly::intersect({poly::disk({s.at, r})}, area);
    if (poly::area(uncoveredRegion(mine, near)) > kSliverArea) out.push_back(s);
  }
  return out;
}

// What the holders keep clear, in a pocket of this size.
HolderSettings holderSettingsOf(const Stages& job) {
  return {job.in.motion.holderClearance, dist(job.pocket.region.minCorner(), job.pocket.region.maxCorner())};
}

// What the growth and the moves read of the job, filled once for both.
JobOptions jobOptions(const Stages& job) {
  const auto& [in, tools, pocket, floor, depths, material, progress, regionArea] = job;
  JobOptions o;
  o.tools = tools;
  o.material = material;
  o.radialAllowance = in.radialAllowance;
  o.floorAllowance = in.floorAllowance;
  o.maxWallStock = in.covering.maxWallStock;
  o.progress = progress;
  return o;
}

EngagementOptions engagementOptions(const Stages& job) {
  EngagementOptions o;
  static_cast<JobOptions&>(o) = jobOptions(job);
  o.maxFloorStock = job.in.floor.maxFloorStock;
  o.start = job.in.motion.start;
  o.pattern = job.in.engagement.pattern;
  return o;
}

MotionOptions motionOptions(const Stages& job) {
  MotionOptions o;
  static_cast<JobOptions&>(o) = jobOptions(job);
  o.safeZ = job.in.safeZ;
  o.settings = job.in.motion;
  return o;
}

// Where the depth search ran out of budget, said (the plan stays gouge-free:
// dense samples stand in, raised to bound the surface between them), with
// what does it on this kind of floor and what avoids it.
Said depthFallbacksSaid(const PlanInput& in, int fallbacks) {
  Said said;
  if (fallbacks == 0) return said;
  const std::string n = std::to_string(fallbacks);
  const std::string places = fallbacks == 1 ? " place" : " places";
  const std::string sampled = ": their depths come from a dense sample of the floor, raised by the rise between samples";
  switch (in.floor.surface.kind) {
    case Floor::Kind::Expression:
      said.warn("the depth search ran out of its budget on " + n + places + " of the floor expression" + sampled +
                " (terms that change steeply or fast do this; a smoother expression avoids it)");
      break;
    case Floor::Kind::Mesh:
      said.warn("the depth search ran out of its budget on " + n + places + " of the floor mesh" + sampled +
                " (many tiny or sliver triangles do this; a coarser meshing of the faces avoids it)");
      break;
    default:
      said.warn("the depth search ran out of its budget on " + n + " floor faces, edges or plunges" + sampled +
                " (a floor of many tiny or badly parametrised faces does this; selecting fewer, cleaner"
                " faces, or a cleaner export of the part, avoids it)");
  }
  return said;
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The automatic tool choice (selection.hpp). Each tool set it tries is an
// input of its own (a subset of the library may lack the start-hole drill a
// plunger needs), placed (packing and covering) for its estimate, the best
// planned in full.
Plan planChoosingTools(const PlanInput& in, const Progress& progress) {
  const std::unique_ptr<FloorSurface> floor = makeFloor(in);
  ToolSetStages stages;
  stages.floor = floor.get();
  stages.plan = [](PlanInput sub, std::optional<CoverResult> positions, const Progress& p) {
    validate(sub);
    return planPlaced(std::move(sub), std::move(positions), p);
  };
  stages.place = [](PlanInput sub, const Progress& p) {
    validate(sub);
    const Planned planned = pocketOf(sub);  // may leave out tools that fit nowhere
    const Pocket& pocket = planned.pocket;
    return placePlunges(planned.in, pocket.region, radiiOf(planned.in.tools), pocket.core, p);
  };
  return planWithToolSelection(in, stages, progress);
}

}  // namespace

Plan plan(PlanInput in, const Progress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  progress.stage(share::kCheck, "checking the pocket");
  if (in.choice.automatic) in.tools = in.choice.library;
  validate(in);
  // The pocket without what of the part overhangs its floor (part.hpp), for
  // every tool set the choice tries too; what is left under it is said first.
  if (in.part) {
    const std::unique_ptr<FloorSurface> floor = makeFloor(in);  // (before `in` is moved)
    in = withoutOverhangs(std::move(in), *floor);
  }
  const std::vector<std::string> notes = in.notes;
  Plan out = in.choice.automatic ? planChoosingTools(in, progress) : planWithTools(std::move(in), progress);
  out.warnings.insert(out.warnings.begin(), notes.begin(), notes.end());
  out.stats.planningSeconds = secondsSince(t0);
  return out;
}

Plan planWithTools(PlanInput in, const Progress& progress) { return planPlaced(std::move(in), std::nullopt, progress); }

namespace {

// The plunges in their machining order: each tool's tour, then (real plunge mills)
// engagement limits and cores (positions and order grown together), flute
// length (levels), holders and shanks kept clear of the part and the
// standing material, in that order: plunges stop where they clear (holder.hpp).
struct MachiningOrder {
  HolderClearance holders;
  int levels = 1;
};

// progress: the job's, or the range of a second ordering (orderReaching).
MachiningOrder orderForMachining(const Stages& job, const MotionOptions& motion, const std::vector<CutDisk>& disks,
                                 const Progress& progress) {
  const auto& [in, tools, pocket, floor, depths, material, jobProgress, regionArea] = job;
  progress.stage(share::kOrder, "ordering the plunges");
  std::vector<Plunge> ordered = sequence(job, disks);
  if (std::any_of(in.tools.begin(), in.tools.end(), [](const Tool& t) { return std::isfinite(engagementLimit(t)); })) {
    progress.stage(share::kGrow, "growing the cut within the engagement limits");
    HeightField stock = stockOf(in.tools, material, pocket.region);
    EngagementOptions eo = engagementOptions(job);
    eo.progress = progress;
    ordered = growWithinLimits(pocket.region, depths, ordered, stock, eo);
  }
  Levels split = splitIntoLevels(ordered, motion);
  return {clearHolders(split.plunges, tools, material, holderSettingsOf(job)), split.levels};
}

// The machining order, and where holders stopped plunges, the tools they did
// not stop cover what is left (reachWhereHeld), and all is ordered again.
MachiningOrder orderReaching(const Stages& job, const MotionOptions& motion, std::vector<CutDisk> disks) {
  MachiningOrder order = orderForMachining(job, motion, disks, job.progress);
  if (order.holders.stops.empty()) return order;
  job.progress.stage(share::kReach, "covering where holders stopped plunges");
  const std::vector<CutDisk> reach = reachWhereHeld(job, order.holders);
  if (reach.empty()) return order;
  disks.insert(disks.end(), reach.begin(), reach.end());
  return orderForMachining(job, motion, disks, job.progress.sub(share::kReach, share::kMotion));
}

// What the final plunges cut and the stock they leave on the floor: measured
// on another thread, with its own floor, while the motion is planned (the moves
// between the plunges change neither where they cut nor how deep).
struct Measures {
  CoverResult cover;
  FloorStockMeasure stock;
  std::optional<PartStock> partStock;  // with the part: the stock left in 3D (part_stock.hpp)
};

// The 3D measure's raster: twice the floor stock's (a quarter of its
// samples, each layer a distance transform): its bands are whole millimetres.
double partStockSpacing(const Stages& job) {
  return 2.0 * stockSpacing(job.regionArea, 0.5 * job.tools.all().back().diameter);
}

// The stock left measured against the whole part (part_stock.hpp). (floor: the job's, or a clone on another thread.)
PartStock partStockOf(const Stages& job, const FloorSurface& floor, const std::vector<Plunge>& plunges) {
  const PlanInput& in = job.in;
  PartStockOptions o;
  o.radialAllowance = in.radialAllowance;
  o.floorAllowance = in.floorAllowance;
  o.maxFloorStock = std::max(in.floor.maxFloorStock, 0.0);
  o.spacing = partStockSpacing(job);
  o.progress = job.progress;
  std::vector<Loop> outlines{in.boundary};
  // Just below each section and each height many plunges stop at: the walls
  // that lean in below them leave the most there.
  for (const Section& s : in.floor.sections) {
    outlines.push_back(s.boundary);
    o.heights.push_back(s.z - 0.02);
  }
  std::set<double> stops;
  for (const Plunge& p : plunges) stops.insert(p.z);
  if (stops.size() <= 64)
    for (double z : stops) o.heights.push_back(z - 0.001);
  return measurePartStock(*in.part, floor, outlines, job.material, plunges, job.tools, o);
}

// What the 3D measure finds beyond the wall band (rings around islands that
// narrow upward, columns the outline left out), said as the band's broken
// limit at its height; the raster's own step is the slack.
Said partStockSaid(const Stages& job, const std::optional<PartStock>& measured) {
  Said said;
  const double band = job.in.covering.maxWallStock;
  if (!measured || band <= 0.0) return said;
  const double slack = 1.5 * partStockSpacing(job);
  if (measured->thickest <= band + slack) return said;
  std::ostringstream w;
  w << std::fixed << std::setprecision(2) << "at " << measured->z << " mm, measured against the whole part, up to "
    << measured->thickest << " mm of stock stay beside the part, more than the " << band << " mm asked for";
  said.limit(w.str(), {"max_wall_stock", band, measured->thickest, measured->at, 1,
                       "the part there is narrower above the floor than the pocket's outline shows (an island or a"
                       " wall that tapers or steps in, a window or a drop-off the outline leaves out): no plunge of"
                       " the pocket reaches that stock"});
  return said;
}

Plan planPlaced(const PlanInput& given, std::optional<CoverResult> positions, const Progress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const Planned planned = pocketOf(given);
  const PlanInput& in = planned.in;
  const Pocket& pocket = planned.pocket;
  // The job's tools, once: every stage from here on knows a tool by its id.
  const ToolTable tools(in.tools);
  const Material material(in.material, in.topZ);  // what the operations before left
  // The floor: flat, an expression, a mesh or BREP faces (read before the long part).
  const std::unique_ptr<FloorSurface> floor = makeFloor(in);
  const Vec2 lo = pocket.region.minCorner(), hi = pocket.region.maxCorner();
  // Refused before the long part: its depths would take hours.
  if (const std::string why = floor->unfollowable(lo, hi); !why.empty()) throw Error(why);
  progress.stage(share::kFloor, "analysing the floor");
  // The part around the pocket, where given: every depth reads it too.
  const DepthSolver depths(*floor, lo, hi, std::max(0.25 * in.tools.back().diameter, kDepthCellFraction * dist(lo, hi)),
                           progress, in.part ? partSurface(in, pocket.region) : nullptr);
  const double regionArea = poly::area(allowedRegion(pocket.region, in.radialAllowance));
  const Stages job{in, tools, pocket, *floor, depths, material, progress, regionArea};

  // Where to plunge and how deep, then which plunges are left out in air.
  const Placed where = placeAndDepth(job, std::move(positions));
  const AirSplit air = dropAirPlunges(job, where.disks);
  // In what order they are machined: levels, holders and the tool that reaches.
  MotionOptions motion = motionOptions(job);
  const MachiningOrder order = orderReaching(job, motion, air.cutting);
  const std::vector<Plunge>& plunges = order.holders.plunges;
  const Said held = holderLimits(stillHeld(pocket, tools, order.holders.stops, plunges), tools,
                                 in.motion.holderClearance);
  // Measured on the final plunges (the floor-stock step and the limits add to
  // the covering's), the plunges left out in air counted as cut: the material
  // is gone there. The thread reads its own copies and what no stage changes.
  std::vector<Plunge> cutting = plunges;
  cutting.insert(cutting.end(), air.inAir.begin(), air.inAir.end());
  auto measuring = std::async(std::launch::async, [&job, cutting = std::move(cutting), own = floor->clone()] {
    Measures m{coverOf(cutting, job.pocket.accessible, job.pocket.core), measureFloorStock(job, *own, cutting), {}};
    if (job.in.part) m.partStock = partStockOf(job, *own, cutting);
    return m;
  });
  // The moves between them.
  progress.stage(share::kMotion, "heights and lead-outs");
  motion.progress = progress.sub(share::kMotion, share::kMeasure);
  Motion moves = planMotion(pocket.region, depths, plunges, motion);
  progress.stage(share::kMeasure, "measuring the stock left");
  const Measures measured = progress.await(measuring);
  const Coverage coverage = coverageOf(job, measured.cover);
  const PlungeCounts counts = countPlunges(in, moves.plunges);
  const int fallbacks = depths.peakFallbacks() + depths.depthFallbacks();

  // The plan, assembled once; what the stages said, in their order.
  Plan out;
  Said said = planned.said;
  said += coverage.said;
  Said above = wallBandAboveSaid(job, moves.plunges);
  above += partStockSaid(job, measured.partStock);
  said += above;
  said += moves.said;
  said += held;
  for (std::string& w : uncheckedHolders(moves.plunges, tools, in.topZ)) said.warn(std::move(w));
  said += floorStockSaid(in, measured.stock, floorStockWhy(where));
  said += depthFallbacksSaid(in, fallbacks);
  out.warnings = std::move(said.warnings);
  out.broken = std::move(said.broken);
  out.accessible = pocket.accessible;
  out.uncovered = measured.cover.uncovered;
  out.stockMap = measured.stock.map;
  PlanStats& st = out.stats;
  st.plungeCount = counts.plungeCount;
  st.floorKind = floorKindName(in.floor.surface.kind);
  st.perTool = counts.perTool;
  st.startHoles = counts.startHoles;
  st.floorStockPlunges = counts.floorStockPlunges;
  st.regionArea = regionArea;
  st.accessibleArea = measured.cover.accessibleArea;
  st.coveredArea = measured.cover.coveredArea;
  st.coverage = coverage.coverage;
  st.hexReferenceCount = coverage.hexReferenceCount;
  st.coreArea = coverage.coreArea;
  st.coreCoverage = coverage.coreCoverage;
  st.maxWallStockLeft = coverage.maxWallStockLeft;
  const StockReport& stock = measured.stock.report;
  st.maxFloorStockLeft = stock.maxFloorStock;
  // A summary never says the walls are within their band where a measure
  // above the floor (the sections', the 3D one) finds they are not.
  for (const BrokenLimit& b : above.broken) st.maxWallStockLeft = std::max(st.maxWallStockLeft, b.worst);
  st.meanFloorStock = stock.meanFloorStock;
  st.volumeRemoved = stock.volumeRemoved;
  st.volumeLeft = stock.volumeLeft;
  st.volumeBefore = stock.volumeBefore;
  st.airPlunges = static_cast<int>(air.inAir.size());
  st.restMaterial = material.known();
  st.levels = order.levels;
  const MotionStats& m = moves.stats;
  st.overEngaged = m.overEngaged;
  st.thinCuts = m.thinCuts;
  st.peckedPlunges = m.peckedPlunges;
  st.leadOuts = m.leadOuts;
  st.raisedLeadOuts = m.raisedLeadOuts;
  st.noLeadOutMaterial = m.noLeadOutMaterial;
  st.noLeadOutWalls = m.noLeadOutWalls;
  st.travelLength = m.travelLength;
  st.estimatedMinutes = m.estimatedMinutes;
  st.minutesAtSafeHeight = m.minutesAtSafeHeight;
  st.boundaryTolerance = planned.tolerance;
  st.depthFallbacks = fallbacks;
  out.plunges = std::move(moves.plunges);
  st.planningSeconds = secondsSince(t0);
  return out;
}

}  // namespace

}  // namespace plunge
