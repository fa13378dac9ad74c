"""The Plunge Rough command and its place in the CAM (1.0) / Path (0.20) workbench.

InitGui.py runs this at FreeCAD's start, before any Path module may be imported,
so this module imports only FreeCAD, FreeCADGui and the addon's constants; the
operation's GUI (freecad_plugin.PlungeRoughGui) is imported when the command
first runs, and imports nothing of this module.

- FreeCAD 1.0 has workbench manipulators: the command goes into the CAM menu
  after Adaptive and at the end of the "New Operations" toolbar, by FreeCAD
  itself, whenever the CAM workbench is built.
- FreeCAD 0.20 has none: the command is added to the Path workbench's "New
  Operations" toolbar definition and its action to the Path menu after Adaptive.
"""
import FreeCAD
import FreeCADGui

from freecad_plugin.constants import COMMAND, ICON, MENU_TEXT, TOOL_TIP, TOOLBAR

translate = FreeCAD.Qt.translate


class CommandPlungeRough:
    """The "Plunge Rough" command: a new operation on the selected floor face."""

    def GetResources(self):
        return {"Pixmap": ICON, "MenuText": translate("PlungeRough", MENU_TEXT),
                "ToolTip": translate("PlungeRough", TOOL_TIP)}

    def IsActive(self):
        doc = FreeCAD.ActiveDocument
        return doc is not None and any(o.Name.startswith("Job") for o in doc.Objects)

    def Activated(self):
        from freecad_plugin import PlungeRoughGui
        return PlungeRoughGui.create_from_command()


class Manipulator:
    """FreeCAD 1.0's workbench manipulator: adds the command where CAM's own
    operations are. Items naming CAM commands or toolbars only match in CAM."""

    def modifyMenuBar(self):
        return [{"insert": COMMAND, "menuItem": "CAM_Adaptive", "after": ""}]

    def modifyToolBars(self):
        return [{"append": COMMAND, "toolBar": TOOLBAR}]


def _insert_into_path_workbench(name):
    """0.20: the command joins the Path workbench's "New Operations" toolbar
    definition once (FreeCAD then makes its action, greyed out while it is not
    active), and its action is put after Adaptive in the Path menu whenever
    FreeCAD rebuilds that menu (every activation)."""
    if name != "PathWorkbench":
        return
    if not _toolbar_added:
        _toolbar_added.append(True)
        workbench = FreeCADGui.getWorkbench(name)
        workbench.appendToolbar(TOOLBAR, [COMMAND])
        workbench.reloadActive()
    actions = FreeCADGui.Command.get(COMMAND).getAction()
    if not actions:
        return
    action = actions[0]
    for menu_action in FreeCADGui.getMainWindow().menuBar().actions():
        menu = menu_action.menu()
        if menu is None or menu_action.text().replace("&", "") != "Path" or action in menu.actions():
            continue
        items = menu.actions()
        after = [i for i, a in enumerate(items) if a.objectName() == "Path_Adaptive"]
        if after and after[0] + 1 < len(items):
            menu.insertAction(items[after[0] + 1], action)
        else:
            menu.addAction(action)


_toolbar_added = []
_installed = []


def install():
    """Registers the command and puts it into the workbench (once; InitGui.py)."""
    if _installed:
        return
    FreeCADGui.addCommand(COMMAND, CommandPlungeRough())
    if hasattr(FreeCADGui, "addWorkbenchManipulator"):
        _installed.append(Manipulator())
        FreeCADGui.addWorkbenchManipulator(_installed[0])
    else:
        _installed.append(_insert_into_path_workbench)
        FreeCADGui.getMainWindow().workbenchActivated.connect(_insert_into_path_workbench)
