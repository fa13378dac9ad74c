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


def _plungeRoughAfterStart():
    """Once FreeCAD has started (its CAM modules can then be imported): the
    plunge-mill tool bits made and registered with the tool library when the
    addon has none yet (a clone by the Addon Manager). One function: FreeCAD
    runs this file with names that later functions cannot see."""
    from PySide import QtCore

    def first_start():
        try:
            from freecad_plugin import plunge_mill

            plunge_mill.ensure_installed()
        except Exception as e:  # never break FreeCAD's start
            import FreeCAD

            FreeCAD.Console.PrintWarning("PlungeRough: the plunge-mill tool bits could not be made (%s)\n" % e)

    QtCore.QTimer.singleShot(0, first_start)


_plungeRoughAfterStart()
