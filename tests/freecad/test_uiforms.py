"""freecad_plugin/uiforms.py: the operation's real form, loaded by Qt's own
loader, with a wrong wrapper put where PySide hands on a stale one (a wrapper
of another class at the widget's address, as FreeCAD 1.1 gave the "Rest from"
combo box as a QWidget, and its simulator's slider as a QDialog). Headless: Qt's offscreen platform."""
import os

import pytest

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
from PySide import QtCore, QtGui  # noqa: E402

from freecad_plugin import uiforms  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PANEL = os.path.join(ROOT, "resources", "panels", "PlungeRoughEdit.ui")


@pytest.fixture(scope="module")
def app():
    return QtGui.QApplication.instance() or QtGui.QApplication([])


def load(path):
    """The form as Qt's loader makes it, each named widget an attribute (as
    FreeCADGui.PySideUic.loadUi gives it)."""
    from PySide import QtUiTools
    f = QtCore.QFile(path)
    f.open(QtCore.QFile.ReadOnly)
    form = QtUiTools.QUiLoader().load(f)
    f.close()
    for name in uiforms.widget_classes(path):
        child = form.findChild(QtCore.QObject, name)
        if child is not None:
            setattr(form, name, child)
    return form


def address(wrapper):
    return uiforms.shiboken().getCppPointer(wrapper)[0]


def test_every_widget_of_the_panel_has_its_class(app):
    classes = uiforms.widget_classes(PANEL)
    assert classes["restFrom"] is QtGui.QComboBox
    assert classes["radialAllowance"] is QtGui.QWidget  # Gui::QuantitySpinBox extends QWidget
    assert len(classes) >= 40


@pytest.mark.skipif(QtGui.QWidget.__module__.startswith("PySide6"),
                    reason="shiboken6 hands back the registered wrapper, of any class: no wrong one can be made, "
                           "and none replaced (the garbage collection before loading is what serves there)")
def test_a_wrong_wrapper_is_replaced_by_one_of_its_class_at_the_same_widget(app):
    form = load(PANEL)
    combo = form.restFrom
    assert isinstance(combo, QtGui.QComboBox)
    sb = uiforms.shiboken()
    # A wrapper of a class the widget is not, as PySide handed one on.
    form.restFrom = sb.wrapInstance(address(combo), QtGui.QDialog)
    form.toolControllers = sb.wrapInstance(address(form.toolControllers), QtGui.QLabel)
    assert not hasattr(form.restFrom, "addItems")
    assert uiforms.retyped(form, PANEL) is form
    assert isinstance(form.restFrom, QtGui.QComboBox) and address(form.restFrom) == address(combo)
    form.restFrom.addItems(["Previous operations", "Job stock", "None"])
    assert combo.count() == 3  # the same widget
    assert isinstance(form.toolControllers, QtGui.QListWidget)
    for name, cls in uiforms.widget_classes(PANEL).items():
        if name != form.objectName():  # the form itself
            assert isinstance(getattr(form, name), cls), name


def test_a_closed_forms_wrappers_in_a_cycle_are_gone_before_the_next_loads(app):
    import weakref
    old = load(PANEL)
    holder = {"form": old}
    holder["self"] = holder  # a cycle, as FreeCAD's closed panel keeps its pages
    combo = weakref.ref(old.restFrom)
    del old, holder
    assert combo() is not None  # alive until a garbage collection
    form = uiforms.load(PANEL, load)
    assert combo() is None
    assert isinstance(form.restFrom, QtGui.QComboBox)


def test_right_wrappers_are_left_as_they_are(app):
    form = load(PANEL)
    before = {name: getattr(form, name, None) for name in uiforms.widget_classes(PANEL)}
    uiforms.retyped(form, PANEL)
    assert all(getattr(form, name, None) is w for name, w in before.items())
