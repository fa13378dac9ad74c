# PlungeRough FreeCAD addon: GUI initialisation (nothing yet; see Init.py).
