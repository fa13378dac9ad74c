"""The addon in FreeCAD's GUI under a virtual display (xvfb-run), as a user works:
the example document made by the main command's own script
(resources/examples/freecad_demo.py, in the GUI), then gui_smoke.py driving the
commands, panels, tree and simulators (see there). Screenshots are kept in
build/test-artifacts/."""
import json
import os
import re
import shutil
import subprocess

import pytest

from conftest import BUILD, HERE, ROOT

pytestmark = pytest.mark.skipif(not shutil.which("xvfb-run") or not shutil.which("freecad"),
                                reason="needs xvfb-run and FreeCAD's GUI")


def run_gui(script, env, timeout):
    # QtWebEngine (FreeCAD's start page) refuses to start as root without this.
    env = dict(os.environ, QT_QPA_PLATFORM="xcb", QTWEBENGINE_DISABLE_SANDBOX="1", **env)
    return subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1600x1000x24", "freecad", script],
                          env=env, timeout=timeout, capture_output=True, text=True)


@pytest.fixture(scope="module")
def out():
    path = os.path.join(BUILD, "test-artifacts")
    os.makedirs(path, exist_ok=True)
    for name in os.listdir(path):  # no picture from an earlier run left to mislead
        if name.endswith(".png"):
            os.remove(os.path.join(path, name))
    return path


def install_addon():
    """The addon as a user installs it (resources/install_addon.sh: FreeCAD's
    user Mod folder, here this test's own profile, see tests/CMakeLists.txt;
    the plunge-mill bits with it). FreeCAD then loads it at start, and only
    modules of installed addons may be loaded with a document (Debian's
    FreeCAD refuses others)."""
    run = subprocess.run(["sh", os.path.join(ROOT, "resources", "install_addon.sh")],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    return run.stdout.split("installed the addon in ")[1].split(",")[0]


@pytest.fixture(scope="module")
def result(out):
    """The installed addon; the example made by the main command's demo script;
    then the GUI session on it."""
    install_addon()
    example = os.path.join(out, "example")
    shutil.rmtree(example, ignore_errors=True)
    run = run_gui(os.path.join(ROOT, "resources", "examples", "freecad_demo.py"), {"PLUNGE_OUT": example}, 600)
    error = os.path.join(example, "demo_error.txt")
    assert not os.path.exists(error), open(error).read()
    doc = os.path.join(example, "plunge_example.FCStd")
    assert os.path.exists(doc), run.stdout[-2000:] + run.stderr[-2000:]
    # The demo's summary: the operations' plunges (feeds down in their Paths)
    # are the plan's, a raised lead-out's feed up not among them.
    lines = open(os.path.join(example, "summary.txt")).read().splitlines()
    total = int(re.match(r"(\d+) plunges \(", lines[1]).group(1))
    per_op = [int(m.group(1)) for m in (re.search(r"(\d+) plunges, plunge feed", l) for l in lines) if m]
    assert per_op and sum(per_op) == total, lines
    # The second demo, where plunging pays: 75 mm deep with 50 mm flutes, so in
    # levels; the tool choice (on for new operations) says what it chose, and
    # the posted program changes tools only to the plungers chosen.
    deep = open(os.path.join(example, "deep_pocket_summary.txt")).read()
    assert "2 levels (flute length)" in deep and "plungers chosen: " in deep, deep
    chosen = re.search(r"plungers chosen: ([\d/.]+)", deep).group(1).split("/")
    program = open(os.path.join(example, "deep_pocket.ngc")).read()
    changes = re.findall(r"^\s*(?:N\d+\s+)?M0?6\s+T(\d+)|^\s*(?:N\d+\s+)?T(\d+)\s+M0?6", program, re.M)
    assert changes and len(changes) == len(chosen), (chosen, changes)
    # Both saved demos post with the post the docs name.
    for saved in (doc, os.path.join(example, "deep_pocket.FCStd")):
        assert saved_post_processor(saved) == "linuxcnc", saved
    # Each demo's pictures, one per question: stop heights only over the
    # first demo's sculptured floor, not over the die pocket's flat one.
    pictures = sorted(f for f in os.listdir(example) if f.endswith(".svg"))
    assert pictures == ["deep_pocket-stock.svg", "deep_pocket.svg", "plunge_rough-heights.svg",
                        "plunge_rough-stock.svg", "plunge_rough.svg"], pictures
    result_file = os.path.join(out, "gui_result.json")
    if os.path.exists(result_file):
        os.remove(result_file)
    run_gui(os.path.join(HERE, "gui_smoke.py"),
            {"PLUNGE_BUILD_DIR": BUILD, "PLUNGE_GUI_OUT": out, "PLUNGE_EXAMPLE_DOC": doc}, 1200)
    with open(result_file) as f:
        return json.load(f)


def saved_post_processor(path):
    """The Job's PostProcessor in a saved document (its Document.xml)."""
    import zipfile
    xml = zipfile.ZipFile(path).read("Document.xml").decode()
    block = xml[xml.index('name="PostProcessor" type="App::PropertyEnumeration"'):]
    block = block[:block.index("</Property>")]
    index = int(re.search(r'<Integer value="(\d+)"', block).group(1))
    return re.findall(r'<Enum value="([^"]*)"/>', block)[index]


def expected_names():
    import FreeCAD
    if int(FreeCAD.Version()[0]) >= 1:
        return {"workbench": "CAMWorkbench", "menu": "&CAM", "voxel": "CAM_Simulator", "best": "CAM_SimulatorGL"}
    return {"workbench": "PathWorkbench", "menu": "&Path", "voxel": "Path_Simulator", "best": "Path_Simulator"}


def first_step_with_errors(result):
    counts = result.get("errors_by_step", {})
    return next((step for step in result["steps"] if counts.get(step)), "after the last step")


def test_the_session_ran_without_errors(result):
    assert result["ok"], result.get("error") or result["steps"]
    assert result["addon"].endswith(os.path.join("Mod", "PlungeRough"))  # the installed copy
    assert not result.get("dialogs"), result["dialogs"]  # no unexpected modal dialog
    # Nothing red in the report view; if there is, the step it came in says where.
    assert result["report_found"] and not result["report"], (first_step_with_errors(result), result["report"])
    assert result["svg_images"]  # FreeCAD's check marks and icons are drawn (resources/setup.sh)


def test_the_readmes_demo_figures_are_the_demos(result, out):
    """The README's figures of both demos come from this run of them: the
    first demo's plunges (the headline table), the deep pocket's plunges,
    levels and minutes. Measured on FreeCAD 0.20 (this project's machine): a
    newer FreeCAD's part modelling may shift a plunge, so elsewhere only that
    the figures are there."""
    import FreeCAD
    readme = open(os.path.join(ROOT, "README.md")).read()
    demo = re.search(r"^\| FreeCAD demo \([^|]*\| (\d+) \|", readme, re.M)
    deep = re.search(r"the deep die pocket[^|]*: (\d+) plunges of a 20 mm plunger, (\d+) levels, about ([\d.]+) min",
                     readme)
    assert demo and deep, "the README's demo figures moved: update this test"
    if FreeCAD.Version()[:2] != ["0", "20"]:
        pytest.skip("the README's figures are FreeCAD 0.20's")
    example = os.path.join(out, "example")
    first = open(os.path.join(example, "summary.txt")).read().splitlines()[1]
    assert first.startswith(demo.group(1) + " plunges ("), (demo.group(0), first)
    summary = open(os.path.join(example, "deep_pocket_summary.txt")).read()
    minutes = float(re.search(r"about ([\d.]+) min", summary).group(1))
    assert re.search(r"\b%s plunges \(T\d+ 20 mm: %s\)" % (deep.group(1), deep.group(1)), summary), summary
    assert "%s levels (flute length)" % deep.group(2) in summary, summary
    assert abs(minutes - float(deep.group(3))) <= 0.05, (deep.group(0), minutes)


def test_example_document_is_a_gui_document(result):
    """Made by the main command's script in the GUI: a Job tree, the operation's
    own view provider and panel, tool bits as wide as their diameters."""
    ex = result["example"]
    assert ex["job_view"] and len(ex["job_children"]) >= 3  # model, stock, operations, tools
    assert ex["op_view"] == "ViewProvider" and set(ex["companion_views"]) == {"CompanionViewProvider"}
    plungers = [(w, d) for w, d in zip(ex["bit_widths"], ex["bit_diameters"]) if d in (20, 12, 6)]
    # The solid the simulators cut with is as wide as the bit (it was 5 mm for
    # every plunger once); saved solids are tessellation-exact to about 0.3 %.
    assert len(plungers) == 3 and all(abs(w - d) < 0.01 * d for w, d in plungers)
    assert ex["panel"] and ex["after_cancel"] == {"same_plan": True, "operations": True}
    # The panel's picture buttons: the example's floor is sculptured, so the
    # plan, the stock left and the stop heights are each shown, drawn whole.
    pictures = ex["pictures"]
    assert set(pictures) == {"showPlan", "showStock", "showHeights"}, pictures
    for name, size in pictures.items():
        assert size is not None and min(size) > 200, (name, size)


def test_it_plans_out_of_freecads_process_and_survives_a_planner_killed(result):
    """The installed addon plans through the program in its bin/. Killed from
    outside while it plans, the planner leaves one red line naming what
    happened; FreeCAD stays up, nothing is cut, and the next recompute plans
    the same plan again."""
    assert ", program %s (the addon's bin)" % os.path.join(result["addon"], "bin", "plunge-rough") in result["planner"]
    k = result["kill"]
    assert k["killed"] and len(k["red"]) == 1 and "PlungeRough: the planner " in k["red"][0], k
    assert "was stopped (SIGKILL)" in k["summary"] and k["cut"] == 0 and k["touched"], k
    assert k["planned_again"], k


def test_a_long_plan_cancels_within_a_second(result):
    """Esc while the example plans (several seconds), Yes in FreeCAD's abort
    box: the plan stops within a second of the Yes, says so in the report view,
    cuts nothing (its companions out of the program), and the next recompute
    plans the same plan again, companions back in."""
    c = result["cancel"]
    assert c["box"] == "Aborting", c
    assert c["yes_to_end"] is not None and c["yes_to_end"] < 1.0, c
    assert c["summary"].startswith("planning cancelled") and c["said"], c
    assert c["cut"] == 0 and not any(c["companions_active"]), c
    assert c["planned_again"] and all(c["companions_active_again"]) and c["example_again"], c


def test_example_simulates_as_a_cleared_pocket(result):
    """The voxel simulator's own panel, run to the end with the tool controllers'
    own tools: under every probed plunge the stock is cut to the plan's depth."""
    sim = result["simulation"]
    assert sim["command"] == expected_names()["voxel"]
    assert sim["probes"] > 20
    assert not sim["wrong"], sim["wrong"]
    if result["simulator"] == "CAM_SimulatorGL":
        assert result["gl_simulator_windows"] == 1


def test_command_in_the_workbench(result):
    names = expected_names()
    assert result["workbench"] == names["workbench"] and result["simulator"] == names["best"]
    assert result["toolbar"] == ["New Operations"] and result["menu"] == [names["menu"]]
    assert result["menu_neighbour"] == "Adaptive"  # with the other operations
    assert result["enabled_without_job"] is False and result["enabled_with_job"] is True


def test_new_operation_from_the_toolbar(result):
    assert "chose" not in result  # FreeCAD did not need to ask: the largest plunger is the op's own
    assert result["job_panel_closed"]
    # Added in the Job panel's Tools tab from .fctb files through FreeCAD's file
    # dialog; in 1.1 one by one from the tool library, where the user put them.
    # (The plunge mill's phase adds one more the same way.)
    if "library_dialogs" in result:
        assert len(result["library_dialogs"]) == 3 + 1 and "file_dialogs" not in result
    else:
        assert len(result["file_dialogs"]) == 1 + 1
    # ("TC: " before the bit's name in 1.1's tool controller labels)
    assert [label.split(" plunger")[0].replace("TC: ", "") for label, _ in result["added_tool_controllers"]] == \
        ["20 mm", "12 mm", "6 mm"]
    assert [checked for _, checked in result["plunger_list"]] == [True, True, True]  # no default 5 mm tool
    assert result["base"] and result["base"][0].startswith("Face")
    assert [d for _, d, _ in result["operations"]] == [20, 12, 6]
    assert all(n > 0 for _, _, n in result["operations"])  # every tool plunges
    assert all("(" not in label for label, _, _ in result["operations"])
    assert result["radial"] == 0.5  # the panel's value reached the op
    assert result["stick_out"] == 120.0  # so did the holder's stick-out
    width, needed, scrolls = result["panel_width"]
    assert needed <= width and scrolls is False, result["panel_width"]  # nothing cut off on the right
    # The screenshots show what the README says of them: the Job panel's Tools
    # tab, and the operation's settings with the allowances.
    assert result["job_panel_tab"] == "Tools"
    assert result["panel_settings_visible"]
    assert result["strategies"] == ["Packing", "Grid (honeycomb)", "Grid (square)"]
    assert result["auto_checkbox"] is True and result["panel_icon"]  # new operations choose their plungers
    assert "coverage" in result["summary"]


def test_cancel_undo_and_delete(result):
    cancel = result["after_cancel"]
    assert cancel["same_objects"] and cancel["plungers"] == [20, 12, 6]
    assert result["undo_name"] == "Create Plunge Rough"
    assert result["after_undo"] == {"plunge_objects": [], "operations": []}
    assert len(result["after_redo"]["operations"]) == 3 and result["after_redo"]["plunges"] > 0
    deleted = result["after_companion_delete"]
    assert len(deleted["operations"]) == 2 and deleted["diameters"] == [6, 20] and deleted["core_coverage"] > 0.9999
    assert result["after_op_delete"] == []


def test_plunge_mill_from_the_library(result):
    """The bit install_addon.sh put in the tool library: added to a Job in its
    panel, a plunger the planner sees with its core and engagement limit, its
    solid to scale, and FreeCAD's tool bit editor opens on it."""
    mill = result["plunge_mill"]
    assert len(mill["added"]) == 1 and "25 mm plunge mill" in mill["added"][0] and mill["plunger"]
    spec = mill["spec"]
    assert spec["diameter"] == 25 and spec["core_diameter"] == 13 and spec["max_engagement"] == 6
    assert spec["center_cutting"] is False
    assert abs(mill["solid"][0] - 25) < 0.1 and abs(mill["solid"][1] - 150) < 0.1  # to scale
    assert mill["editor"]
    # FreeCAD 0.20's own editor bug (gui_smoke.UPSTREAM_BUGS), set aside in the
    # report view, costs one more try and no other.
    if "editor_attempts" in mill:
        editor_bugs = [k for k in result["report_known_upstream"] if k["bug"] == "editor"]
        assert mill["editor_attempts"] == 1 + len(editor_bugs), result["report_known_upstream"]
    # FreeCAD 1.1's editor, made again at most twice after its own __init__
    # met a stale PySide6 wrapper (gui_smoke.plunge_mill_bit).
    if "editor_retries" in mill:
        assert mill["editor_retries"] in (0, 1, 2), mill


def test_rest_material_from_the_panel(result):
    """The panel's "Rest from" lists the choices, and its "Rest material"
    button makes the solid of what the example's plan leaves: less than the
    stock, more than nothing, valid, shown."""
    assert result["rest_from"] == ["Previous operations", "Job stock", "None"]
    assert result["rest_from_current"] == "Job stock"  # the example's Job has no operation before it
    solid = result["rest_solid"]
    assert solid and solid["valid"] and solid["visible"], solid
    assert 0.3 * solid["stock_volume"] < solid["volume"] < solid["stock_volume"] - 1000.0, solid
    assert solid["drawn"] > 0.1, solid  # rest_material_3d.png shows it
    # Shaded, by height: the stock's top in stock colour, the pocket's cut floor in blue.
    assert solid["display_mode"] == "Shaded" and solid["stock_coloured"] > 0.3 and solid["deep_coloured"] > 0.02, solid


def test_screenshots(result, out):
    names = ["example_simulated.png", "job_panel.png", "plunge_rough_panel.png", "plunge_rough_gui.png",
             "plunge_mill_bit.png"]
    if result["simulator"] == "CAM_SimulatorGL":
        names.append("example_gl_simulator.png")
    for name in names:
        assert os.path.getsize(os.path.join(out, name)) > 10000, name
