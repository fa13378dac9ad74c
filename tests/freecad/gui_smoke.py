"""GUI smoke test, run inside FreeCAD's GUI (tests/freecad/test_gui.py starts it
under xvfb-run): open the example, activate the CAM (1.0) or Path (0.20)
workbench, make the Job as its Job command does, select the floor face, run
Plunge Rough from the toolbar, tick the plungers, accept, check, screenshot."""
import json
import os
import sys
import time
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
BUILD = os.environ.get("PLUNGE_BUILD_DIR", os.path.join(ROOT, "build"))
OUT = os.environ.get("PLUNGE_GUI_OUT", os.path.join(BUILD, "test-artifacts"))
for p in (os.path.join(ROOT, "resources", "examples"), ROOT, os.path.join(BUILD, "cpp")):
    sys.path.insert(0, p)

import FreeCAD  # noqa: E402
import FreeCADGui  # noqa: E402
from PySide import QtCore, QtGui  # noqa: E402

result = {"ok": False, "steps": []}
# The tool controller to answer FreeCAD's "Choose a Tool Controller" dialog with
# (it asks when the job has several), as the user would: the largest plunger.
answer = {"tc": None}


def save():
    with open(os.path.join(OUT, "gui_result.json"), "w") as f:
        json.dump(result, f, indent=1)


def step(name):
    # Written after every step so a hang shows how far the GUI got.
    result["steps"].append(name)
    save()
    QtGui.QApplication.processEvents()


def watch_dialogs():
    """A modal dialog would block this script forever: record its text, close it,
    and let the test fail on it instead of timing out."""
    w = QtGui.QApplication.activeModalWidget()
    combo = w.findChild(QtGui.QComboBox, "uiToolController") if w is not None else None
    if combo is not None and answer["tc"]:  # FreeCAD's "Choose a Tool Controller"
        combo.setCurrentIndex(combo.findText(answer["tc"]))
        result["chose"] = combo.currentText()
        w.accept()
    elif w is not None:
        texts = [l.text() for l in w.findChildren(QtGui.QLabel) if l.text()]
        result.setdefault("dialogs", []).append("%s: %s" % (w.windowTitle(), " | ".join(texts)[:500]))
        save()
        w.close()


def report_errors():
    """What FreeCAD's report view shows as errors (red, the colour of its report
    highlighter in a default profile) or tracebacks: what the user would see."""
    view = FreeCADGui.getMainWindow().findChild(QtGui.QTextEdit, "Report view")
    result["report_found"] = view is not None
    errors = []
    block = view.document().begin() if view is not None else None
    while block is not None and block.isValid():
        text = block.text()
        red = [r for r in block.layout().formats()
               if r.format.foreground().color() == QtGui.QColor(QtCore.Qt.red)]
        if red or "Traceback" in text:
            errors.append(text)
        block = block.next()
    result["report"] = errors
    save()


def main():
    os.makedirs(OUT, exist_ok=True)
    timer = QtCore.QTimer()
    timer.timeout.connect(watch_dialogs)
    timer.start(2000)
    # A machinist's unit schema (mm, mm/min): otherwise Path warns in a modal box
    # on activation.
    FreeCAD.ParamGet("User parameter:BaseApp/Preferences/Units").SetInt("UserSchema", 6)
    FreeCAD.Units.setSchema(6)
    # The addon as FreeCAD loads it: InitGui.py's hook on the Path workbench.
    exec(open(os.path.join(ROOT, "InitGui.py")).read(), {"__name__": "InitGui"})
    import example_part
    from freecad_plugin import compat

    # Open the example part.
    doc = FreeCAD.newDocument("PlungeExample")
    part = doc.addObject("Part::Feature", "Part")
    part.Shape = example_part.freeform_part(True)
    doc.recompute()
    path = os.path.join(OUT, "plunge_example.FCStd")
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(path)
    FreeCADGui.ActiveDocument.ActiveView.viewIsometric()
    step("opened example")

    result["workbench"] = compat.workbench_name()
    FreeCADGui.activateWorkbench(result["workbench"])
    step("workbench " + result["workbench"])

    job = compat.job_gui().Create([doc.getObject("Part")], openTaskPanel=False)
    tcs = [example_part.add_tool_controller(job, d, n, os.path.join(OUT, "bits")) for d, n in ((20, 2), (12, 3), (6, 4))]
    doc.recompute()
    step("job")

    # The command as the user finds it: a toolbar button and a menu entry.
    mw = FreeCADGui.getMainWindow()
    bars = [b for b in mw.findChildren(QtGui.QToolBar) if b.isVisible()
            and any(a.text() == "Plunge Rough" for a in b.actions())]
    result["toolbar"] = [b.objectName() for b in bars]
    result["menu"] = [a.text() for a in mw.menuBar().actions() if a.menu() and
                      any(m.text() == "Plunge Rough" for m in a.menu().actions())]
    action = next(a for a in bars[0].actions() if a.text() == "Plunge Rough")
    step("command in toolbar and menu")

    clone = job.Model.Group[0]
    face = example_part.floor_face_name(clone.Shape, True)
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(doc.Name, clone.Name, face)
    step("selected " + face)

    answer["tc"] = tcs[0].Label
    action.trigger()  # as the user clicks it
    step("command run")
    ops = [o for o in job.Operations.Group if o.Name.startswith("PlungeRough")]
    op = ops[0]
    panel = op.ViewObject.Proxy.panel
    page = panel.featurePages[-1]
    for i in range(page.form.toolControllers.count()):
        item = page.form.toolControllers.item(i)
        if any(item.text().startswith("T%d " % tc.ToolNumber) for tc in tcs):
            item.setCheckState(QtCore.Qt.Checked)
        else:
            item.setCheckState(QtCore.Qt.Unchecked)
    result["strategies"] = [page.form.strategy.itemText(i) for i in range(page.form.strategy.count())]
    result["auto_checkbox"] = page.form.autoSelectTools.isChecked()
    page.form.radialAllowance.setProperty("rawValue", 0.5)
    page.form.radialAllowance.editingFinished.emit()
    step("panel filled")
    result["base"] = [sub for _, subs in op.Base for sub in subs]
    panel.accept()
    doc.recompute()
    step("accepted")

    result["operations"] = [(o.Label, float(o.ToolController.Tool.Diameter),
                             sum(1 for c in o.Path.Commands if c.Name == "G1"))
                            for o in job.Operations.Group]
    result["summary"] = op.Summary
    result["radial"] = op.RadialAllowance.Value
    result["icon"] = op.ViewObject.Proxy.getIcon()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.ActiveDocument.scrollToTreeItem(op.ViewObject)  # show the operations in the tree
    FreeCADGui.Selection.addSelection(op)
    FreeCADGui.ActiveDocument.ActiveView.fitAll()
    for _ in range(20):
        QtGui.QApplication.processEvents()
    # The screen, not mw.grab(): the 3D view is OpenGL and only the screen has it.
    QtGui.QApplication.primaryScreen().grabWindow(0).save(os.path.join(OUT, "plunge_rough_gui.png"))
    FreeCADGui.ActiveDocument.ActiveView.saveImage(os.path.join(OUT, "plunge_rough_3d.png"), 1000, 700, "White")
    step("screenshots")
    simulate(doc)
    report_errors()
    result["ok"] = True


def wait(seconds, done=lambda: False):
    end = time.time() + seconds
    while time.time() < end and not done():
        QtGui.QApplication.processEvents()
        time.sleep(0.05)


def click(window, at):
    """A left click on a window, with the pointer moved there first."""
    for kind, buttons in ((QtCore.QEvent.MouseMove, QtCore.Qt.NoButton),
                          (QtCore.QEvent.MouseButtonPress, QtCore.Qt.LeftButton),
                          (QtCore.QEvent.MouseButtonRelease, QtCore.Qt.NoButton)):
        button = QtCore.Qt.NoButton if kind == QtCore.QEvent.MouseMove else QtCore.Qt.LeftButton
        QtGui.QGuiApplication.sendEvent(window, QtGui.QMouseEvent(kind, at, button, buttons, QtCore.Qt.NoModifier))
        wait(0.3)


def simulate(doc):
    """The job in the best simulator this FreeCAD has, as the user runs it: the
    command, then the panel's play (1.0's OpenGL CAM simulator) or fast-forward
    (0.20's Path simulator) button, each tool cut with its tool controller's solid."""
    from freecad_plugin import compat
    name = compat.simulator_command()
    result["simulator"] = name
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.runCommand(name)
    wait(2)
    mw = FreeCADGui.getMainWindow()
    button = "toolButtonPlay" if name == "CAM_SimulatorGL" else "toolButtonFF"
    mw.findChild(QtGui.QToolButton, button).click()
    if name == "CAM_SimulatorGL":
        # Its own OpenGL window, played with its on-screen buttons along the
        # bottom edge: faster (>>, twice), then play.
        windows = [w for w in QtGui.QGuiApplication.topLevelWindows()
                   if w.isVisible() and w is not mw.windowHandle() and w.width() > 200]
        result["simulator_windows"] = len(windows)
        for w in windows:
            for x in (136, 136, 52):
                click(w, QtCore.QPointF(x, w.height() - 34))
        wait(110)  # x40: the whole job, about a minute and a half under xvfb
    else:  # the play button comes back when the simulation has ended
        play = mw.findChild(QtGui.QToolButton, "toolButtonPlay")
        wait(300, lambda: play.isEnabled())
        result["stock_volume"] = doc.getObject("Job").Stock.Shape.Volume
        cut = doc.getObject("CutMaterial")
        result["simulated_volume"] = cut.Mesh.Volume if cut is not None else None
        for o in doc.Objects:  # the cut material alone, from above
            if o.ViewObject is not None and o.Name not in ("CutMaterial", "CutMaterialIn"):
                o.ViewObject.Visibility = False
        FreeCADGui.ActiveDocument.ActiveView.viewTop()
        FreeCADGui.ActiveDocument.ActiveView.fitAll()
        wait(1)
    QtGui.QApplication.primaryScreen().grabWindow(0).save(os.path.join(OUT, "plunge_rough_simulation.png"))
    step("simulated with " + name)
    FreeCADGui.Control.closeDialog()
    wait(1)


try:
    main()
except Exception:
    result["error"] = traceback.format_exc()
finally:
    save()
    os._exit(0)
