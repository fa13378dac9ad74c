"""The Plunge Rough operation (App side: properties, planning, paths).

One Plunge Rough operation plans the pocket once for all its plunger tool
controllers (ToolControllers). Its own path holds the plunges of the largest
plunger; every other plunger gets a companion operation ("Plunge Rough T2 ...")
right after it in the Job, holding that tool's plunges from the same plan. So
each plunge is made by the tool the plan gave it, the post processor writes a
tool change before each tool's plunges, and the Path simulator cuts each tool's
plunges with that tool.

This module never imports GUI code: it runs headless (freecadcmd).
"""
import json
import os
import tempfile

import FreeCAD
import Part
from PySide.QtCore import QT_TRANSLATE_NOOP

from freecad_plugin import companions, geometry, planner, rest, tools
from freecad_plugin.compat import PathFeedRate, PathJob, PathOp, PathUtils

__title__ = "Plunge Rough operation"
__doc__ = "Plunge roughing of pockets: circle packing, gap covering, sequencing, depths."

translate = FreeCAD.Qt.translate

# Properties the job's setup sheet can carry defaults for.
SETUP_PROPERTIES = ["IncludeFillets", "RadialAllowance", "FloorAllowance", "ChordTolerance", "UseCannedCycle",
                    "PeckEnabled", "PeckDepth", "DwellTime",
                    "MinCoverage", "AutoSelectTools", "Strategy", "MaxWallStock", "MaxFloorStock", "LeadOut",
                    "StockAwareHeights", "MaxEngagement", "MinEngagement", "ToolChangeTime", "GrowthPattern",
                    "StickOut", "HolderDiameter", "HolderClearance"]

# GrowthPattern property values -> the planner's "growth_pattern".
GROWTH_PATTERNS = {"Auto": "auto", "Rows": "rows", "Offsets": "offsets"}

# Strategy property values -> the planner's "strategy" and "grid" input.
STRATEGIES = {
    "Packing": {},
    "Grid (honeycomb)": {"strategy": "grid", "grid": {"pattern": "honeycomb"}},
    "Grid (square)": {"strategy": "grid", "grid": {"pattern": "square"}},
}


def mount_of(obj):
    """The operation's stick-out, holder diameter and holder clearance in mm
    (files from before them: none known, 1 mm)."""
    def mm(name, default):
        value = getattr(obj, name, None)
        return float(value.Value) if value is not None else default
    return mm("StickOut", 0.0), mm("HolderDiameter", 0.0), mm("HolderClearance", 1.0)


def SetupProperties():
    return list(SETUP_PROPERTIES)


def _report(obj, message, error=True):
    """A problem the user must see: the report view (an error; a warning for
    what the user asked for, a cancel), the op's summary, an empty path, and
    companions that stay out of the program (no tool change without plunges
    after it) until the operation plans again."""
    (FreeCAD.Console.PrintError if error else FreeCAD.Console.PrintWarning)("%s: %s\n" % (obj.Label, message))
    obj.Summary = message
    companions.deactivate(obj)


class _PlanAgain:
    """After a cancelled plan: once the recompute that ran it is over, marks
    the operation to be recomputed, so that the next recompute plans it (a
    touch inside execute() is cleared when it returns)."""

    def __init__(self, obj):
        self.obj = obj

    def slotRecomputedDocument(self, doc):
        FreeCAD.removeDocumentObserver(self)
        try:
            if doc == self.obj.Document:
                self.obj.touch()
        except (ReferenceError, RuntimeError):  # the operation was deleted meanwhile
            pass


def _add(obj, kind, name, tip, default=None, mode=None):
    if not hasattr(obj, name):
        obj.addProperty(kind, name, "Plunge Rough", QT_TRANSLATE_NOOP("App::Property", tip))
        if default is not None:
            # Lengths as quantities: the setup sheet's op prototypes (the Job
            # panel's "Op Defaults") keep the value as given and expect units.
            if kind in ("App::PropertyDistance", "App::PropertyLength"):
                default = FreeCAD.Units.Quantity(default, FreeCAD.Units.Length)
            setattr(obj, name, default)
    if mode is not None:
        obj.setEditorMode(name, mode)


class ObjectPlungeRough(PathOp.ObjectOp):
    """Proxy of the Plunge Rough operation."""

    def __init__(self, obj, name, parentJob=None):
        # While FreeCAD picks the new operation's tool controller, only the
        # largest plunger is offered: it is the operation's own, so FreeCAD
        # need not ask (opSetDefaultValues then ticks every plunger).
        self._creating = True
        try:
            super().__init__(obj, name, parentJob)
        finally:
            self._creating = False

    def isToolSupported(self, obj, tool):
        job = PathUtils.findParentJob(obj) or getattr(self, "job", None)
        plungers = tools.job_plungers(job)
        if getattr(self, "_creating", False):
            return bool(plungers) and plungers[0].Tool == tool
        return any(tc.Tool == tool for tc in plungers)

    def opFeatures(self, obj):
        return (PathOp.FeatureTool | PathOp.FeatureDepths | PathOp.FeatureHeights | PathOp.FeatureBaseFaces
                | PathOp.FeatureCoolant)

    def initOperation(self, obj):
        self._addProperties(obj)

    def _addProperties(self, obj):
        _add(obj, "App::PropertyLinkList", "ToolControllers",
             "All plunger tool controllers to use; the largest one is this operation's own")
        _add(obj, "App::PropertyBool", "IncludeFillets",
             "The fillets between the selected floor and its walls belong to the floor: roughed as floor, up to "
             "the walls above them", True)
        _add(obj, "App::PropertyDistance", "RadialAllowance", "Material left on the walls and islands", 0.0)
        _add(obj, "App::PropertyDistance", "FloorAllowance", "Material left above the floor", 0.0)
        _add(obj, "App::PropertyLength", "ChordTolerance",
             "Largest deviation when free-form walls become polylines (added to the radial allowance)", 0.01)
        _add(obj, "App::PropertyBool", "UseCannedCycle", "Plunge with G81 (G83 when pecking) instead of G1 moves",
             False)
        _add(obj, "App::PropertyBool", "PeckEnabled",
             "Peck the holes drilled into solid that are deeper than Peck Depth (G83 with canned cycles); crescent "
             "plunges beside removed material are never pecked", True)
        _add(obj, "App::PropertyLength", "PeckDepth",
             "Depth of one peck into solid; 0 = three diameters of each plunger", 0.0)
        _add(obj, "App::PropertyFloat", "DwellTime",
             "Seconds at the bottom of each pecked hole (explicit moves only; 0: none)", 0.0)
        _add(obj, "App::PropertyLength", "MaxWallStock",
             "Thickest material the plunges may leave along walls and islands, beyond the radial allowance "
             "(wall rows spaced for it; 0: clear Min Coverage of the reachable floor instead)", 1.0)
        _add(obj, "App::PropertyLength", "MaxFloorStock",
             "Highest stock a sculptured floor may keep above floor + allowance: more plunges where it would "
             "(0: none added)", 1.0)
        _add(obj, "App::PropertyLength", "LeadOut",
             "After reaching depth, feed this far sideways toward cleared space before retracting (explicit moves "
             "only; 0: straight up)", 0.5)
        _add(obj, "App::PropertyBool", "StockAwareHeights",
             "Rapid down to 1 mm above the stock still under each plunge and retract only as high as the next move "
             "needs (explicit moves only); off: every rapid at the safe height", True)
        _add(obj, "App::PropertyFloat", "MaxEngagement",
             "Widest radial band one plunge may cut, % of each plunger's diameter (100: unlimited); a bit's own "
             "MaxEngagement property wins", 100.0)
        _add(obj, "App::PropertyFloat", "MinEngagement",
             "Narrowest band a plunge should cut, % of the diameter (0: no limit); a bit's own MinEngagement "
             "property wins", 0.0)
        _add(obj, "App::PropertyFloat", "MinCoverage",
             "With Max Wall Stock 0: percentage of the reachable floor the plunges must clear", 99.6)
        _add(obj, "App::PropertyBool", "AutoSelectTools",
             "Let the planner choose which of the plungers to use (shortest estimated time, tool changes "
             "included); the others stay idle. Off: every plunger cuts", True)
        _add(obj, "App::PropertyFloat", "ToolChangeTime",
             "Seconds one tool change takes on the machine: the automatic tool choice weighs it against the "
             "minutes a plunger saves", 20.0)
        # What holds the plungers (the planner's holder.hpp), for bits that do not carry their own.
        _add(obj, "App::PropertyLength", "StickOut",
             "Length from each plunger's tip to its holder's face (0: not known, holders not checked); a bit's own "
             "StickOut property wins", 0.0)
        _add(obj, "App::PropertyLength", "HolderDiameter",
             "Diameter of the holders, kept clear of the part and the standing material with the Stick Out (0: not "
             "known, taken as wide as the pocket); a bit's own HolderDiameter property wins", 0.0)
        _add(obj, "App::PropertyLength", "HolderClearance",
             "What holders and shanks keep from the part and the standing material", 1.0)
        if not hasattr(obj, "GrowthPattern"):
            _add(obj, "App::PropertyEnumeration", "GrowthPattern",
                 "With a Max Engagement: how the cut grows from its starts, along rows, along offsets of the walls, "
                 "or whichever plans fewer plunges (Auto)")
            obj.GrowthPattern = list(GROWTH_PATTERNS)
            obj.GrowthPattern = "Auto"
        if not hasattr(obj, "Strategy"):
            _add(obj, "App::PropertyEnumeration", "Strategy",
                 "Packing and covering (default), or a regular grid of plunges (the baseline CAM systems offer)")
            obj.Strategy = list(STRATEGIES)
            obj.Strategy = "Packing"
        if not hasattr(obj, "RestFrom"):
            _add(obj, "App::PropertyEnumeration", "RestFrom",
                 "The material the plunges start from: the Job's stock less what the enabled operations before this "
                 "one cut (their paths replayed), the Job's stock solid alone, or none (solid stock from the start "
                 "depth down)")
            obj.RestFrom = list(rest.REST_FROM)
            obj.RestFrom = rest.STOCK
        _add(obj, "App::PropertyLength", "RestResolution",
             "Cell size of the material model (Rest From): a rest narrower than about two cells at the edge of "
             "what the operations before cut is not seen; 0: a 64th of the smallest plunger's diameter, at least "
             "0.2 mm", 0.0)
        # A plain link list, hidden in the editor: FreeCAD's hidden links do not
        # order the recompute.
        _add(obj, "App::PropertyLinkList", "RestSources",
             "The operations before this one whose paths the plan started from (Rest From): this operation plans "
             "again after they change", mode=2)
        _add(obj, "App::PropertyString", "Summary", "The last plan: plunges per tool, coverage, travel, time",
             "", mode=1)
        _add(obj, "App::PropertyString", "PlanData", "The last plan and its input (JSON), read by the companions",
             "", mode=2)

    def opOnDocumentRestored(self, obj):
        # Files from older versions lack newer properties, and their companions
        # have labels with parentheses (nested comments in G-code). A file from
        # before the tool choice existed used every plunger: it still does.
        # One from before rest plunging planned for solid stock from its start depth.
        chose = hasattr(obj, "AutoSelectTools")
        rested = hasattr(obj, "RestFrom")
        self._addProperties(obj)
        if not chose:
            obj.AutoSelectTools = False
        if not rested:
            obj.RestFrom = rest.NONE
        for comp in companions.companions(obj):
            label = companions.companion_label(obj, comp.ToolController, bool(getattr(comp, "StartHoles", False)))
            if comp.ToolController is not None and comp.Label != label:
                comp.Label = label

    def opSetDefaultValues(self, obj, job):
        # Every plunger of the Job, largest as the operation's own; whatever
        # FreeCAD chose (the previous operation's tool controller) otherwise.
        plungers = tools.job_plungers(job)
        if plungers:
            obj.ToolController = plungers[0]
            obj.ToolControllers = plungers
        elif obj.ToolController and not obj.ToolControllers:
            obj.ToolControllers = [obj.ToolController]
        companions.syncCompanions(obj)  # the proxy is not attached yet: opOnChanged does not run
        # Rest plunging after whatever the Job already does to the stock.
        obj.RestFrom = rest.PREVIOUS if rest.earlier(obj, job) else rest.STOCK
        rest.link_sources(obj, job)

    def opUpdateDepths(self, obj):
        # FreeCAD takes the highest of the selected faces' bottoms; a pocket with
        # several levels is roughed down to its lowest point (a plane's own
        # height: a curved face's box depends on whether it was drawn yet).
        faces = [base.Shape.getElement(sub) for base, subs in obj.Base for sub in subs if sub.startswith("Face")]
        if len(faces) > 1:
            lowest = min(f.Surface.Position.z if geometry.is_horizontal_plane(f) else f.BoundBox.ZMin for f in faces)
            if abs(obj.OpFinalDepth.Value - lowest) > 1e-9:
                obj.OpFinalDepth = lowest

    def opOnChanged(self, obj, prop):
        # Not while a file loads or an undo/redo replays the document: those
        # restore the companions themselves.
        settled = "Restore" not in obj.State and not obj.Document.Transacting
        if prop == "ToolControllers" and settled and hasattr(obj, "PlanData"):
            companions.syncCompanions(obj)
        if prop == "Active" and settled:
            for comp in companions.companions(obj):  # the plan's other tools follow the operation
                if not obj.Active and comp.Active:
                    comp.Active = False
                elif obj.Active and not comp.Active and not obj.AutoSelectTools:
                    comp.Active = True
        if prop == "AutoSelectTools" and "Restore" not in obj.State and not obj.AutoSelectTools:
            tcs = companions.tool_controllers(obj)
            if tcs and obj.ToolController != tcs[0]:  # the largest plunger again
                obj.ToolController = tcs[0]
            for comp in companions.companions(obj):  # every plunger works again
                if not comp.Active:
                    comp.Active = True

    def opExecute(self, obj):
        obj.PlanData = ""
        tcs = companions.tool_controllers(obj)
        try:
            faces = selected_faces(obj, tcs)
        except ValueError as e:
            _report(obj, str(e))
            return
        if not faces:
            obj.Summary = translate("PlungeRough", "select the pocket's floor face")
            return
        rest.link_sources(obj, PathUtils.findParentJob(obj))
        workdir = plan_folder(obj)
        notes = []
        try:
            plunger = planner.planner()
            data = build_input(obj, tcs, faces, workdir, notes, plunger.floors)
            progress = planner.PlanProgress(obj.Label)
            try:
                plan = plunger.plan(data, svg=True, progress=progress)
            finally:
                progress.stop()
            write_pictures(workdir, plan)
            companions.hold_plan_data(obj, {"input": data, "plan": plan})
            report_plan(obj, plan, notes, plunger.name)
            own_tc, problem = companions.activate_companions(obj, plan, tcs)
        except ValueError as e:
            _report(obj, str(e))
            return
        except planner.PlannerFailed as e:  # crashed or killed: said, nothing cut, planned again
            _report(obj, "%s: %s" % (e, translate("PlungeRough", "nothing is cut until it plans again "
                                                     "(the next recompute)")))
            FreeCAD.addDocumentObserver(_PlanAgain(obj))
            return
        except (planner.ABORT, RuntimeError) as e:  # the user aborted (Esc): said, nothing cut
            if not planner.is_abort(e):
                raise
            _report(obj, translate("PlungeRough", "planning cancelled: nothing is cut until it plans again "
                                   "(the next recompute)"), error=False)
            FreeCAD.addDocumentObserver(_PlanAgain(obj))
            return
        if own_tc is None:
            _report(obj, problem)
            obj.PlanData = ""
            return
        self.commandlist.extend(companions.toolCommands(obj, companions.plunges_of_tool(plan, own_tc)))
        PathFeedRate.setFeedRate(self.commandlist, own_tc)


def selected_faces(obj, tcs):
    """The selected floor faces as (name, face); ValueError naming what stops the
    operation from planning: its tool controllers, an edge selected, a deleted companion."""
    # With the automatic choice the operation itself takes the largest plunger
    # the plan uses (activate_companions); otherwise its tool controller is the largest.
    if tcs and obj.ToolController != tcs[0] and not (obj.AutoSelectTools and obj.ToolController in tcs):
        raise ValueError(translate("PlungeRough", "the operation's tool controller must be its largest plunger (%s)")
                         % tcs[0].Label)
    faces = []
    for base, subs in obj.Base:
        for sub in subs:
            if not sub.startswith("Face"):
                raise ValueError(translate("PlungeRough", "%s.%s is not a face: select the pocket's floor face")
                                 % (base.Label, sub))
            faces.append(("%s.%s" % (base.Label, sub), base.Shape.getElement(sub)))
    if not faces:
        return faces
    diameters = [tools.diameter(tc) for tc in tcs]
    if len(set(diameters)) != len(diameters):
        raise ValueError(translate("PlungeRough", "two plunger tool controllers have the same diameter"))
    # Each further plunger cuts through its companion operation: without it
    # its plunges would silently be missing from the simulation and G-code.
    have = {comp.ToolController for comp in companions.companions(obj)}
    missing = [tc for tc in tcs[1:] if tc not in have]
    if missing:
        raise ValueError(translate("PlungeRough", "the operation of plunger %s was deleted, so its plunges would "
                                   "not be cut: untick it in the plunger list (or tick it again)")
                         % ", ".join(tc.Label for tc in missing))
    return faces


def check_settings(obj, tcs):
    """ValueError for heights and bits the planner cannot be given."""
    depth = obj.StartDepth.Value - obj.FinalDepth.Value
    for tc in tcs:
        length = tools.bit_length(tc.Tool, "Length")
        if length and length < depth:
            raise ValueError("%s is %g mm long, shorter than the pocket is deep (%g mm): use a longer tool"
                             % (tc.Label, length, depth))
    if obj.SafeHeight.Value > obj.ClearanceHeight.Value:
        raise ValueError("the safe height is above the clearance height")
    if obj.StartDepth.Value <= obj.FinalDepth.Value:
        raise ValueError("the start depth must be above the final depth")


def model_of(obj):
    """The part the selected faces belong to (walls, fillets and open sides are
    found on it)."""
    shapes = [base.Shape for base, subs in obj.Base if subs]
    return shapes[0] if len(shapes) == 1 else Part.makeCompound(shapes)


def build_input(obj, tcs, faces, workdir, notes=None, floors=("z", "brep")):
    """The planner's input (docs/plan-format.md) for the operation's properties,
    its plunger tool controllers (largest first) and its floor faces (with the
    part's fillets and open sides, geometry.pocket). Writes nothing but a
    sculptured floor's BREP into workdir; ValueError names a bad setting or face.
    notes: a list that gets what the summary should say of the pocket."""
    # Past an open side the plunges reach as far as the wall band guarantee
    # needs to cut up to the edge, and a little more.
    margin = obj.RadialAllowance.Value + obj.MaxWallStock.Value + 0.5
    pocket = geometry.pocket(faces, obj.ChordTolerance.Value, obj.IncludeFillets, margin, model_of(obj))
    if notes is not None:
        notes.extend(pocket.notes())
    check_settings(obj, tcs)
    # Where the pocket widens above its floor, the wall band is kept there too.
    sections, deviation = geometry.sections(model_of(obj), pocket, obj.StartDepth.Value,
                                                obj.MaxWallStock.Value) \
        if obj.MaxWallStock.Value > 0 else ([], 0.0)
    deviation = max(deviation, pocket.deviation)
    data = {
        "version": 1,
        "boundary": pocket.boundary,
        "islands": pocket.islands,
        "tools": [tools.spec(tc, obj.MaxEngagement, obj.MinEngagement, tools.Mount(*mount_of(obj)[:2])) for tc in tcs],
        "holder_clearance": mount_of(obj)[2],
        # Rapids and retracts at the first plunger's rapid rates, as the post runs them.
        "time_model": tools.time_model(tcs[0], getattr(obj, "ToolChangeTime", 20.0)),
        "top_z": obj.StartDepth.Value,
        "safe_z": obj.SafeHeight.Value,
        "floor": geometry.floor_spec(pocket, obj.FinalDepth.Value, workdir, floors),
        # FinalDepth is the deepest any plunge goes.
        "final_depth": obj.FinalDepth.Value,
        # The chords of a discretised free-form wall may lie off it by the
        # measured deviation: keeping that much more from the walls never gouges.
        "allowance": {"radial": obj.RadialAllowance.Value + deviation + 1e-6,
                      "floor": obj.FloorAllowance.Value},
        "min_coverage": obj.MinCoverage / 100.0,
        "max_wall_stock": obj.MaxWallStock.Value,
        "max_floor_stock": obj.MaxFloorStock.Value,
        # Lead-out and stock-aware heights are explicit moves: a canned cycle has neither.
        "lead_out": 0.0 if obj.UseCannedCycle else obj.LeadOut.Value,
        "stock_aware_heights": bool(obj.StockAwareHeights and not obj.UseCannedCycle),
        "peck": bool(obj.PeckEnabled),
        "growth_pattern": GROWTH_PATTERNS.get(getattr(obj, "GrowthPattern", "Auto"), "auto"),
    }
    if sections:
        data["sections"] = sections
    xs = [p[0] for p in pocket.boundary]
    ys = [p[1] for p in pocket.boundary]
    material, rest_notes = rest.material(obj, PathUtils.findParentJob(obj), tcs, ((min(xs), min(ys)), (max(xs), max(ys))),
                                         obj.StartDepth.Value)
    if material is not None:
        data["material"] = material
    if notes is not None:
        notes.extend(rest_notes)
    if obj.DwellTime > 0 and not obj.UseCannedCycle:
        data["peck_dwell"] = obj.DwellTime
    if obj.PeckDepth.Value > 0:
        for tool in data["tools"]:
            tool["peck_depth"] = obj.PeckDepth.Value
    data.update(STRATEGIES.get(obj.Strategy, {}))
    if obj.AutoSelectTools:
        data["tool_library"] = data.pop("tools")
        data["tools"] = "auto"
    return data


def plan_folder(obj, create=True):
    """The operation's own folder for its floor BREP and plan picture."""
    workdir = os.path.join(tempfile.gettempdir(), "plungerough-%s-%s" % (obj.Document.Name, obj.Name))
    if create:
        os.makedirs(workdir, exist_ok=True)
    return workdir


def report_plan(obj, plan, notes=(), planned_by=None):
    """The plan's summary on the operation (with what it says of the pocket:
    fillets added, open sides, the planner that made it), its stock and
    warnings in the report view."""
    warnings = list(plan.get("warnings", []))
    post_warning = canned_cycle_warning(obj)
    if post_warning:
        warnings.append(post_warning)
    notes = list(notes) + ([translate("PlungeRough", "planned by %s") % planned_by] if planned_by else [])
    text = plan["summary"]  # the planner's own words (the CLI's summary, with the plungers chosen)
    obj.Summary = "; ".join([text] + warnings + list(notes))
    FreeCAD.Console.PrintMessage("%s: %s\n" % (obj.Label, text))
    for note in notes:
        FreeCAD.Console.PrintMessage("%s: %s\n" % (obj.Label, note))
    for warning in warnings:
        FreeCAD.Console.PrintWarning("%s: %s\n" % (obj.Label, warning))


def canned_cycle_warning(obj):
    """Grbl has no canned cycles; FreeCAD's grbl post passes G81/G83 through
    unless it is told to translate them."""
    job = PathUtils.findParentJob(obj)
    if not obj.UseCannedCycle or job is None:
        return None
    post = str(getattr(job, "PostProcessor", "") or "").lower()
    args = str(getattr(job, "PostProcessorArgs", "") or "")
    if "grbl" in post and "--translate_drill" not in args:
        return translate("PlungeRough", "the Job posts with grbl, which has no canned cycles: add --translate_drill "
                         "to the Job's post processor arguments, or turn canned cycles off")
    return None


# The plan's pictures, one per question: (key in the planner's result, file, title).
PICTURES = (("svg", "plan.svg", "The plan"),
            ("svg_stock", "plan-stock.svg", "Stock left"),
            ("svg_heights", "plan-heights.svg", "Stop heights"))


def write_pictures(workdir, plan):
    """The planner's pictures into the operation's folder (taken out of the plan);
    a view the plan has not (stop heights over a flat floor) is removed."""
    for key, name, _ in PICTURES:
        path = os.path.join(workdir, name)
        picture = plan.pop(key, None)
        if picture is None:
            if os.path.exists(path):
                os.remove(path)
            continue
        with open(path, "w") as f:
            f.write(picture)


def plan_pictures(obj):
    """[(title, path)] of the pictures of the operation's last plan that exist."""
    folder = plan_folder(obj, create=False)
    return [(title, os.path.join(folder, name)) for _, name, title in PICTURES
            if os.path.exists(os.path.join(folder, name))]


def plan_picture(obj, name="plan.svg"):
    """Path of one picture of the operation's last plan (plan.svg: the plan)."""
    return os.path.join(plan_folder(obj, create=False), name)


# The tool controller questions live in tools.py; these names stay for callers
# that ask the operation's module.
is_plunger = tools.is_plunger
job_plungers = tools.job_plungers

# Files saved before the companions had their own module name this class as
# freecad_plugin.PlungeRough.ObjectPlungeRoughTool; plan_of is the operation's.
ObjectPlungeRoughTool = companions.ObjectPlungeRoughTool
plan_of = companions.plan_of


def register():
    """Lets job setup sheets carry defaults for the operation. The companions are
    internal: they have no defaults of their own and are not offered there."""
    from freecad_plugin.compat import PathSetupSheet
    PathSetupSheet.RegisterOperation("PlungeRough", Create, SetupProperties)


def _active_job():
    """The Job a new operation goes into when none is given: the only one."""
    doc = FreeCAD.ActiveDocument
    jobs = [o for o in (doc.Objects if doc else []) if isinstance(getattr(o, "Proxy", None), PathJob.ObjectJob)]
    return jobs[0] if len(jobs) == 1 else None


def Create(name, obj=None, parentJob=None):
    """Create(name) ... a Plunge Rough operation, as FreeCAD's own operations do."""
    if obj is None:
        job = parentJob or _active_job()
        if job is not None and not tools.job_plungers(job):
            raise ValueError(translate(
                "PlungeRough", "the Job has no plunger: add a tool controller with a flat, ball or bull-nose bit and "
                "a vertical feed (the plunge feed)"))
        obj = FreeCAD.ActiveDocument.addObject("Path::FeaturePython", name)
    obj.Proxy = ObjectPlungeRough(obj, name, parentJob)
    return obj


register()
