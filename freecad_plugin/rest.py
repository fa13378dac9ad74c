"""Rest plunging: the material before a Plunge Rough operation.

The Job's stock solid, whatever its shape, as a height field over the pocket
(the top of the material per cell, docs/plan-format.md "material"), lowered by
what every enabled operation before this one in the Job cuts: which ones, and
over which cells, is said here; their Path commands are replayed by replay.py.
Each cell holds the material at its centre: a rest narrower than a cell may go
unseen (RestResolution). Also the "rest material" document feature (the stock
left after an operation, as a solid); its view provider is rest_gui.py's.

App side: never imports GUI code.
"""
import math

import FreeCAD
from PySide.QtCore import QT_TRANSLATE_NOOP

from freecad_plugin import companions, compat, replay, tools

translate = FreeCAD.Qt.translate

# The RestFrom property's choices.
PREVIOUS, STOCK, NONE = "Previous operations", "Job stock", "None"
REST_FROM = (PREVIOUS, STOCK, NONE)

# The finest automatic cell, and the most cells a grid may have (the planner
# refuses more than 4 million).
MIN_SPACING = 0.2
MAX_CELLS = 1_000_000

def op_property(op, name, default=None):
    """A property of an operation or, for a dressup, of the operation under it."""
    while op is not None:
        if hasattr(op, name):
            return getattr(op, name)
        op = getattr(op, "Base", None) if not isinstance(getattr(op, "Base", None), list) else None
    return default


def earlier(obj, job):
    """The enabled operations before obj in the Job (their paths may not be
    computed yet), obj's own companions (its start holes) left out."""
    own = {c.Name for c in companions.companions(obj)}
    out = []
    for op in job.Operations.Group if job is not None else []:
        if op.Name == obj.Name:
            break
        if op.Name not in own and op_property(op, "Active", True):
            out.append(op)
    return out


def sources(obj, job):
    """The operations before obj that cut: enabled, with a path and a tool
    controller, as (operation, tool controller)."""
    out = []
    for op in earlier(obj, job):
        tc = op_property(op, "ToolController")
        if tc is not None and getattr(op, "Path", None) is not None and op.Path.Commands:
            out.append((op, tc))
    return out


def link_sources(obj, job):
    """Links obj to the operations before it (RestSources), so that a recompute
    plans it after them, and again when they change."""
    linked = earlier(obj, job) if getattr(obj, "RestFrom", NONE) == PREVIOUS else []
    if hasattr(obj, "RestSources") and list(obj.RestSources) != linked:
        obj.RestSources = linked


def spacing_for(obj, lo, hi, tcs):
    """The cell size: the RestResolution property, or a 64th of the smallest
    plunger's diameter (at least MIN_SPACING), coarsened to at most MAX_CELLS."""
    asked = obj.RestResolution.Value if hasattr(obj, "RestResolution") else 0.0
    h = asked if asked > 0 else max(MIN_SPACING, min(tools.diameter(tc) for tc in tcs) / 64.0)
    area = (hi[0] - lo[0]) * (hi[1] - lo[1])
    return max(h, math.sqrt(area / MAX_CELLS))


def material(obj, job, tcs, region, top_z, progress=None):
    """The "material" plan input for obj (None: the full stock, today's box),
    and the notes for the summary. region: (lo, hi) of the pocket in XY."""
    rest_from = getattr(obj, "RestFrom", NONE)
    if rest_from == NONE or job is None or getattr(job, "Stock", None) is None:
        return None, []
    margin = max(tools.diameter(tc) for tc in tcs)  # the widest plunge past the pocket's edge, and a cell
    lo = (region[0][0] - margin, region[0][1] - margin)
    hi = (region[1][0] + margin, region[1][1] + margin)
    grid = replay.grid_over(lo, hi, spacing_for(obj, lo, hi, tcs), top_z)
    grid["top"] = replay.stock_tops(job.Stock.Shape, grid, top_z)
    notes = []
    if rest_from == PREVIOUS:
        notes = replay.replay_onto(grid, sources(obj, job), job.Stock.Shape.BoundBox.ZMax, progress)
    if _full(grid, region, top_z):
        return None, notes  # nothing cut yet, stock all over the pocket: the full stock
    return grid, notes


def _full(grid, region, top_z):
    """Whether the material stands at top_z over the whole pocket's box (the
    margin around it lies in the part's walls, where no plunge goes)."""
    nx, h = grid["nx"], grid["spacing"]
    x0, y0 = grid["origin"]
    i0, i1 = int((region[0][0] - x0) // h), int((region[1][0] - x0) // h)
    j0, j1 = int((region[0][1] - y0) // h), int((region[1][1] - y0) // h)
    top = grid["top"]
    return all(min(top[j * nx + i0:j * nx + i1 + 1]) >= top_z - 1e-9 for j in range(j0, j1 + 1))


# -- the material an operation hands on ---------------------------------------------------
def through(op, job):
    """The operations that cut, up to op and its companions (its other plungers
    and start holes), as (operation, tool controller)."""
    mine = {op.Name} | {c.Name for c in companions.companions(op)}
    group = list(job.Operations.Group)
    last = max(i for i, o in enumerate(group) if o.Name in mine)
    out = []
    for o in group[:last + 1]:
        tc = op_property(o, "ToolController")
        if op_property(o, "Active", True) and tc is not None and o.Path.Commands:
            out.append((o, tc))
    return out


def material_after(op, resolution=0.0):
    """The material left after op (and everything before it) over the whole
    stock, as a grid (docs/plan-format.md "material")."""
    job = compat.PathUtils.findParentJob(op)
    box = job.Stock.Shape.BoundBox
    lo, hi = (box.XMin, box.YMin), (box.XMax, box.YMax)
    # Coarser than the planner's: a solid to look at and to start a Job from.
    h = resolution if resolution > 0 else max(MIN_SPACING, min(tools.diameter(tc) for tc in
                                                                companions.tool_controllers(op)) / 16.0)
    h = max(h, math.sqrt((hi[0] - lo[0]) * (hi[1] - lo[1]) / MAX_CELLS))
    grid = replay.grid_over(lo, hi, h, box.ZMax)
    grid["top"] = replay.stock_tops(job.Stock.Shape, grid, box.ZMax)
    replay.replay_onto(grid, through(op, job), box.ZMax)
    return grid


def grid_solid(grid, bottom, step=0.01):
    """A compound of boxes from `bottom` up to each cell's top (heights rounded
    up to `step`): cells of one height merged into rectangles, row runs first,
    then equal runs of consecutive rows."""
    import Part
    nx, ny, h = grid["nx"], grid["ny"], grid["spacing"]
    x0, y0 = grid["origin"]
    tops = [math.ceil((t - 1e-9) / step) * step for t in grid["top"]]
    open_runs = {}  # (i0, i1, z) -> first row
    boxes = []

    def close(key, j0, j1):
        i0, i1, z = key
        boxes.append(Part.makeBox((i1 - i0) * h, (j1 - j0) * h, z - bottom,
                                  FreeCAD.Vector(x0 + i0 * h, y0 + j0 * h, bottom)))

    for j in range(ny + 1):
        runs = set()
        if j < ny:
            row = tops[j * nx:(j + 1) * nx]
            i = 0
            while i < nx:
                k = i
                while k + 1 < nx and row[k + 1] == row[i]:
                    k += 1
                if row[i] > bottom + 1e-9:
                    runs.add((i, k + 1, row[i]))
                i = k + 1
        for key in [k for k in open_runs if k not in runs]:
            close(key, open_runs.pop(key), j)
        for key in runs:
            open_runs.setdefault(key, j)
    return Part.makeCompound(boxes)


class RestSolid:
    """Proxy of the rest material feature: the stock a Plunge Rough operation
    leaves (wall band, floor rest, scallops between plunges) with everything
    before it in the Job, as a solid over the Job's stock. Show or hide it,
    or use it as the stock of a later Job; a later Plunge Rough replays the
    same paths (Rest From)."""

    def __init__(self, obj, op):
        obj.addProperty("App::PropertyLink", "Operation", "Rest",
                        QT_TRANSLATE_NOOP("App::Property", "The Plunge Rough operation whose rest this is"))
        # A plain link list (hidden in the editor): FreeCAD's hidden links do
        # not order the recompute.
        obj.addProperty("App::PropertyLinkList", "Sources", "Rest",
                        QT_TRANSLATE_NOOP("App::Property", "The operations replayed (recomputed after them)"))
        obj.setEditorMode("Sources", 2)
        obj.addProperty("App::PropertyLength", "Resolution", "Rest",
                        QT_TRANSLATE_NOOP("App::Property", "Cell size; 0: a 16th of the operation's smallest "
                                          "plunger's diameter, at least 0.2 mm"))
        obj.Operation = op
        obj.Proxy = self

    def execute(self, obj):
        op = obj.Operation
        job = compat.PathUtils.findParentJob(op) if op is not None else None
        if job is None:
            FreeCAD.Console.PrintError("%s: no Plunge Rough operation in a Job to take the rest of\n" % obj.Label)
            return
        ops = [o for o, _ in through(op, job)]
        if list(obj.Sources) != ops:
            obj.Sources = ops
        grid = material_after(op, obj.Resolution.Value)
        obj.Shape = grid_solid(grid, job.Stock.Shape.BoundBox.ZMin)

    def dumps(self):
        return None

    def loads(self, state):
        return None


def rest_solid_of(op):
    """The operation's rest material feature, if it has one."""
    for o in op.InList:
        if isinstance(getattr(o, "Proxy", None), RestSolid) and o.Operation == op:
            return o
    return None


def make_rest_solid(op, view=None):
    """The rest material feature of a Plunge Rough operation, recomputed; the
    GUI gives its view provider as view(obj), before the recompute
    (rest_gui.make_and_show)."""
    obj = op.Document.addObject("Part::FeaturePython", "PlungeRoughRest")
    RestSolid(obj, op)
    if view is not None and obj.ViewObject is not None:
        view(obj)
    obj.Label = "%s rest" % op.Label
    op.Document.recompute()
    return obj
