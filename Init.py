# PlungeRough FreeCAD addon: headless initialisation (runs in freecadcmd too).
# Nothing to do yet at this point: FreeCAD's Path modules cannot be imported
# while FreeCAD is still starting (FreeCAD.GuiUp is not set), so the operation
# registers with the job setup sheets when freecad_plugin.PlungeRough is first
# imported (creating the op, opening a document that holds one, or the GUI
# command). The compiled planner (`plunge`) sits beside this file.
