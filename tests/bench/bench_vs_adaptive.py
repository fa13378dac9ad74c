"""Plunge Rough against FreeCAD's own Adaptive clearing: the same pockets, the
same 20 mm tool, both posted with FreeCAD's linuxcnc post and timed from the
G-code (a table for docs/benchmarks.md).

Run headless inside FreeCAD, from the repository after the build (docs/cli.md: the
planner module comes from build/cpp, the addon from the source tree):

    XDG_DATA_HOME=$(mktemp -d) XDG_CONFIG_HOME=$(mktemp -d) freecadcmd tests/bench/bench_vs_adaptive.py

(a profile of its own: an installed copy of the addon would be loaded first).

PLUNGE_BENCH_POCKETS="2,3" runs only those pockets (numbers below),
PLUNGE_BENCH_CELL the height field's cell (mm, default 0.25),
PLUNGE_BENCH_GCODE a folder to keep the posted programs in,
PLUNGE_BUILD_DIR another build tree.

Pockets (Part booleans; the floor face is the operations' base, as the tests
select it): 1 the example part (resources/examples, B-spline floor, free-form
wall and island, about 25 mm deep), 2 a 120 x 80 pocket 20 mm deep, 3 the same
60 mm deep, 4 a 140 x 100 pocket 50 mm deep with a round island (D 40), 5 a
deep narrow pocket, 40 x 100 and 70 mm deep (3.5 x the largest plunger). Each
is in a block 20 mm wider on every side, 10 mm below the floor. The Job's
stock is FreeCAD's default box, 1 mm around the part; the demo keeps its 1 mm
above the part's top too (as resources/examples does), the others have their
top at the part's top (ExtZpos 0, a faced block): each is as deep as named
(with 1 mm more a 20 mm pocket is 20.7 mm of cut, one Adaptive layer more at 1 D).

Operations, one Job each, built as tests/freecad builds them
(example_part.make_job, add_tool_controller, add_plunge_rough: one .fctb
endmill bit per tool):
  Plunge Rough   the 20, 12 and 6 mm plungers (tools 2, 3, 4), radial
                 allowance 0.5 mm, floor allowance 0.3 mm (the demo's), every
                 other property at its default;
  Adaptive       FreeCAD's Adaptive (Clearing, Side Inside, StepOver 20 %, no
                 finishing profile) with the 20 mm tool, StockToLeave = the
                 radial allowance and FinalDepth = the highest point of the
                 floor face + the floor allowance: 0.20's Adaptive cuts flat
                 layers, so a lower final depth would gouge a free-form floor.
Every tool controller: HorizFeed 1200, VertFeed 300, rapids 5000 mm/min;
Plunge Rough is planned once per model, its plungers' VertFeed at that model's
plunge feed (A: 1200, B: 300), so that its tool choice (on, as for every new
operation) weighs tool changes against the plunges at the feed they will run.
Cycle time, from the posted G-code by this file's own reader (G0/G1/G2/G3,
G81/G82/G83/G73 with G98/G99 expanded into their moves, G4, M6):
  Model A  every feed move at 1200 mm/min whatever its F; Adaptive StepDown 1 D (20 mm).
  Model B  the posted F words (1200 horizontal, 300 vertical: the plunges, and
           Adaptive's helix entries, which FreeCAD feeds at VertFeed);
           Adaptive StepDown 2 D (40 mm).
  Both     rapids at 5000 mm/min along their 3D length, 20 s per M6.
Beside them, not used: the planner's own estimate of Plunge Rough
(stats.estimated_minutes, from the same tool controllers). FreeCAD 0.20's
CycleTime of an operation is not shown: Path.getCycleTime takes an axis a
command leaves out as 0, not as where the tool is.

Lower bound: the volume the operations should remove (the pocket less its
allowances, area A in plan view, mean depth h = volume / A), plunged by the
largest tool (D) on a hexagonal grid of pitch D:
    n = A / ((sqrt(3) / 2) D^2)
    t = n (h / F_plunge + h / 5000 + 0.87 D / 5000) + 20 s
(each plunge feeds its depth at the model's plunge feed, 1200 or 300 mm/min,
rapids back up and 0.87 D on; 20 s for the one tool load every program has).
No plan can cover the pocket with fewer plunges of that tool, nor plunge them
faster.

Volumes: each posted program is replayed on a numpy height field of the stock
(cells of PLUNGE_BENCH_CELL; each tool's flat, bull or ball end from its bit),
every move, rapids included. "Target" is the stock above the part's surface
dilated by the radial allowance and raised by the floor allowance (the
pocket less allowances); "left" the stock the program leaves above that;
"gouge" what it cut below the part's surface (rasterised from a fine mesh).
Checks (said under the tables when they fail): the G-code's plunges per tool
equal the plan's, the planner's removed volume the replay's, the volumes
within 3 % of the target and of each other, no gouge, no rapid through stock.

Tested with FreeCAD 0.20.2 (Debian 12). Adaptive's paths vary a little from
one run to the next (a few % of its time); Plunge Rough's do not.
"""
import importlib
import math
import os
import sys
import tempfile
import time
from collections import namedtuple

import numpy as np
from scipy import ndimage

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.environ.get("PLUNGE_BUILD_DIR", os.path.join(ROOT, "build"))
for _p in (os.path.join(BUILD, "cpp"), ROOT, os.path.join(ROOT, "resources", "examples"),
           os.path.join(ROOT, "tests", "freecad")):
    if _p not in sys.path:
        sys.path.insert(0, _p)

import FreeCAD  # noqa: E402
import Part  # noqa: E402

import example_part  # noqa: E402
from freecad_plugin import companions, compat  # noqa: E402
from gcode_replay import Stock, part_surface, read_program, replay, tools_of  # noqa: E402

# An installed copy of the addon (the README's install) is loaded by FreeCAD
# before this script runs, with its own planner: the bench would time that.
if not os.path.abspath(companions.__file__).startswith(ROOT + os.sep):
    sys.exit("the addon comes from %s, not this tree: run with a profile of its own, e.g. "
             "XDG_DATA_HOME=$(mktemp -d) XDG_CONFIG_HOME=$(mktemp -d) freecadcmd %s"
             % (os.path.dirname(os.path.dirname(companions.__file__)), os.path.relpath(__file__, ROOT)))

V = FreeCAD.Vector
PLUNGERS = (20.0, 12.0, 6.0)
RADIAL, FLOOR = 0.5, 0.3
FEED, PLUNGE_FEED, RAPID = 1200.0, 300.0, 5000.0  # mm/min
TOOL_CHANGE = 20.0  # s per M6
CELL = float(os.environ.get("PLUNGE_BENCH_CELL", "0.25"))
CHECK_TOL = 0.03  # volumes: fraction of the target
# name, Adaptive StepDown (x D), feed of every feed move (None: the posted F), the lower bound's plunge feed
Model = namedtuple("Model", "name step_down feed plunge_feed")
MODELS = (Model("A", 1, FEED, FEED), Model("B", 2, None, PLUNGE_FEED))


# -- the pockets -------------------------------------------------------------------
def box_pocket(width, length, depth, island_diameter=0.0, margin=20.0, below=10.0):
    """A block with a width x length pocket, depth deep, and a round island in its middle."""
    block = Part.makeBox(width + 2 * margin, length + 2 * margin, depth + below)
    cavity = Part.makeBox(width, length, depth + 1, V(margin, margin, below))
    if island_diameter:
        centre = V(margin + width / 2, margin + length / 2, below)
        cavity = cavity.cut(Part.makeCylinder(island_diameter / 2, depth + 1, centre))
    return block.cut(cavity).removeSplitter()


Pocket = namedtuple("Pocket", "name part sculptured stock_above")
POCKETS = [
    Pocket("demo (B-spline floor)", lambda: example_part.freeform_part(sculptured=True), True, 1.0),
    Pocket("120 x 80 x 20", lambda: box_pocket(120, 80, 20), False, 0.0),
    Pocket("120 x 80 x 60", lambda: box_pocket(120, 80, 60), False, 0.0),
    Pocket("140 x 100 x 50, island D 40", lambda: box_pocket(140, 100, 50, 40), False, 0.0),
    Pocket("40 x 100 x 70 (deep, narrow)", lambda: box_pocket(40, 100, 70), False, 0.0),
]


# -- the two Jobs --------------------------------------------------------------------
def adaptive_module():
    for name in ("Path.Op.Adaptive", "PathScripts.PathAdaptive"):
        try:
            return importlib.import_module(name)
        except ImportError:
            continue
    raise ImportError("FreeCAD's Adaptive operation")


def set_feeds(tc, vertical=PLUNGE_FEED):
    tc.HorizFeed = "%g mm/min" % FEED
    tc.VertFeed = "%g mm/min" % vertical
    tc.HorizRapid = tc.VertRapid = "%g mm/min" % RAPID
    return tc


def set_value(obj, prop, value):
    """A property set by hand (its default expression, e.g. FinalDepth = OpFinalDepth, cleared)."""
    obj.setExpression(prop, None)
    setattr(obj, prop, value)


def new_job(pocket, shape, name):
    doc = FreeCAD.newDocument(name)
    job = example_part.make_job(doc, shape)
    job.Stock.ExtZpos = pocket.stock_above
    doc.recompute()
    return job, job.Model.Group[0]


def plunge_job(pocket, shape, bits, vertical):
    """A Job with the plungers (plunging at `vertical` mm/min) and a Plunge Rough
    on the floor; seconds of its creation and plan."""
    job, model = new_job(pocket, shape, "BenchPlunge")
    for i, d in enumerate(PLUNGERS):
        set_feeds(example_part.add_tool_controller(job, d, i + 2, bits), vertical)
    face = example_part.floor_face_name(model.Shape, pocket.sculptured)
    start = time.perf_counter()
    op, _ = example_part.add_plunge_rough(job, face, (), bits, RadialAllowance=RADIAL, FloorAllowance=FLOOR)
    seconds = time.perf_counter() - start
    if not op.PlanData:
        raise RuntimeError("Plunge Rough made no plan: " + op.Summary)
    return job, op, seconds


def adaptive_job(pocket, shape, bits):
    """A Job with the 20 mm tool and an Adaptive clearing of the floor face; seconds of its recompute."""
    job, model = new_job(pocket, shape, "BenchAdaptive")
    # FreeCAD 0.20 headless: the first operation of a Job with more than one tool
    # controller fails (PathUtils.findToolController leaves `tc` unbound where the
    # GUI would ask which one): the unused default tool controller goes first.
    for default in list(job.Tools.Group):
        bit = default.Tool
        job.Document.removeObject(default.Name)
        job.Document.removeObject(bit.Name)
    tc = set_feeds(example_part.add_tool_controller(job, PLUNGERS[0], 2, bits))
    face = example_part.floor_face_name(model.Shape, pocket.sculptured)
    op = adaptive_module().Create("Adaptive", parentJob=job)
    op.ToolController = tc
    op.Base = [(model, [face])]
    op.OperationType, op.Side, op.StepOver = "Clearing", "Inside", 20
    op.FinishingProfile = False
    op.StockToLeave = RADIAL
    set_value(op, "FinalDepth", model.Shape.getElement(face).BoundBox.ZMax + FLOOR)
    set_value(op, "StepDown", MODELS[0].step_down * PLUNGERS[0])
    start = time.perf_counter()
    job.Document.recompute()
    seconds = time.perf_counter() - start
    if len(op.Path.Commands) < 3:
        raise RuntimeError("Adaptive made no path")
    return job, op, seconds


def post(job, name):
    text = compat.post_job(job, "linuxcnc", "--no-show-editor")
    keep = os.environ.get("PLUNGE_BENCH_GCODE")
    if keep:
        os.makedirs(keep, exist_ok=True)
        with open(os.path.join(keep, name + ".ngc"), "w") as f:
            f.write(text)
    return text


def minutes(program, model):
    """The program's cycle time under a feed model: feeds at the model's feed (or
    their F), rapids at RAPID (3D length), TOOL_CHANGE per M6, dwells."""
    feed = rapid = down = 0.0
    for m in program.moves:
        length = math.dist(m.a, m.b)
        if m.rapid:
            rapid += length / RAPID
        else:
            rate = model.feed or m.feed
            if not rate:
                raise ValueError("a feed move without F")
            feed += length / rate
            if m.b[2] < m.a[2] - 1e-6 and math.dist(m.a[:2], m.b[:2]) < 1e-6:
                down += length / rate
    changes = program.tool_changes * TOOL_CHANGE / 60.0
    return {"total": feed + rapid + changes + program.dwell / 60.0, "feed": feed, "rapid": rapid, "changes": changes,
            "down": down}


def break_even(plunge, adaptive):
    """Model A's plunge feed (the side feed) times this is the plunge feed at
    which Plunge Rough takes as long as Adaptive: its feeds straight down scale
    with the plunge feed, everything else stays (the same plan)."""
    rest = plunge["total"] - plunge["down"]
    return plunge["down"] / (adaptive["total"] - rest) if adaptive["total"] > rest else float("inf")


def plunges_per_tool(program):
    """Feeds straight down (Z only); a further feed down at the same X Y with no
    move sideways since (a pecked hole) goes on with the same plunge."""
    counts, moved = {}, True
    for m in program.moves:
        sideways = abs(m.a[0] - m.b[0]) > 1e-6 or abs(m.a[1] - m.b[1]) > 1e-6
        if sideways:
            moved = True
        elif not m.rapid and m.b[2] < m.a[2] - 1e-6:
            if moved:
                counts[m.tool] = counts.get(m.tool, 0) + 1
            moved = False
    return counts


def target_surface(surface, part_top, cell):
    """The lowest the roughing may go: the part's surface dilated by the radial
    allowance and raised by the floor allowance; and the pocket's cells (below the part's top)."""
    k = int(math.ceil(RADIAL / cell))
    yy, xx = np.mgrid[-k:k + 1, -k:k + 1]
    target = ndimage.grey_dilation(surface, footprint=np.hypot(xx, yy) * cell <= RADIAL + 1e-9) + FLOOR
    return target, target < part_top - 1e-6


def volumes(stock, surface, target, pocket):
    """mm3 left above the target in the pocket, and cut below the part's surface."""
    cell2 = stock.cell ** 2
    return {"left": float(np.maximum(stock.z - target, 0)[pocket].sum()) * cell2,
            "gouge": float(np.maximum(surface - stock.z, 0).sum()) * cell2}


# -- one pocket ---------------------------------------------------------------------------------
def lower_bound(area, volume, model):
    """Minutes to plunge the volume on a hexagonal grid of pitch D (the docstring's formula)."""
    d = PLUNGERS[0]
    n = area / (math.sqrt(3) / 2 * d * d)
    h = volume / area
    return n * (h / model.plunge_feed + h / RAPID + 0.87 * d / RAPID) + TOOL_CHANGE / 60.0


def measure(text, job, geometry):
    """A posted program read back, timed under both models and replayed on a fresh stock."""
    program = read_program(text)
    stock = Stock(geometry["box"], CELL)
    cut = replay(program, stock, tools_of(job))
    cut.update(volumes(stock, geometry["surface"], geometry["target"], geometry["pocket"]))
    cut["plunges"] = plunges_per_tool(program)
    cut["tool_changes"] = program.tool_changes
    cut["layers"] = len({round(m.b[2], 3) for m in program.moves if not m.rapid and m.a[2] == m.b[2]})
    return program, cut


def pocket_geometry(job):
    """The part's surface, the target surface and the pocket's cells on a grid of the Job's stock."""
    stock = Stock(job.Stock.Shape.BoundBox, CELL)
    shape = job.Model.Group[0].Shape
    surface = part_surface(shape, stock)
    target, pocket = target_surface(surface, shape.BoundBox.ZMax, CELL)
    cell2 = CELL ** 2
    return {"box": job.Stock.Shape.BoundBox, "surface": surface, "target": target, "pocket": pocket,
            "area": float(pocket.sum()) * cell2, "volume": float((stock.top - target)[pocket].sum()) * cell2}


def bench_pocket(name, pocket, bits):
    shape = pocket.part()
    # As FreeCAD's GUI shows the part before a Job is made of it: a curved face's
    # bounding box, from which the Job's default stock is made, is tight only then.
    shape.tessellate(0.1)
    result = {"name": name, "plan": {}, "plunge": {}, "plunge_minutes": {}, "plunge_seconds": {}}
    # Planned for each model's plunge feed: the tool choice weighs a tool change
    # against the plunges it saves at that feed.
    for m in MODELS:
        job, op, result["plunge_seconds"][m.name] = plunge_job(pocket, shape, bits, m.plunge_feed)
        result["plan"][m.name] = companions.plan_of(op)
        geometry = result["geometry"] = pocket_geometry(job)
        program, result["plunge"][m.name] = measure(post(job, "%s plunge %s" % (name, m.name)), job, geometry)
        result["plunge_minutes"][m.name] = minutes(program, m)
        FreeCAD.closeDocument(job.Document.Name)

    job, op, result["adaptive_seconds"] = adaptive_job(pocket, shape, bits)
    result["same_stock"] = job.Stock.Shape.BoundBox.isInside(geometry["box"]) and \
        geometry["box"].isInside(job.Stock.Shape.BoundBox)
    result["adaptive"], result["adaptive_minutes"] = {}, {}
    for model in MODELS:
        set_value(op, "StepDown", model.step_down * PLUNGERS[0])
        job.Document.recompute()
        program, result["adaptive"][model.name] = measure(post(job, "%s adaptive %s" % (name, model.name)), job, geometry)
        result["adaptive_minutes"][model.name] = minutes(program, model)
    FreeCAD.closeDocument(job.Document.Name)
    result["bound"] = {m.name: lower_bound(geometry["area"], geometry["volume"], m) for m in MODELS}
    return result


# -- the report ------------------------------------------------------------------------------------
def checks(r):
    """What does not hold of a pocket's results, one line each."""
    notes = [] if r["same_stock"] else ["the two Jobs' stocks differ (the replay uses the Plunge Job's)"]
    target = r["geometry"]["volume"]
    for m in MODELS:
        plan, cut = r["plan"][m.name], r["plunge"][m.name]
        planned = {}
        for p in plan["plunges"]:
            planned[p["tool_id"]] = planned.get(p["tool_id"], 0) + 1
        if planned != cut["plunges"]:
            notes.append("%s: G-code plunges per tool %s, the plan's %s" % (m.name, cut["plunges"], planned))
        own = plan["stats"]["volume_removed"]
        if abs(own - cut["removed"]) > CHECK_TOL * target:
            notes.append("%s: the planner says %.1f cm3 removed, the replay %.1f" % (m.name, own / 1e3,
                                                                                  cut["removed"] / 1e3))
    runs = [("Plunge Rough " + k, v) for k, v in r["plunge"].items()] + \
        [("Adaptive " + k, v) for k, v in r["adaptive"].items()]
    for label, cut in runs:
        if abs(cut["removed"] - target) > CHECK_TOL * target:
            notes.append("%s removed %.1f cm3, %.1f %% of the target %.1f cm3 (leaves %.1f cm3 above it)"
                         % (label, cut["removed"] / 1e3, 100 * cut["removed"] / target, target / 1e3,
                            cut["left"] / 1e3))
        if cut["gouge"] > 0.01 * target / 100:
            notes.append("%s cut %.2f cm3 below the part's surface" % (label, cut["gouge"] / 1e3))
        if cut["by_rapids"] > 1e3 * 0.01:
            notes.append("%s: rapids through %.2f cm3 of stock" % (label, cut["by_rapids"] / 1e3))
    a = r["adaptive"][MODELS[0].name]["removed"]
    p = r["plunge"][MODELS[0].name]["removed"]
    if abs(p - a) > CHECK_TOL * target:
        notes.append("Plunge Rough and Adaptive removed %.1f and %.1f cm3: %.1f %% apart"
                     % (p / 1e3, a / 1e3, 100 * abs(p - a) / target))
    return notes


def volume_table(results):
    print("| pocket | target cm3 (area cm2) | removed: Plunge / Adaptive cm3 | left above target: Plunge / "
          "Adaptive cm3 | plunges A; B (T2/T3/T4), levels | Adaptive layers A / B | planning s: Plunge / Adaptive |")
    print("|---|---|---|---|---|---|---|")
    for r in results:
        g, p, a = r["geometry"], r["plunge"]["A"], r["adaptive"]
        counts = "; ".join("%d (%s)" % (sum(r["plunge"][m.name]["plunges"].values()), "/".join(
            str(r["plunge"][m.name]["plunges"].get(t, 0)) for t in (2, 3, 4))) for m in MODELS)
        print("| %s | %.1f (%.1f) | %.1f / %.1f | %.1f / %.1f | %s, %d | %s | %.1f / %.1f |" % (
            r["name"], g["volume"] / 1e3, g["area"] / 1e2, p["removed"] / 1e3, a["A"]["removed"] / 1e3,
            p["left"] / 1e3, a["A"]["left"] / 1e3, counts, r["plan"]["A"]["stats"]["levels"],
            " / ".join(str(a[m.name]["layers"]) for m in MODELS), r["plunge_seconds"]["A"], r["adaptive_seconds"]))


def time_table(results):
    print("| pocket | model | Plunge min (feed / rapid / M6) | Adaptive min (feed / rapid / M6) | lower bound min | "
          "Plunge / Adaptive | Plunge / bound | feed in air: Plunge / Adaptive | planner's estimate min |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in results:
        for m in MODELS:
            p, a, b = r["plunge_minutes"][m.name], r["adaptive_minutes"][m.name], r["bound"][m.name]
            air = [c["air_length"] / max(c["feed_length"], 1e-9) for c in (r["plunge"][m.name],
                                                                          r["adaptive"][m.name])]
            estimate = "%.1f" % r["plan"][m.name]["stats"]["estimated_minutes"]
            print("| %s | %s | %.2f (%.1f / %.1f / %.1f) | %.2f (%.1f / %.1f / %.1f) | %.1f | %.3f | %.2f | "
                  "%.0f %% / %.0f %% | %s |" % (
                      r["name"], m.name, p["total"], p["feed"], p["rapid"], p["changes"], a["total"], a["feed"],
                      a["rapid"], a["changes"], b, p["total"] / a["total"], p["total"] / b, 100 * air[0],
                      100 * air[1], estimate))


def selected_pockets():
    wanted = os.environ.get("PLUNGE_BENCH_POCKETS")
    numbers = [int(n) for n in wanted.split(",")] if wanted else range(1, len(POCKETS) + 1)
    return [(n, POCKETS[n - 1]) for n in numbers]


def main():
    FreeCAD.Units.setSchema(6)  # mm, mm/min (the workbench's preference; this session only)
    results = []
    with tempfile.TemporaryDirectory() as bits:
        for n, pocket in selected_pockets():
            start = time.perf_counter()
            results.append(bench_pocket("%d %s" % (n, pocket.name), pocket, bits))
            print("pocket %d done in %.0f s" % (n, time.perf_counter() - start), file=sys.stderr, flush=True)
    print("\nFreeCAD %s, height field cell %g mm\n" % (".".join(FreeCAD.Version()[:3]), CELL))
    volume_table(results)
    print()
    time_table(results)
    print()
    print("| pocket | mean depth / largest plunger's diameter | Plunge Rough is faster than Adaptive above this "
          "plunge feed (x the side feed) |")
    print("|---|---|---|")
    for r in results:
        g = r["geometry"]
        print("| %s | %.1f | %.2f |" % (r["name"], g["volume"] / g["area"] / 20.0,
                                        break_even(r["plunge_minutes"]["A"], r["adaptive_minutes"]["A"])))
    notes = [(r["name"], n) for r in results for n in checks(r)]
    print("\nchecks (the G-code's plunges per tool = the plan's, the planner's volume = the replay's, volumes "
          "within %g %% of the target and of each other, no gouge, no rapid through stock): %s"
          % (100 * CHECK_TOL, "all hold" if not notes else "these do not hold"))
    for name, note in notes:
        print("- %s: %s" % (name, note))


try:
    main()
except Exception:
    import traceback
    traceback.print_exc()  # freecadcmd itself prints only the exception's message
    raise
finally:
    # FreeCAD 1.1 drops what is still buffered when the script ends.
    sys.stdout.flush()
    sys.stderr.flush()
