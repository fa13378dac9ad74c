# PlungeRough FreeCAD addon: GUI initialisation.
# FreeCAD 0.20 has no workbench manipulator: the Plunge Rough command joins the
# Path workbench's menu and "New Operations" toolbar whenever that workbench is
# activated (FreeCAD 1.0 would offer FreeCADGui.addWorkbenchManipulator).


def _plungeRoughWorkbenchActivated(name):
    if name not in ("PathWorkbench", "CAMWorkbench"):
        return
    try:
        from freecad_plugin import PlungeRoughGui

        PlungeRoughGui.install()
    except Exception as e:  # never break the workbench
        import FreeCAD

        FreeCAD.Console.PrintError("PlungeRough: the command could not be added (%s)\n" % e)


import FreeCADGui  # noqa: E402

FreeCADGui.getMainWindow().workbenchActivated.connect(_plungeRoughWorkbenchActivated)
