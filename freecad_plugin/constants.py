"""The addon's names and files, in one leaf module: every other module may
import it, and it imports none of theirs (so no two modules import each other).
Only os and Qt's translation marker: InitGui.py reads it at FreeCAD's start."""
import os

from PySide.QtCore import QT_TRANSLATE_NOOP

# The addon's folder (the one holding Init.py, resources/ and bin/).
ADDON = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
COMMAND = "PlungeRough"
ICON = os.path.join(ADDON, "resources", "icons", "PlungeRough.svg")
PANEL = os.path.join(ADDON, "resources", "panels", "PlungeRoughEdit.ui")
MENU_TEXT = QT_TRANSLATE_NOOP("PlungeRough", "Plunge Rough")
TOOL_TIP = QT_TRANSLATE_NOOP(
    "PlungeRough", "Rough the selected pocket floor by plunging: packed and covered plunges of several plunger "
    "sizes, short tours, per-plunge depths")
# The workbench toolbar the command joins.
TOOLBAR = "New Operations"
