"""The one place that knows how FreeCAD's Path/CAM API differs between versions.

Supported and tested: FreeCAD 0.20.2 (Debian 12: the "Path" workbench, modules
under PathScripts), FreeCAD 1.0 (Debian 13: the "CAM" workbench, modules under
Path.*) and FreeCAD 1.1 (Debian forky: Qt6, tool bits and their shapes are
assets of a library, Path.Tool.ToolBit). 0.21 has 1.0's module names with
0.20's workbench name; it is handled by the same look-ups but not tested.
Decisions are made by what the API offers, not by version numbers; where a
version is compared, FreeCAD's calendar versions (26.x, 27.x) are newer than
1.1 as plain numbers. Everything else imports from here.
"""
import importlib
import os
import tempfile

import FreeCAD


def first_module(*names):
    for name in names:
        try:
            return importlib.import_module(name)
        except ImportError:
            continue
    raise ImportError("none of " + ", ".join(names))


PathOp = first_module("Path.Op.Base", "PathScripts.PathOp")
PathUtils = first_module("PathScripts.PathUtils")
PathJob = first_module("Path.Main.Job", "PathScripts.PathJob")
PathToolController = first_module("Path.Tool.Controller", "PathScripts.PathToolController")
PathToolBit = first_module("Path.Tool.Bit", "PathScripts.PathToolBit")
PathFeedRate = first_module("Path.Base.FeedRate", "PathFeedRate")
PathSetupSheet = first_module("Path.Base.SetupSheet", "PathScripts.PathSetupSheet")


def version():
    """FreeCAD's (major, minor) version, e.g. (0, 20), (1, 1) or (26, 3): as
    numbers, so the calendar versions after 1.1 compare as newer."""
    major, minor = FreeCAD.Version()[:2]
    return int(major), int(minor)


def tool_bit_from_file(path, doc=None):
    """A tool bit document object from a .fctb file, as the Job's tool dialog
    makes one. 1.1: Path.Tool.ToolBit (an asset; its shape from the shape
    library), attached to doc (default: the active document). Before:
    PathToolBit.Factory.CreateFrom."""
    if tool_library() is None:
        return PathToolBit.Factory.CreateFrom(path)
    from Path.Tool import ToolBit
    return ToolBit.from_file(path).attach_to_doc(doc or FreeCAD.ActiveDocument)


def tool_library():
    """FreeCAD 1.1's asset library of tool bits, shapes and libraries
    (Path.Tool.cam_assets), or None before 1.1 (bits are .fctb files)."""
    if getattr(PathToolBit, "Factory", None) is not None:
        return None
    from Path.Tool import cam_assets
    return cam_assets


def bit_shape(bit):
    """A tool bit's shape, lower case: "endmill", "ballend", "bullnose", "drill",
    ... or the name of a shape file of the user's ("plungemill"). 1.1 bits say
    it in ShapeType (or, for a shape of the user's, "Custom" and the file's
    name in ShapeID); before 1.1 in BitShape, the shape file's name."""
    kind = str(getattr(bit, "ShapeType", "") or "")
    if kind and kind.lower() != "custom":
        return kind.lower()
    name = str(getattr(bit, "ShapeID", "") or getattr(bit, "BitShape", "") or "")
    return os.path.splitext(os.path.basename(name))[0].lower()


def voxel_simulator():
    """FreeCAD's voxel (height map) simulator, PathSimulator.PathSim: the engine
    behind the GUI's Path simulator in 0.20 and its legacy simulator in 1.0.
    Runs headless: BeginSimulation, SetToolShape, ApplyCommand, GetResultMesh."""
    import PathSimulator
    return PathSimulator.PathSim()


def post_module(name):
    """A post processor script module by its short name ("linuxcnc", "grbl")."""
    return first_module("Path.Post.scripts.%s_post" % name, "PathScripts.post.%s_post" % name)


def post_job(job, name, args):
    """The whole job's G-code through the named post processor, as the Job's post
    command makes it (operations and tool changes in the job's output order).

    1.0: Path.Post.Processor.PostProcessorFactory with the job's PostProcessorArgs.
    0.20: PathPost.CommandPathPost().buildPostList + the post module's export; the
    0.20 grbl post insists on writing a file, so it gets a temporary one."""
    try:
        from Path.Post.Processor import PostProcessorFactory
    except ImportError:
        PostProcessorFactory = None
    if PostProcessorFactory is not None:
        saved = job.PostProcessorArgs
        job.PostProcessorArgs = args
        try:
            post = PostProcessorFactory.get_post_processor(job, name)
            if post is None:
                raise ValueError("no post processor named %r" % name)
            return "\n".join(gcode or "" for _, gcode in post.export())
        finally:
            job.PostProcessorArgs = saved
    PathPost = first_module("PathScripts.PathPost")
    module = post_module(name)
    gcode = []
    for objects in PathPost.CommandPathPost().buildPostList(job):
        with tempfile.TemporaryDirectory() as scratch:
            out = os.path.join(scratch, "post.nc")
            text = module.export(objects, out if name == "grbl" else "-", args)
            if name == "grbl":
                with open(out) as f:
                    text = f.read()
        gcode.append(text or "")
    return "\n".join(gcode)
