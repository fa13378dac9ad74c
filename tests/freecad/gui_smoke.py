"""GUI smoke test, run inside FreeCAD's GUI (tests/freecad/test_gui.py starts it
under xvfb-run): open the example, activate Path, select the floor face, run
Plunge Rough from the toolbar, tick the plungers, accept, check, screenshot."""
import json
import os
import sys
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
    if w is not None and w.windowTitle() == "Choose a Tool Controller" and answer["tc"]:
        combo = w.findChild(QtGui.QComboBox, "uiToolController")
        combo.setCurrentIndex(combo.findText(answer["tc"]))
        result["chose"] = combo.currentText()
        w.accept()
    elif w is not None:
        texts = [l.text() for l in w.findChildren(QtGui.QLabel) if l.text()]
        result.setdefault("dialogs", []).append("%s: %s" % (w.windowTitle(), " | ".join(texts)[:500]))
        save()
        w.close()


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

    FreeCADGui.activateWorkbench("PathWorkbench")
    step("path workbench")
    import PathScripts.PathJobGui as PathJobGui

    job = PathJobGui.Create([doc.getObject("Part")], openTaskPanel=False)
    tcs = [example_part.add_tool_controller(job, d, n) for d, n in ((20, 2), (12, 3), (6, 4))]
    doc.recompute()
    step("job")

    mw = FreeCADGui.getMainWindow()
    action = mw.findChild(QtGui.QAction, "PlungeRoughAction")
    bars = [b for b in mw.findChildren(QtGui.QToolBar) if action in b.actions()]
    menus = [a.text() for a in mw.menuBar().actions() if a.menu() and action in a.menu().actions()]
    result["toolbar"] = [b.objectName() for b in bars]
    result["menu"] = menus
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
    result["ok"] = True


try:
    main()
except Exception:
    result["error"] = traceback.format_exc()
finally:
    save()
    os._exit(0)
