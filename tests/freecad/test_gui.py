"""The op through FreeCAD's GUI under a virtual display (xvfb-run): the command
sits in the CAM (1.0) or Path (0.20) workbench's toolbar and menu, creates the op from the selected face, the task
panel is accepted, the op has paths, and a screenshot is kept."""
import json
import os
import shutil
import subprocess

import pytest

from conftest import BUILD, HERE

pytestmark = pytest.mark.skipif(not shutil.which("xvfb-run") or not shutil.which("freecad"),
                                reason="needs xvfb-run and FreeCAD's GUI")


def test_gui_smoke():
    out = os.path.join(BUILD, "test-artifacts")
    os.makedirs(out, exist_ok=True)
    result_file = os.path.join(out, "gui_result.json")
    if os.path.exists(result_file):
        os.remove(result_file)
    # QtWebEngine (FreeCAD's start page) refuses to start as root without this.
    env = dict(os.environ, PLUNGE_BUILD_DIR=BUILD, PLUNGE_GUI_OUT=out, QT_QPA_PLATFORM="xcb",
               QTWEBENGINE_DISABLE_SANDBOX="1")
    subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1600x1000x24", "freecad", os.path.join(HERE, "gui_smoke.py")],
                   env=env, timeout=600, capture_output=True)
    with open(result_file) as f:
        result = json.load(f)
    assert result["ok"], result.get("error") or result["steps"]
    assert not result.get("dialogs"), result["dialogs"]  # no unexpected modal dialog
    assert result["report_found"] and not result["report"], result["report"]  # nothing went wrong in the report view
    assert result["chose"].startswith("TC: 20")  # FreeCAD's tool controller chooser was answered
    import FreeCAD
    expected = ("CAMWorkbench", "&CAM") if int(FreeCAD.Version()[0]) >= 1 else ("PathWorkbench", "&Path")
    assert result["workbench"] == expected[0]
    assert result["toolbar"] == ["New Operations"] and result["menu"] == [expected[1]]
    assert result["base"] and result["base"][0].startswith("Face")
    ops = result["operations"]
    assert [d for _, d, _ in ops] == [20, 12, 6]
    assert all(n > 0 for _, _, n in ops)  # every tool plunges
    assert result["radial"] == 0.5  # the panel's value reached the op
    assert result["strategies"] == ["Packing", "Grid (honeycomb)", "Grid (square)"]
    assert result["auto_checkbox"] is False
    assert "coverage" in result["summary"]
    assert os.path.getsize(os.path.join(out, "plunge_rough_gui.png")) > 10000
    # The version's own simulator ran the job: 1.0's OpenGL window opened, or
    # 0.20's voxel simulation removed material.
    assert result["simulator"] == ("CAM_SimulatorGL" if expected[0] == "CAMWorkbench" else "Path_Simulator")
    if result["simulator"] == "CAM_SimulatorGL":
        assert result["simulator_windows"] == 1
    else:
        assert 0 < result["simulated_volume"] < 0.95 * result["stock_volume"]
    assert os.path.getsize(os.path.join(out, "plunge_rough_simulation.png")) > 10000
