# PlungeRough FreeCAD addon: headless initialisation (runs in freecadcmd too).
# Nothing to do yet at this point: FreeCAD's Path modules cannot be imported
# while FreeCAD is still starting (FreeCAD.GuiUp is not set), so the operation
# registers with the job setup sheets when freecad_plugin.PlungeRough is first
# imported (creating the op, opening a document that holds one, or the GUI
# command). The compiled planner (`plunge`) sits beside this file.


def _plungeRoughCheckPlanner():
    """Says at every start, in the report view and on the console, when the
    compiled planner is missing (a clone by the Addon Manager has only the
    sources), with the one command that builds and installs it."""
    try:
        import plunge  # noqa: F401
    except ImportError as e:
        import FreeCAD
        from freecad_plugin import planner

        FreeCAD.Console.PrintWarning("PlungeRough: %s\n" % planner.missing_planner_message(e))


_plungeRoughCheckPlanner()
