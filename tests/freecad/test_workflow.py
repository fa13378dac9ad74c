"""What a machinist does around the operation, headless: the Job's setup sheet,
the tool controllers a new operation takes, deleting and deactivating, undo,
warnings that reach the summary, and G-code comments a controller accepts."""
import re

import FreeCAD
import pytest

import parts
from conftest import build_op
from freecad_plugin import companions, compat, PlungeRough, tools


def test_setup_sheet_prototype_shows_every_default():
    """The Job panel's "Op Defaults" tab builds a prototype of each registered
    operation and shows each value with its unit: quantities, not bare floats.
    The internal companion operation is not offered there."""
    registered = compat.PathSetupSheet._RegisteredOps
    assert "PlungeRough" in registered and "PlungeRoughTool" not in registered
    proto = registered["PlungeRough"].prototype("PlungeRough")
    for name in PlungeRough.SetupProperties():
        prop = proto.getProperty(name)
        shown = prop.displayString()  # raised on a bare float before
        if prop.propType in ("App::PropertyDistance", "App::PropertyLength"):
            assert FreeCAD.Units.Quantity(shown).Unit == FreeCAD.Units.Length, (name, shown)


def test_new_op_ticks_every_plunger_largest_its_own(doc):
    """A Job with FreeCAD's default tool controller (no vertical feed), a drill,
    three plungers and an operation already using the smallest: the new
    operation takes all plungers, the largest as its own, nothing else."""
    job = parts.make_job(doc, parts.islands_part())
    tcs = [parts.add_tool_controller(job, d, n) for d, n in ((6, 4), (20, 2), (12, 3))]
    first = PlungeRough.Create("PlungeRough", parentJob=job)
    first.ToolControllers = [tcs[0]]
    doc.recompute()
    op = PlungeRough.Create("PlungeRough", parentJob=job)
    doc.recompute()
    assert [float(tc.Tool.Diameter) for tc in op.ToolControllers] == [20, 12, 6]
    assert float(op.ToolController.Tool.Diameter) == 20
    default = [tc for tc in job.Tools.Group if tc not in tcs]
    assert default and not any(tools.is_plunger(tc) for tc in default)
    assert [c.Label for c in companions.companions(op)] == [op.Label + " T3 12 mm", op.Label + " T4 6 mm"]


def test_no_plunger_in_the_job_is_a_clear_error(doc):
    job = parts.make_job(doc, parts.islands_part())
    with pytest.raises(ValueError, match="no plunger.*vertical feed"):
        PlungeRough.Create("PlungeRough", parentJob=job)


def test_labels_and_posted_comments_are_well_formed(doc):
    """RS274/NGC comments do not nest: no label the addon makes has parentheses,
    and every comment the posts write is one balanced pair."""
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    for o in job.Operations.Group:
        assert "(" not in o.Label and ")" not in o.Label, o.Label
    for name, args in (("linuxcnc", "--no-show-editor"), ("grbl", "--no-show-editor --translate_drill")):
        text = compat.post_job(job, name, args)
        for line in text.splitlines():
            depth = 0
            for ch in line.split(";")[0]:
                depth += {"(": 1, ")": -1}.get(ch, 0)
                assert depth in (0, 1), (name, line)  # never nested, never closed before opened
            assert depth == 0, (name, line)
        assert re.search(r"\(begin operation: PlungeRough T3 12 mm\)", text, re.I), name


def test_deleted_companion_is_never_silent(doc):
    """Without its companion a plunger's plunges would be missing from the
    simulation and the G-code: the operation says so and cuts nothing."""
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    comp = companions.companions(op)[0]
    doc.removeObject(comp.Name)
    op.touch()
    doc.recompute()
    assert "deleted" in op.Summary and tcs[1].Label in op.Summary
    assert not [c for c in op.Path.Commands if c.Name in ("G1", "G81", "G83")]
    # Unticking it replans with the others.
    op.ToolControllers = [tcs[0], tcs[2]]
    doc.recompute()
    plan = PlungeRough.plan_of(op)
    assert plan and {p["diameter"] for p in plan["plunges"]} == {20, 6}
    assert plan["stats"]["core_coverage"] > 0.9999


def test_inactive_operation_takes_its_companions_along(doc):
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    comps = companions.companions(op)
    op.Active = False
    doc.recompute()
    assert not any(c.Active for c in comps)
    assert not any(c.Name in ("G1", "G81", "G83") for o in job.Operations.Group for c in o.Path.Commands)
    op.Active = True
    doc.recompute()
    assert all(c.Active for c in comps)
    assert all(any(c.Name == "G1" for c in o.Path.Commands) for o in job.Operations.Group)


def test_undo_creation_undoes_everything(doc):
    """One undo after creating the operation (as the GUI command does, in one
    transaction) leaves the Job as it was, with no error."""
    doc.UndoMode = 1
    job = parts.make_job(doc, parts.islands_part())
    for d, n in ((20, 2), (12, 3)):
        parts.add_tool_controller(job, d, n)
    doc.recompute()
    before = [o.Name for o in doc.Objects]
    doc.openTransaction("Create Plunge Rough")
    PlungeRough.Create("PlungeRough", parentJob=job)
    doc.commitTransaction()
    doc.recompute()
    assert len(job.Operations.Group) == 2
    doc.undo()
    doc.recompute()
    assert [o.Name for o in doc.Objects] == before
    assert job.Operations.Group == []
    doc.redo()
    doc.recompute()
    assert [o.Name for o in job.Operations.Group] == ["PlungeRough", "PlungeRough_T"]


def test_summary_warnings_speak_freecad(doc):
    """Coverage short of the target, in the grid strategy too, and canned cycles
    for a grbl post, reach the summary in the panel's words."""
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    op.Strategy = "Grid (square)"
    doc.recompute()
    assert "farther than 1.00 mm from the walls uncut" in op.Summary and "grid" in op.Summary
    assert "max_wall_stock" not in op.Summary
    op.Strategy = "Packing"
    op.UseCannedCycle = True
    job.PostProcessor = "grbl"
    job.PostProcessorArgs = ""
    op.touch()
    doc.recompute()
    assert "grbl" in op.Summary and "--translate_drill" in op.Summary
    job.PostProcessorArgs = "--translate_drill"
    op.touch()
    doc.recompute()
    assert "grbl" not in op.Summary


@pytest.mark.bundle
def test_planning_reports_progress_and_can_be_aborted(doc, monkeypatch):
    """The plan runs under FreeCAD's progress indicator (the status bar in the
    GUI); when the user aborts it (Esc), the operation says so and cuts nothing."""
    calls = []

    class Indicator:
        def start(self, text, steps):
            calls.append(text)

        def next(self, can_abort=False):
            calls.append("next")
            # The user aborts once planning is under way (a program first starts).
            working = [c for c in calls if c not in ("next", "stop") and ": starting the planner" not in c]
            if working and len(calls) - calls.index(working[0]) > 2:
                raise FreeCAD.Base.FreeCADAbort("Aborting...")

        def stop(self):
            calls.append("stop")

    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False)
    assert PlungeRough.plan_of(op)
    op.MaxEngagement = 10.0  # a plan of seconds, not a fraction of one, to abort
    monkeypatch.setattr(FreeCAD.Base, "ProgressIndicator", Indicator)
    op.touch()
    doc.recompute()
    # Through a program, the status bar says so until its first stage, then
    # the stage the planner is in at each poll (0.1 s: a quick stage may pass
    # between two polls unseen).
    stages = [c for c in calls if c not in ("next", "stop") and ": starting the planner" not in c]
    assert stages and all(c.startswith(op.Label + ": ") for c in stages) and calls[-1] == "stop"
    assert op.Summary.startswith("planning cancelled")
    assert not [c for c in op.Path.Commands if c.Name in ("G1", "G81", "G83")]
    # The operation waits for the next recompute, which plans it again.
    assert "Touched" in op.State
    monkeypatch.undo()
    doc.recompute()
    assert PlungeRough.plan_of(op) and [c for c in op.Path.Commands if c.Name == "G1"]
