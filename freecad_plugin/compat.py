"""One place for FreeCAD's Path module names, which moved between versions.

0.20 (tested): PathScripts.*; 0.21 and 1.0 (read in source, untested here):
Path.Op.Base, Path.Main.Job, ... . Everything else imports from here.
"""
import importlib


def _first(*names):
    for name in names:
        try:
            return importlib.import_module(name)
        except ImportError:
            continue
    raise ImportError("none of " + ", ".join(names))


PathOp = _first("Path.Op.Base", "PathScripts.PathOp")
PathLog = _first("Path.Log", "PathScripts.PathLog")
PathUtils = _first("PathScripts.PathUtils")
PathJob = _first("Path.Main.Job", "PathScripts.PathJob")
PathToolController = _first("Path.Tool.Controller", "PathScripts.PathToolController")
PathToolBit = _first("Path.Tool.Bit", "PathScripts.PathToolBit")
PathFeedRate = _first("Path.Base.FeedRate", "PathFeedRate")
PathSetupSheet = _first("Path.Base.SetupSheet", "PathScripts.PathSetupSheet")


def gui_modules():
    """The GUI-side modules (only importable with a GUI)."""
    op_gui = _first("Path.Op.Gui.Base", "PathScripts.PathOpGui")
    selection = _first("Path.Op.Gui.Selection", "PathScripts.PathSelection")
    return op_gui, selection


def post_module(name):
    """A post processor module by its short name ("linuxcnc", "grbl")."""
    return _first("Path.Post.scripts.%s_post" % name, "PathScripts.post.%s_post" % name)


def post_command_module():
    """The module of the Job's post command (buildPostList), imported on demand."""
    return _first("Path.Post.Command", "PathScripts.PathPost")
