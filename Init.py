# PlungeRough FreeCAD addon: headless initialisation (runs in freecadcmd too).
# Nothing to do yet at this point: FreeCAD's Path modules cannot be imported
# while FreeCAD is still starting (FreeCAD.GuiUp is not set), so the operation
# registers with the job setup sheets when freecad_plugin.PlungeRough is first
# imported (creating the op, opening a document that holds one, or the GUI
# command). The planner program sits in bin/ beside this file
# (freecad_plugin/planner.py says where else it is looked for).


def _plungeRoughCheckPlanner():
    """Says at every start, in the report view and on the console, when no
    planner is found (a clone by the Addon Manager has only the sources): the
    bundle to get, and on Debian the one command that builds and installs it.
    A bundle unzipped by the Addon Manager gets its program's execute bit back."""
    import FreeCAD
    from freecad_plugin import planner

    try:
        planner.planner()
    except ValueError as e:
        FreeCAD.Console.PrintWarning("PlungeRough: %s\n" % e)


_plungeRoughCheckPlanner()
