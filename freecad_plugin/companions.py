"""The companion operations of a Plunge Rough operation, and their management.

One Plunge Rough operation plans the pocket once for all its plunger tool
controllers. Its own path holds the plunges of the largest plunger; every other
plunger gets a companion operation ("PlungeRough T3 12 mm") right after it in
the Job, holding that tool's plunges from the same plan, and each plunge mill
that does not cut at its centre a start hole companion before it. So each
plunge is made by the tool the plan gave it, the post processor writes a tool
change before each tool's plunges, and the Path simulator cuts each tool's
plunges with that tool.

App side: never imports GUI code.
"""
import json

import FreeCAD
from PySide.QtCore import QT_TRANSLATE_NOOP

from freecad_plugin import generator, planner, tools
from freecad_plugin.compat import PathFeedRate, PathOp, PathUtils

translate = FreeCAD.Qt.translate


def tool_controllers(obj):
    """The plunger tool controllers, largest first (the op's own one if none is listed)."""
    tcs = []
    for tc in list(obj.ToolControllers) or ([obj.ToolController] if obj.ToolController else []):
        if tc is not None and tc not in tcs:
            tcs.append(tc)
    return tools.largest_first(tcs)


def plunges_of_tool(plan, tc, start_holes=False):
    """The plan's plunges made by the tool controller's tool, in order: its start
    holes for non-centre-cutting plungers, or its own plunges."""
    number = tools.number(tc)
    return [p for p in plan["plunges"] if p["tool_id"] == number and bool(p.get("start_hole")) == start_holes]


def toolCommands(op, plunges):
    """One tool's plunges as Path commands, with the main operation's heights,
    cycle and pecks (the tool's peck depth and the clearance as planned)."""
    data = plan_data(op) or {"input": {}, "plan": {"stats": {"per_tool": []}}}
    ids = {p["tool_id"] for p in plunges}
    peck = max([t.get("peck_depth", 0.0) for t in data["plan"]["stats"]["per_tool"] if t["tool_id"] in ids] or [0.0])
    return generator.generate(plunges, op.ClearanceHeight.Value, op.SafeHeight.Value, op.UseCannedCycle, peck,
                              rapid_clearance=data["input"].get("rapid_clearance", 1.0),
                              dwell=getattr(op, "DwellTime", 0.0))


class ObjectPlungeRoughTool(PathOp.ObjectOp):
    """Proxy of a companion operation: one more plunger's plunges of a Plunge Rough plan."""

    def opFeatures(self, obj):
        return PathOp.FeatureTool | PathOp.FeatureCoolant

    def initOperation(self, obj):
        if not hasattr(obj, "PlanOperation"):
            obj.addProperty("App::PropertyLink", "PlanOperation", "Plunge Rough",
                            QT_TRANSLATE_NOOP("App::Property", "The Plunge Rough operation whose plan this follows"))

    def opExecute(self, obj):
        main = obj.PlanOperation
        plan = plan_of(main) if main is not None and main.Active else None
        if plan is None:
            return
        plunges = plunges_of_tool(plan, obj.ToolController, bool(getattr(obj, "StartHoles", False)))
        if obj.CoolantMode != main.CoolantMode:
            obj.CoolantMode = main.CoolantMode
        self.commandlist.extend(toolCommands(main, plunges))
        PathFeedRate.setFeedRate(self.commandlist, obj.ToolController)


def plan_data(obj):
    """The last plan of a Plunge Rough operation and its input, {"input", "plan"}
    (docs/plan-format.md), or None. The objects the planner handed over in
    this session (hold_plan_data); PlanData, the document's copy, is parsed
    only once after the document was opened."""
    text = obj.PlanData
    if not text:
        return None
    proxy = getattr(obj, "Proxy", None)
    held = getattr(proxy, "_plan_data", None)
    if held is None or held[0] != text:
        held = (text, json.loads(text))
        if proxy is not None:
            proxy._plan_data = held
    return held[1]


def hold_plan_data(obj, data):
    """Stores a new plan and its input in the document (PlanData, JSON: what a
    saved file keeps) and holds the objects themselves for plan_data."""
    obj.PlanData = text = json.dumps(data)
    obj.Proxy._plan_data = (text, data)


def plan_of(obj):
    """The last plan of a Plunge Rough operation (docs/plan-format.md, "Output"), or None."""
    data = plan_data(obj)
    return data["plan"] if data else None


def companions(obj):
    """The companion operations of a Plunge Rough operation."""
    return [o for o in obj.InList if getattr(o, "PlanOperation", None) == obj]


def companion_label(obj, tc, start_holes=False):
    """"PlungeRough T3 12 mm": no parentheses, which the post would nest in comments."""
    if tc is None:
        return obj.Label + " plunger"
    return "%s T%d %g mm%s" % (obj.Label, tools.number(tc), tools.diameter(tc),
                               " start holes" if start_holes else "")


def start_hole_tcs(tcs):
    """The tool controllers that drill start holes, as the planner chooses them
    (plunge.start_hole_tools): for each plunger that does not cut at its centre,
    the smallest centre-cutting one at least as wide as its core."""
    by_id = tools.by_number(tcs)
    drill_of = planner.planner().start_hole_tools([tools.spec(tc) for tc in tcs])
    drills = []
    for tc in tcs:
        drill = by_id.get(drill_of.get(tools.number(tc)))
        if drill is not None and drill not in drills:
            drills.append(drill)
    return drills


def removeOrphans(doc):
    """Removes companion operations whose Plunge Rough operation is gone or that
    are in no Job (left by a cancelled task panel)."""
    for o in list(doc.Objects):
        if not isinstance(getattr(o, "Proxy", None), ObjectPlungeRoughTool):
            continue
        main = getattr(o, "PlanOperation", None)
        if main is None or main.Document is not doc or o not in companions(main) or \
                PathUtils.findParentJob(o) is None:
            doc.removeObject(o.Name)


def syncCompanions(obj):
    """One companion per plunger besides the largest, ordered after obj by size."""
    job = PathUtils.findParentJob(obj)
    if job is None:
        return
    tcs = tool_controllers(obj)
    if not tcs:
        return
    if obj.ToolController != tcs[0]:
        obj.ToolController = tcs[0]
    existing = {(o.ToolController, bool(getattr(o, "StartHoles", False))): o for o in companions(obj)}
    wanted, before = [], []
    try:
        drills = start_hole_tcs(tcs)
    except (ValueError, planner.PlannerFailed):
        drills = []  # a bad bit, or no planner: the operation reports it when it plans
    for tc, holes in [(d, True) for d in drills] + [(tc, False) for tc in tcs[1:]]:
        comp = existing.pop((tc, holes), None)
        if comp is None:
            comp = obj.Document.addObject("Path::FeaturePython", obj.Name + ("_H" if holes else "_T"))
            # Its settings are the Plunge Rough operation's, not the setup sheet's
            # (which knows nothing of companions and would say so in the log).
            comp.addProperty("App::PropertyBool", "DoNotSetDefaultValues", "Path")
            comp.DoNotSetDefaultValues = True
            comp.setEditorMode("DoNotSetDefaultValues", 2)
            comp.Proxy = ObjectPlungeRoughTool(comp, "PlungeRoughTool", job)
            comp.Active = True
            comp.PlanOperation = obj
            comp.ToolController = tc
            if holes:
                comp.addProperty("App::PropertyBool", "StartHoles", "Plunge Rough",
                                 QT_TRANSLATE_NOOP("App::Property", "Drills the start holes of the plan"))
                comp.StartHoles = True
                comp.setEditorMode("StartHoles", 1)
        comp.Label = companion_label(obj, tc, holes)
        (before if holes else wanted).append(comp)
    for stale in existing.values():
        obj.Document.removeObject(stale.Name)
    # Start holes are drilled before the operation's own plunges, the other
    # plungers follow it.
    group = [o for o in job.Operations.Group if o not in wanted and o not in before]
    at = group.index(obj) if obj in group else len(group)
    job.Operations.Group = group[:at] + before + group[at:at + 1] + wanted + group[at + 1:]
    for comp in before + wanted:
        comp.touch()


def activate_companions(obj, plan, tcs):
    """The tool controller the operation itself cuts with; the companions that
    have plunges to make active, the others idle (so the post writes no tool
    change without plunges after it); with None for the problem. (None, the
    problem) for a plan that drills start holes no companion makes."""
    used = {p["tool_id"] for p in plan["plunges"]}
    own_tc = tcs[0]
    # Automatic choice: this operation cuts with the largest plunger the plan uses.
    if obj.AutoSelectTools:
        own_tc = next((tc for tc in tcs if tools.number(tc) in used), tcs[0])
        if obj.ToolController != own_tc:
            obj.ToolController = own_tc
    # Start holes: every one is drilled by its companion, placed before this operation.
    drilling = {p["tool_id"] for p in plan["plunges"] if p.get("start_hole")}
    holes_by = {tools.number(c.ToolController) for c in companions(obj) if getattr(c, "StartHoles", False)}
    if drilling - holes_by:
        return None, translate("PlungeRough", "the plan drills start holes with T%s, which has no start hole "
                               "operation: tick the plungers again") % ", T".join(str(t) for t in drilling - holes_by)
    for comp in companions(obj):
        if getattr(comp, "StartHoles", False):
            active = tools.number(comp.ToolController) in drilling
        else:
            active = not obj.AutoSelectTools or (tools.number(comp.ToolController) in used
                                                 and comp.ToolController != own_tc)
        if comp.Active != active:
            comp.Active = active
    return own_tc, None


def deactivate(obj):
    """Keeps the companions out of the program (no tool change without plunges
    after it) until the operation plans again."""
    for comp in companions(obj):
        if comp.Active:
            comp.Active = False
