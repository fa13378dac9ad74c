"""The Plunge Rough operation's GUI: command, view providers and task panel page.

The command and its icon come from this addon, not from FreeCAD's Qt resources,
so it brings its own view provider (icon, face selection gate) and creation
function; the page is loaded from resources/panels/PlungeRoughEdit.ui.
"""
import os
import weakref

import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from freecad_plugin import companions, plan_files, PlungeRough, rest, rest_gui, tools, uiforms
from freecad_plugin.constants import COMMAND, ICON, MENU_TEXT, PANEL, TOOL_TIP
from freecad_plugin import compat_gui
from freecad_plugin.compat import PathUtils
from freecad_plugin.compat_gui import gui_modules, gui_util

PathOpGui, PathSelection = gui_modules()
PathGui = gui_util()

translate = FreeCAD.Qt.translate



class SpinBox(PathGui.QuantitySpinBox):
    """FreeCAD's QuantitySpinBox helper whose focus filter only looks at events.
    With PySide2 (FreeCAD 0.20) a filter is now and then handed, instead of the
    event, the stale wrapper of a deleted widget that lived at the event's
    address; FreeCAD's own filter then raises "'QWidget' object has no
    attribute 'type'" in the report view."""

    def eventFilter(self, obj, event):
        if isinstance(event, QtCore.QEvent):
            return super().eventFilter(obj, event)
        return False


class PictureDialog(QtGui.QDialog):
    """A plan's picture (SVG, drawn by Qt's SVG image plugin), scaled to fit
    the screen, with its file's path to open it elsewhere."""

    def __init__(self, path, title, parent=None):
        super().__init__(parent)
        self.setWindowTitle(translate("PlungeRough", "Plunge Rough: %s") % title)
        self.setAttribute(QtCore.Qt.WA_DeleteOnClose)
        layout = QtGui.QVBoxLayout(self)
        self.image = QtGui.QLabel()
        pixmap = QtGui.QPixmap(path)
        screen = QtGui.QGuiApplication.primaryScreen().availableGeometry()
        if not pixmap.isNull():
            pixmap = pixmap.scaled(int(0.6 * screen.width()), int(0.75 * screen.height()),
                                   QtCore.Qt.KeepAspectRatio, QtCore.Qt.SmoothTransformation)
        self.image.setPixmap(pixmap)
        layout.addWidget(self.image)
        where = QtGui.QLabel(path)
        where.setTextInteractionFlags(QtCore.Qt.TextSelectableByMouse)
        layout.addWidget(where)
        close = QtGui.QDialogButtonBox(QtGui.QDialogButtonBox.Close)
        close.rejected.connect(self.close)
        layout.addWidget(close)


class TaskPanelOpPage(PathOpGui.TaskPanelPage):
    """The operation's own page: plungers, allowances, cycle, the plan's summary."""

    def getForm(self):
        return uiforms.load(PANEL, FreeCADGui.PySideUic.loadUi)

    def initPage(self, obj):
        self.spins = {
            "RadialAllowance": SpinBox(self.form.radialAllowance, obj, "RadialAllowance"),
            "FloorAllowance": SpinBox(self.form.floorAllowance, obj, "FloorAllowance"),
            "ChordTolerance": SpinBox(self.form.chordTolerance, obj, "ChordTolerance"),
            "PeckDepth": SpinBox(self.form.peckDepth, obj, "PeckDepth"),
            "MaxWallStock": SpinBox(self.form.maxWallStock, obj, "MaxWallStock"),
            "MaxFloorStock": SpinBox(self.form.maxFloorStock, obj, "MaxFloorStock"),
            "LeadOut": SpinBox(self.form.leadOut, obj, "LeadOut"),
            "StickOut": SpinBox(self.form.stickOut, obj, "StickOut"),
            "HolderDiameter": SpinBox(self.form.holderDiameter, obj, "HolderDiameter"),
            "HolderClearance": SpinBox(self.form.holderClearance, obj, "HolderClearance"),
        }
        self.obj = obj
        self.picture = None
        for button, name in self._pictureButtons():
            button.clicked.connect(lambda checked=False, name=name: self.showPicture(name))
        self.form.restSolid.clicked.connect(self.showRestSolid)
        self._enablePictures()

    def _pictureButtons(self):
        return [(self.form.showPlan, "plan.svg"), (self.form.showStock, "plan-stock.svg"),
                (self.form.showHeights, "plan-heights.svg")]

    def _enablePictures(self):
        """A picture's button is live when the last plan drew it, or when no
        picture is drawn yet (a plan restored with its document: the pictures
        sit in a temporary folder, and a click draws them)."""
        if getattr(self, "obj", None) is None:  # before initPage
            return
        drawn = [os.path.exists(plan_files.plan_picture(self.obj, name)) for _, name in self._pictureButtons()]
        for (button, _), there in zip(self._pictureButtons(), drawn):
            button.setEnabled(there or not any(drawn))

    def showPicture(self, name):
        """One of the last plan's pictures in a window of its own beside the
        panel; planned again first when it is not drawn (None when the plan
        has no such picture: stop heights over a flat floor)."""
        if self.picture is not None:
            self.picture.close()
            self.picture = None
        if not os.path.exists(plan_files.plan_picture(self.obj, name)):
            self.obj.touch()
            self.obj.Document.recompute()
            self._enablePictures()
            if not os.path.exists(plan_files.plan_picture(self.obj, name)):
                return None
        self.picture = PictureDialog(plan_files.plan_picture(self.obj, name),
                                     dict((n, t) for _, n, t in plan_files.PICTURES)[name],
                                     FreeCADGui.getMainWindow())
        self.picture.show()
        return self.picture

    def showRestSolid(self):
        """The operation's rest material feature (made once, then shown)."""
        feature = rest.rest_solid_of(self.obj) or rest_gui.make_and_show(self.obj)
        if feature.ViewObject is not None:
            feature.ViewObject.Visibility = True
        return feature

    def cleanupPage(self, obj):
        if self.picture is not None:
            self.picture.close()
            self.picture = None
        # The panel's widgets are deleted with it: no filter left on them and
        # no wrapper of them kept alive by this page (a stale wrapper is what
        # SpinBox guards against).
        for spin in self.spins.values():
            spin.widget.removeEventFilter(spin)
        self.spins = {}

    def getTitle(self, obj):
        return translate("PlungeRough", "Plunge Rough")

    def _jobToolControllers(self):
        """The plungers offered in the list (drills, V-bits, tool controllers
        without a vertical feed are not), plus any the operation already uses."""
        job = PathUtils.findParentJob(self.obj)
        offered = tools.job_plungers(job)
        return offered + [tc for tc in self.obj.ToolControllers if tc not in offered]

    def getFields(self, obj):
        """UI to object."""
        for spin in self.spins.values():
            spin.updateProperty()
        for prop, box in (("UseCannedCycle", self.form.useCannedCycle), ("PeckEnabled", self.form.peckEnabled)):
            if getattr(obj, prop) != box.isChecked():
                setattr(obj, prop, box.isChecked())
        if abs(obj.DwellTime - self.form.dwellTime.value()) > 1e-9:
            obj.DwellTime = self.form.dwellTime.value()
        if obj.AutoSelectTools != self.form.autoSelectTools.isChecked():
            obj.AutoSelectTools = self.form.autoSelectTools.isChecked()
        if obj.Strategy != self.form.strategy.currentText():
            obj.Strategy = self.form.strategy.currentText()
        if obj.RestFrom != self.form.restFrom.currentText():
            obj.RestFrom = self.form.restFrom.currentText()
        if abs(obj.MinCoverage - self.form.minCoverage.value()) > 1e-9:
            obj.MinCoverage = self.form.minCoverage.value()
        for prop, box in (("MaxEngagement", self.form.maxEngagement), ("MinEngagement", self.form.minEngagement)):
            if abs(getattr(obj, prop) - box.value()) > 1e-9:
                setattr(obj, prop, box.value())
        if obj.StockAwareHeights != self.form.stockAwareHeights.isChecked():
            obj.StockAwareHeights = self.form.stockAwareHeights.isChecked()
        self.updateCoolant(obj, self.form.coolantController)
        chosen = []
        for i, tc in enumerate(self._jobToolControllers()):
            if self.form.toolControllers.item(i).checkState() == QtCore.Qt.Checked:
                chosen.append(tc)
        if chosen and chosen != list(obj.ToolControllers):
            obj.ToolControllers = chosen

    def setFields(self, obj):
        """Object to UI."""
        for spin in self.spins.values():
            compat_gui.refresh_spin_box(spin)
        self.form.useCannedCycle.setChecked(obj.UseCannedCycle)
        self.form.peckEnabled.setChecked(obj.PeckEnabled)
        self.form.dwellTime.setValue(obj.DwellTime)
        self.form.autoSelectTools.setChecked(obj.AutoSelectTools)
        self.form.strategy.blockSignals(True)
        self.form.strategy.clear()
        self.form.strategy.addItems(obj.getEnumerationsOfProperty("Strategy"))
        self.form.strategy.setCurrentText(obj.Strategy)
        self.form.strategy.blockSignals(False)
        self.form.restFrom.blockSignals(True)
        self.form.restFrom.clear()
        self.form.restFrom.addItems(obj.getEnumerationsOfProperty("RestFrom"))
        self.form.restFrom.setCurrentText(obj.RestFrom)
        self.form.restFrom.blockSignals(False)
        self.form.minCoverage.setValue(obj.MinCoverage)
        self.form.maxEngagement.setValue(obj.MaxEngagement)
        self.form.minEngagement.setValue(obj.MinEngagement)
        self.form.stockAwareHeights.setChecked(obj.StockAwareHeights)
        self.form.cannedCycleNote.setVisible(obj.UseCannedCycle)
        self.setupCoolant(obj, self.form.coolantController)
        self.form.toolControllers.blockSignals(True)
        self.form.toolControllers.clear()
        for tc in self._jobToolControllers():
            item = QtGui.QListWidgetItem(tools.label(tc))
            item.setToolTip(item.text())  # elided in a narrow panel
            item.setFlags(item.flags() | QtCore.Qt.ItemIsUserCheckable)
            item.setCheckState(QtCore.Qt.Checked if tc in obj.ToolControllers else QtCore.Qt.Unchecked)
            self.form.toolControllers.addItem(item)
        self.form.toolControllers.blockSignals(False)
        self.form.summary.setText(obj.Summary)
        self._enablePictures()

    def getSignalsForUpdate(self, obj):
        return [
            self.form.radialAllowance.editingFinished,
            self.form.floorAllowance.editingFinished,
            self.form.chordTolerance.editingFinished,
            self.form.peckDepth.editingFinished,
            self.form.peckEnabled.stateChanged,
            self.form.dwellTime.editingFinished,
            self.form.maxWallStock.editingFinished,
            self.form.maxFloorStock.editingFinished,
            self.form.leadOut.editingFinished,
            self.form.stickOut.editingFinished,
            self.form.holderDiameter.editingFinished,
            self.form.holderClearance.editingFinished,
            self.form.maxEngagement.editingFinished,
            self.form.minEngagement.editingFinished,
            self.form.stockAwareHeights.stateChanged,
            self.form.useCannedCycle.stateChanged,
            self.form.autoSelectTools.stateChanged,
            self.form.strategy.currentIndexChanged,
            self.form.restFrom.currentIndexChanged,
            self.form.minCoverage.editingFinished,
            self.form.coolantController.currentIndexChanged,
            self.form.toolControllers.itemChanged,
        ]

    def updateData(self, obj, prop):
        if prop == "Summary":
            self.form.summary.setText(obj.Summary)
        # A recompute that plans the same again changes no Summary: the pictures
        # are looked for whatever changed.
        self._enablePictures()
        if prop == "UseCannedCycle":
            self.form.cannedCycleNote.setVisible(obj.UseCannedCycle)


class ViewProvider(PathOpGui.ViewProvider):
    """The operation's view provider with the addon's icon and a face selection gate."""

    def attach(self, vobj):
        super().attach(vobj)
        # FreeCAD's base class looks the icon up as ":/icons/<pixmap>.svg" in its
        # own resources; this addon's icon is a file.
        self.OpIcon = ICON

    def getIcon(self):
        return ICON

    def setupTaskPanel(self, panel):
        super().setupTaskPanel(panel)
        # Held weakly: a closure over the panel (or its bound reject) stored on
        # the panel is a reference cycle, which keeps the closed panel's Qt
        # wrappers alive until a later garbage collection; collected then, in
        # the middle of opening another panel, they broke it ("Internal C++
        # object already deleted" in FreeCAD's base geometry page).
        ref = weakref.ref(panel)

        def rejectAndTidy(resetEdit=True):
            # Cancel rolls the operation back; companions made while the panel
            # was open (ticked plungers) or of a removed new operation go too.
            this = ref()
            result = type(this).reject(this, resetEdit)
            companions.removeOrphans(FreeCAD.ActiveDocument)
            return result

        panel.reject = rejectAndTidy

    def getSelectionFactory(self):
        return PathSelection.pocketselect

    def onDelete(self, vobj, arg2=None):
        # The companion operations belong to this one.
        for comp in companions.companions(vobj.Object):
            comp.Document.removeObject(comp.Name)
        return super().onDelete(vobj, arg2)


class CompanionViewProvider:
    """View provider of the companion operations: the icon; editing opens the main op."""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        return ICON

    def setEdit(self, vobj, mode=0):
        main = vobj.Object.PlanOperation
        if main is not None and main.ViewObject:
            main.ViewObject.Document.setEdit(main.ViewObject, 0)
        return False

    def canDelete(self, obj):
        # The Plunge Rough operation may go: it takes its companions with it.
        return obj == self.Object.PlanOperation

    def onDelete(self, vobj, subelements=None):
        """Deleting a companion drops its plunger from the plan: the operation
        replans with the others, so no plunge is silently lost."""
        comp = vobj.Object
        doc, name, main = comp.Document, comp.Name, comp.PlanOperation
        if main is not None and comp.ToolController in main.ToolControllers:
            main.ToolControllers = [tc for tc in main.ToolControllers if tc != comp.ToolController]
            main.touch()
            return doc.getObject(name) is not None  # False: the operation removed it already
        return True

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


def _adoptCompanions(obj):
    for comp in companions.companions(obj):
        if comp.ViewObject and not isinstance(comp.ViewObject.Proxy, CompanionViewProvider):
            CompanionViewProvider(comp.ViewObject)


def resources():
    return PathOpGui.CommandResources(COMMAND, PlungeRough.Create, TaskPanelOpPage, ICON, MENU_TEXT, None, TOOL_TIP)


def create_from_command():
    """What the Plunge Rough command runs: a new operation on the selection."""
    return create(resources())


def attach_view_providers(obj):
    """The operation's and its companions' view providers, as the command gives
    them (for operations made by a script in the GUI)."""
    obj.ViewObject.Proxy = ViewProvider(obj.ViewObject, resources())
    obj.ViewObject.Proxy.deleteOnReject = False
    _adoptCompanions(obj)


def create(res):
    """PathOpGui.Create with this addon's view provider."""
    doc = FreeCAD.ActiveDocument
    doc.openTransaction("Create Plunge Rough")
    try:
        obj = res.objFactory(res.name, obj=None, parentJob=res.job)
        if obj.Proxy:
            obj.ViewObject.Proxy = ViewProvider(obj.ViewObject, res)
            obj.ViewObject.Visibility = True
            doc.commitTransaction()
            obj.ViewObject.Document.setEdit(obj.ViewObject, 0)
            return obj
    except Exception as e:  # no tool controller, no job: say so
        FreeCAD.Console.PrintError("Plunge Rough: %s\n" % e)
    doc.abortTransaction()
    doc.recompute()
    return None


class _DocumentObserver:
    """Gives companion operations made during editing their view provider."""

    def slotRecomputedObject(self, obj):
        if getattr(obj, "PlanData", None) is not None and isinstance(getattr(obj, "Proxy", None),
                                                                    PlungeRough.ObjectPlungeRough):
            _adoptCompanions(obj)

    def slotCreatedObject(self, obj):
        pass


_observer = []


def _watch_documents():
    """Companions made while editing get their view provider (once per session)."""
    if not _observer:
        _observer.append(_DocumentObserver())
        FreeCAD.addDocumentObserver(_observer[0])


_watch_documents()
