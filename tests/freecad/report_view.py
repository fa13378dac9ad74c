"""The GUI test's reading of FreeCAD's report view: which lines are errors, and
which tracebacks are FreeCAD's own known bugs (set aside, and recorded). Plain
Python but read(), so that test_report_view.py checks it on report views as
FreeCAD writes them, on every version."""
import re

# FreeCAD's own bugs that the GUI test sets aside (each recorded, with the step
# it came in, in its result["report_known_upstream"]); every other traceback fails it.
# A traceback is one of them if it has all the parts of one of a bug's forms.
UPSTREAM_BUGS = {
    # FreeCAD 0.20's tool bit editor (PathToolBitEdit.ToolBitEditor) now and
    # then finds a widget it has just loaded from its own .ui file already
    # deleted, or wrapped as another (a stale PySide wrapper: its toolName a
    # QDialogButtonBox), while it builds itself (FreeCAD's code only).
    "editor": [("PathToolBitEdit.py", "self.form.bitParams.layout()",
                "Internal C++ object (PySide2.QtWidgets.QWidget) already deleted."),
               ("PathToolBitEdit.py", "in updateUI", "self.form.", "<class 'AttributeError'>: 'PySide2.QtWidgets.",
                "object has no attribute")],
    # FreeCAD's QuantitySpinBox helper (PathGui.py before 1.0,
    # Path/Base/Gui/Util.py since; the same code in both) is now and then
    # handed a deleted widget's stale wrapper instead of the event its focus
    # filter installed on a spin box gets; seen once on 0.20, in a page of
    # FreeCAD's own (this addon's page guards its filters: PlungeRoughGui.SpinBox).
    # FreeCAD 0.20's operation task panel (PathOpGui.TaskPanel) now and then
    # finds a page's form it has just loaded already deleted when it adds it
    # to its toolbox (the same PySide2 stale-wrapper family; seen once here,
    # opening this operation's panel a second time in a session). Whether this
    # addon's page has a part in it is not established.
    "panel": [("PathOpGui.py", "in setEdit", "toolbox.addItem(page.form",
               "Internal C++ object (PySide2.QtWidgets.QWidget) already deleted.")],
    # FreeCAD 1.0's and 1.1's OpenGL simulator (SimulatorGL.CAMSimulation.Activate)
    # now and then finds a widget of its panel (its accuracy slider, its list
    # of operations) wrapped as another (a QDialog: the voxel simulator's task
    # form, closed just before, whose wrapper FreeCAD's voxel simulator keeps),
    # or (1.1 with PySide6) its play button, just loaded, already deleted; both
    # seen with PySide2's and PySide6's messages. The same stale-wrapper
    # family, all in FreeCAD's code. No panel opens; the
    # user runs the command again, and so does play_gl_simulator, up to three times.
    "simulator": [("SimulatorGL.py", "in Activate", "form.", "'PySide", ".QtWidgets.", "object has no attribute"),
                  ("SimulatorGL.py", "in Activate", "form.", "Internal C++ object (PySide",
                   ") already deleted.")],
    "spin box filter": [("in eventFilter", "if event.type() == QtCore.QEvent.Type.FocusIn",
                         "QtWidgets.QWidget' object has no attribute 'type'")],
}


OLD_ONLY = {"editor", "panel"}  # seen on FreeCAD 0.20 only: set aside there only


def upstream_bug(trace, old):
    """Which of UPSTREAM_BUGS a traceback (its lines joined) is, or None: only
    one whose every frame is in FreeCAD's own installed code, and the editor's
    only on 0.20 (old), where it was seen."""
    frames = re.findall(r'File "([^"]+)"', trace)
    if not frames or not all(f.startswith("/usr/") and "/freecad/Mod/" in f for f in frames):
        return None
    for name, forms in UPSTREAM_BUGS.items():
        if (old or name not in OLD_ONLY) and any(all(part in trace for part in parts) for parts in forms):
            return name
    return None


def continues(trace, text, red):
    """Whether a report view line (text, shown red or not) belongs to the
    traceback read so far (trace, its lines). FreeCAD writes a failed
    command's traceback, a blank line, then its exception's message, red,
    with no line end: whatever is written next follows on that line."""
    if text.startswith(" "):
        return True  # a frame, its code, its carets
    last = trace[-1]
    told = last != "" and not last.startswith(" ") and not last.startswith("Traceback")
    return not told and (text == "" or red)  # up to the exception's message


def classify(lines, old):
    """The report view's errors (a list of lines), and FreeCAD's own known ones
    (old: the version is 0.x), each a (name in UPSTREAM_BUGS, its traceback's
    lines joined). lines: the report view's lines, each (text, shown red)."""
    errors, known, trace = [], [], []
    for text, red in lines + [(None, False)]:
        if trace and text is not None and continues(trace, text, red):
            trace.append(text)
            continue
        if trace:
            whole = "\n".join(line for line in trace if line)
            bug = upstream_bug(whole, old)
            if bug:
                known.append((bug, whole))
            else:
                errors.extend(line for line in trace if line)
            trace = []
        if text is None:
            break
        if "Traceback" in text:
            # A command's traceback comes after FreeCAD's line naming the command.
            header = errors[-1:] if errors and re.search(r"Running the Python command '\w+' failed:$", errors[-1]) else []
            del errors[len(errors) - len(header):]
            trace = header + [text]
        elif red and old and text.endswith("<class 'AttributeError'>: setAttr failed."):
            # FreeCAD 0.20 itself reports this on opening any document with tool
            # bits (its ToolBit proxies), with or without this addon; 1.0 does not.
            pass
        elif red:
            errors.append(text)
    return errors, known


def read(document):
    """The lines of the report view's document, each (text, shown red: the
    colour of its highlighter in a default profile). A line's layout is
    fetched as a QTextLayout: PySide may hand on a stale wrapper of another
    class at its address (a QListWidgetItem, once, in a CI run)."""
    from PySide import QtCore, QtGui
    from freecad_plugin import uiforms
    red = QtGui.QColor(QtCore.Qt.red)
    lines, block = [], document.begin()
    while block.isValid():
        layout = uiforms.fetched(block.layout, QtGui.QTextLayout)
        lines.append((block.text(), any(r.format.foreground().color() == red for r in layout.formats())))
        block = block.next()
    return lines
