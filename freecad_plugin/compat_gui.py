"""FreeCAD's Path/CAM GUI as it differs between versions (GUI only): the GUI
side of compat.py, which App code imports; this module only GUI code, tests and
examples driving the GUI import."""
import FreeCADGui

from freecad_plugin.compat import first_module, version


def refresh_spin_box(spin):
    """A QuantitySpinBox helper shows its property's value again: updateSpinBox()
    before 1.1, updateWidget() in 1.1 (GUI only)."""
    update = getattr(spin, "updateSpinBox", None) or getattr(spin, "updateWidget")
    update()


def workbench_name():
    """The CAM workbench's name: "CAMWorkbench" from 1.0 on, "PathWorkbench" before."""
    try:
        names = FreeCADGui.listWorkbenches()
        for name in ("CAMWorkbench", "PathWorkbench"):
            if name in names:
                return name
    except AttributeError:  # a FreeCADGui without its main window
        pass
    return "CAMWorkbench" if version() >= (1, 0) else "PathWorkbench"


def gui_modules():
    """The GUI-side modules (only importable with a GUI)."""
    op_gui = first_module("Path.Op.Gui.Base", "PathScripts.PathOpGui")
    selection = first_module("Path.Op.Gui.Selection", "PathScripts.PathSelection")
    return op_gui, selection


def gui_util():
    """QuantitySpinBox and friends (GUI only)."""
    return first_module("Path.Base.Gui.Util", "PathScripts.PathGui")


def job_gui():
    """The Job's GUI module, whose Create(base, template, openTaskPanel) is what
    the Job command runs (GUI only)."""
    return first_module("Path.Main.Gui.Job", "PathScripts.PathJobGui")


def simulator_command():
    """The GUI command of the best simulator this FreeCAD has: 1.0's OpenGL CAM
    simulator (CAM_SimulatorGL), else the Path simulator (Path_Simulator)."""
    commands = FreeCADGui.listCommands()
    for name in ("CAM_SimulatorGL", "CAM_Simulator", "Path_Simulator"):
        if name in commands:
            return name
    return None


def voxel_simulator_command():
    """The GUI command of the voxel simulator's panel: Path_Simulator (0.20),
    CAM_Simulator (1.0, the legacy simulator)."""
    commands = FreeCADGui.listCommands()
    return next((n for n in ("CAM_Simulator", "Path_Simulator") if n in commands), None)
