"""Records how FreeCAD's report view shows a Python command that fails, for
test_report_view.py (tests/data/report_view/). Run it in FreeCAD's GUI:
  QTWEBENGINE_DISABLE_SANDBOX=1 xvfb-run -a freecad tests/freecad/report_view_capture.py
It writes report_view-<FreeCAD version>.json in the current folder: the
report view's lines from the command's on, each [text, shown red]."""
import json
import os
import sys

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(os.path.dirname(HERE))]  # report_view, freecad_plugin
from report_view import read  # noqa: E402


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
    lines = [list(line) for line in read(view.document())]
    first = next(i for i, (text, _) in enumerate(lines) if "ReportView_Failing" in text)
    version = ".".join(FreeCAD.Version()[:2])
    with open(os.path.join(os.getcwd(), "report_view-%s.json" % version), "w") as f:
        json.dump({"freecad": version, "lines": lines[first:]}, f, indent=1)
    FreeCADGui.getMainWindow().close()


FreeCADGui.addCommand("ReportView_Failing", Failing())
QtCore.QTimer.singleShot(3000, run)
