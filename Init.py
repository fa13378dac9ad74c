# PlungeRough FreeCAD addon: headless initialisation (App side, runs in freecadcmd too).
# Registers the Plunge Rough operation with the Path setup sheets. The compiled
# planner (`plunge`) sits beside this file in the installed addon folder.
try:
    from freecad_plugin import PlungeRough as _PlungeRough

    _PlungeRough.register()
except Exception as e:  # never break FreeCAD's start-up
    import FreeCAD

    FreeCAD.Console.PrintWarning("PlungeRough: not loaded (%s)\n" % e)
