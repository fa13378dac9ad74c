# PlungeRough FreeCAD addon: headless initialisation (App side).
# The Plunge Rough operation itself arrives with the FreeCAD addon issue; the
# core planner is the `plunge` module built from cpp/.
