"""PlungeRough's FreeCAD Path operation (App proxy, generator and GUI) lives here."""
