"""Run by install_addon.sh inside freecadcmd, after the addon is installed: the
plunge-mill tool-bit shape, example bits and their tool library, made by this
FreeCAD (freecad_plugin/plunge_mill.py), into the installed addon's Tools
folder; on FreeCAD 1.1 also into the user's CAM asset library."""
import os
import sys

root = os.environ["PLUNGE_ADDON"]
sys.path.insert(0, root)
from freecad_plugin import compat, plunge_mill  # noqa: E402

plunge_mill.install(root)
print("TOOLS=%s%s" % (os.path.join(root, "Tools"), " and the CAM asset library" if compat.tool_library() else ""))
