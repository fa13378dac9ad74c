"""A task panel's form whose named widgets are each wrapped as their class.

PySide keeps one Python wrapper per C++ address. A widget that C++ deletes
while its wrapper is still referenced leaves that wrapper registered, and
PySide hands it on to the next widget made at the same address: FreeCAD 1.1
(PySide6) gave this page's "Rest from" combo box as a QWidget, with no
addItems, and the panel did not open. A closed operation panel, its pages,
forms and widgets' wrappers stay alive in reference cycles of FreeCAD's panel
until Python's next garbage collection (seen on 1.1), so the form is loaded
after one. A wrong wrapper still left is replaced by one of the widget's
class at the same address (PySide2; shiboken6 hands back the registered one). No FreeCAD import:
tests/freecad/test_uiforms.py checks it headless."""
import gc
import xml.etree.ElementTree as ElementTree

from PySide import QtGui


def shiboken():
    """The binding's helper module (shiboken2 for PySide2, shiboken6 for PySide6)."""
    if QtGui.QWidget.__module__.startswith("PySide6"):
        import shiboken6 as module
    else:
        import shiboken2 as module
    return module


def widget_classes(path):
    """The .ui file's named widgets: {name: Qt class}; a custom widget
    (Gui::QuantitySpinBox) as the Qt class it extends."""
    root = ElementTree.parse(path).getroot()
    extends = {c.findtext("class"): c.findtext("extends") for c in root.iter("customwidget")}
    classes = {}
    for w in root.iter("widget"):
        cls = getattr(QtGui, extends.get(w.get("class"), w.get("class")), None)
        if cls is not None:
            classes[w.get("name")] = cls
    return classes


def rewrapped(wrapper, cls):
    """wrapper if it is a cls, else a cls wrapper of the same C++ object
    (PySide2; shiboken6 hands back the registered one)."""
    if isinstance(wrapper, cls):
        return wrapper
    module = shiboken()
    return module.wrapInstance(module.getCppPointer(wrapper)[0], cls)


def fetched(get, cls):
    """The Qt object get() returns, as a cls wrapper. A wrapper of another
    class is a stale one at the object's address: get() again after a garbage
    collection, else rewrapped; a TypeError naming both when neither serves."""
    wrapper = get()
    if not isinstance(wrapper, cls):
        gc.collect()
        wrapper = rewrapped(get(), cls)
    if not isinstance(wrapper, cls):
        raise TypeError("PySide gave a stale %s wrapper for a %s" % (type(wrapper).__name__, cls.__name__))
    return wrapper


def retyped(form, path):
    """form, loaded from the .ui file at path, with each named widget's
    attribute a wrapper of its class (the same widget)."""
    for name, cls in widget_classes(path).items():
        wrapper = getattr(form, name, None)
        if wrapper is not None:
            setattr(form, name, rewrapped(wrapper, cls))
    return form


def load(path, load_ui):
    """The form of the .ui file at path, loaded by load_ui
    (FreeCADGui.PySideUic.loadUi) once closed panels' wrappers are collected,
    each named widget wrapped as its class."""
    gc.collect()
    return retyped(load_ui(path), path)
