"""Records how FreeCAD's report view shows a Python command that fails, for
test_report_view.py (tests/data/report_view/). Run it in FreeCAD's GUI:
  QTWEBENGINE_DISABLE_SANDBOX=1 xvfb-run -a freecad tests/freecad/report_view_capture.py
It writes report_view-<FreeCAD version>.json in the current folder: the
report view's lines from the command's on, each [text, shown red]."""
import json
import os

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui


class Failing:
    """A command that raises as FreeCAD's simulator did: a stale wrapper."""

    def GetResources(self):
        return {"MenuText": "Failing"}

    def IsActive(self):
        return True

    def Activated(self):
        def inner():
            raise RuntimeError("Internal C++ object (PySide2.QtWidgets.QToolButton) already deleted.")
        inner()


def run():
    FreeCADGui.runCommand("ReportView_Failing")
    FreeCAD.Console.PrintMessage("PlungeRough: a message after it\n")
    FreeCAD.Console.PrintError("an error after it\n")
    QtCore.QTimer.singleShot(500, record)


def record():
    view = FreeCADGui.getMainWindow().findChild(QtGui.QTextEdit, "Report view")
    lines, block = [], view.document().begin()
    while block.isValid():
        red = any(r.format.foreground().color() == QtGui.QColor(QtCore.Qt.red) for r in block.layout().formats())
        lines.append([block.text(), red])
        block = block.next()
    first = next(i for i, (text, _) in enumerate(lines) if "ReportView_Failing" in text)
    version = ".".join(FreeCAD.Version()[:2])
    with open(os.path.join(os.getcwd(), "report_view-%s.json" % version), "w") as f:
        json.dump({"freecad": version, "lines": lines[first:]}, f, indent=1)
    FreeCADGui.getMainWindow().close()


FreeCADGui.addCommand("ReportView_Failing", Failing())
QtCore.QTimer.singleShot(3000, run)
