# PlungeRough FreeCAD addon: GUI initialisation.
# Registers the Plunge Rough command and puts it into the CAM workbench (FreeCAD
# 1.0: a workbench manipulator) or the Path workbench (0.20: added to its menu and
# toolbar on activation). See freecad_plugin/command.py.


def _plungeRoughInstall():
    try:
        from freecad_plugin import command

        command.install()
    except Exception as e:  # never break FreeCAD's start
        import FreeCAD

        FreeCAD.Console.PrintError("PlungeRough: the command could not be added (%s)\n" % e)


_plungeRoughInstall()
