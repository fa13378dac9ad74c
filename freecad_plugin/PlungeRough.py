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
import FreeCAD
from PySide.QtCore import QT_TRANSLATE_NOOP

from freecad_plugin import companions, geometry, operation_input, plan_files, planner, rest, tools
from freecad_plugin.plan_input import DEFAULTS, GROWTH_PATTERNS, STRATEGIES
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
             "the walls above them", DEFAULTS["include_fillets"])
        _add(obj, "App::PropertyDistance", "RadialAllowance",
             "Material left on the walls and islands (default 0: set what the finishing pass needs)",
             DEFAULTS["radial_allowance"])
        _add(obj, "App::PropertyDistance", "FloorAllowance",
             "Material left above the floor (default 0: set what the finishing pass needs)",
             DEFAULTS["floor_allowance"])
        _add(obj, "App::PropertyLength", "ChordTolerance",
             "Largest deviation when free-form walls become polylines (added to the radial allowance)",
             DEFAULTS["chord_tolerance"])
        _add(obj, "App::PropertyBool", "UseCannedCycle", "Plunge with G81 (G83 when pecking) instead of G1 moves",
             DEFAULTS["canned_cycle"])
        _add(obj, "App::PropertyBool", "PeckEnabled",
             "Peck the holes drilled into solid that are deeper than Peck Depth (G83 with canned cycles); crescent "
             "plunges beside removed material are never pecked", DEFAULTS["peck"])
        _add(obj, "App::PropertyLength", "PeckDepth",
             "Depth of one peck into solid; 0 = three diameters of each plunger", DEFAULTS["peck_depth"])
        _add(obj, "App::PropertyFloat", "DwellTime",
             "Seconds at the bottom of each pecked hole (explicit moves only; 0: none)", DEFAULTS["dwell"])
        _add(obj, "App::PropertyLength", "MaxWallStock",
             "Thickest material the plunges may leave along walls and islands, beyond the radial allowance "
             "(wall rows spaced for it; 0: clear Min Coverage of the reachable floor instead)",
             DEFAULTS["max_wall_stock"])
        _add(obj, "App::PropertyLength", "MaxFloorStock",
             "Highest stock a sculptured floor may keep above floor + allowance: more plunges where it would "
             "(0: none added)", DEFAULTS["max_floor_stock"])
        _add(obj, "App::PropertyLength", "LeadOut",
             "After reaching depth, feed this far sideways toward cleared space before retracting (explicit moves "
             "only; 0: straight up)", DEFAULTS["lead_out"])
        _add(obj, "App::PropertyBool", "StockAwareHeights",
             "Rapid down to 1 mm above the stock still under each plunge and retract only as high as the next move "
             "needs (explicit moves only); off: every rapid at the safe height", DEFAULTS["stock_aware_heights"])
        _add(obj, "App::PropertyFloat", "MaxEngagement",
             "Widest radial band one plunge may cut, % of each plunger's diameter (100: unlimited); a bit's own "
             "MaxEngagement property wins", 100.0)
        _add(obj, "App::PropertyFloat", "MinEngagement",
             "Narrowest band a plunge should cut, % of the diameter (0: no limit); a bit's own MinEngagement "
             "property wins", 0.0)
        _add(obj, "App::PropertyFloat", "MinCoverage",
             "With Max Wall Stock 0: percentage of the reachable floor the plunges must clear",
             DEFAULTS["min_coverage"])
        _add(obj, "App::PropertyBool", "AutoSelectTools",
             "Let the planner choose which of the plungers to use (shortest estimated time, tool changes "
             "included); the others stay idle. Off: every plunger cuts", DEFAULTS["auto_select"])
        _add(obj, "App::PropertyFloat", "ToolChangeTime",
             "Seconds one tool change takes on the machine: the automatic tool choice weighs it against the "
             "minutes a plunger saves", DEFAULTS["tool_change_time"])
        # What holds the plungers (the planner's holder.hpp), for bits that do not carry their own.
        _add(obj, "App::PropertyLength", "StickOut",
             "Length from each plunger's tip to its holder's face (0: not known, holders not checked); a bit's own "
             "StickOut property wins", 0.0)
        _add(obj, "App::PropertyLength", "HolderDiameter",
             "Diameter of the holders, kept clear of the part and the standing material with the Stick Out (0: not "
             "known, taken as wide as the pocket); a bit's own HolderDiameter property wins", 0.0)
        _add(obj, "App::PropertyLength", "HolderClearance",
             "What holders and shanks keep from the part and the standing material", DEFAULTS["holder_clearance"])
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
            faces = operation_input.selected_faces(obj, tcs)
        except ValueError as e:
            _report(obj, str(e))
            return
        if not faces:
            obj.Summary = translate("PlungeRough", "select the pocket's floor face")
            return
        rest.link_sources(obj, PathUtils.findParentJob(obj))
        workdir = plan_files.plan_folder(obj)
        notes = []
        try:
            plunger = planner.planner()
            data = operation_input.build_input(obj, tcs, faces, workdir, notes, plunger.floors)
            progress = planner.PlanProgress(obj.Label)
            try:
                plan = plunger.plan(data, svg=True, progress=progress)
            finally:
                progress.stop()
            plan_files.write_pictures(workdir, plan)
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
        except (planner.ABORT, planner.Cancelled, RuntimeError) as e:  # the user aborted (Esc): said, nothing cut
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
