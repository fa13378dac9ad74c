"""The GUI test's reading of the report view (report_view.py), on report views
as FreeCAD 0.20, 1.0 and 1.1 write them: tests/data/report_view/, recorded by
report_view_capture.py. A failed command's traceback there ends with a blank
line, then its message, red, with whatever comes next on the same line."""
import gc
import glob
import json
import os

import pytest

from report_view import classify, read

HERE = os.path.dirname(os.path.abspath(__file__))
CAPTURES = sorted(glob.glob(os.path.join(HERE, "..", "data", "report_view", "report_view-*.json")))
# The frames of FreeCAD 1.0's OpenGL simulator failing in its own code, as the
# report view showed them in a CI run (its stale-wrapper bug, UPSTREAM_BUGS).
SIMULATOR_FRAMES = [
    '  File "/usr/share/freecad/Mod/CAM/Path/Main/Gui/SimulatorGL.py", line 366, in Activated',
    '    CamSimulation.Activate()',
    '  File "/usr/share/freecad/Mod/CAM/Path/Main/Gui/SimulatorGL.py", line 219, in Activate',
    '    self.Connect(form.toolButtonPlay, self.SimPlay)',
    '  File "/usr/share/freecad/Mod/CAM/Path/Main/Gui/SimulatorGL.py", line 115, in Connect',
    '    QtCore.QObject.connect(but, QtCore.SIGNAL("clicked()"), sig)',
]


def capture(path):
    with open(path) as f:
        data = json.load(f)
    return [tuple(line) for line in data["lines"]], data["freecad"].startswith("0.")


def with_frames(lines, frames, binding="PySide2"):
    """The captured report view with its traceback's frames replaced."""
    first = next(i for i, (text, _) in enumerate(lines) if text.startswith("Traceback"))
    blank = next(i for i in range(first, len(lines)) if lines[i][0] == "")
    message = [(text.replace("PySide2", binding), red) for text, red in lines[blank:]]
    return lines[:first + 1] + [(f, True) for f in frames] + message


def test_every_version_is_recorded():
    assert [os.path.basename(p) for p in CAPTURES] == [
        "report_view-0.20.json", "report_view-1.0.json", "report_view-1.1.json"]


@pytest.mark.parametrize("path", CAPTURES, ids=os.path.basename)
def test_a_command_failing_in_other_code_is_an_error_with_its_message(path):
    lines, old = capture(path)
    errors, known = classify(lines, old)
    assert known == []
    red = [text for text, shown_red in lines if shown_red]
    assert errors == red  # the header, the traceback, its message, the later error
    assert any("already deleted." in e for e in errors)
    assert not any(text in errors for text, shown_red in lines if not shown_red)


@pytest.mark.parametrize("binding", ["PySide2", "PySide6"])
@pytest.mark.parametrize("path", CAPTURES, ids=os.path.basename)
def test_freecads_own_simulator_bug_is_set_aside_whole(path, binding):
    lines, old = capture(path)
    errors, known = classify(with_frames(lines, SIMULATOR_FRAMES, binding), old)
    assert [bug for bug, _ in known] == ["simulator"]
    trace = known[0][1]
    assert trace.startswith(lines[0][0]) and "already deleted." in trace  # header to message
    assert errors == [lines[-2][0]]  # only the error after it
    assert "an error after it" in errors[0]


@pytest.mark.parametrize("path", CAPTURES, ids=os.path.basename)
def test_the_same_bug_through_other_code_is_an_error(path):
    lines, old = capture(path)
    frames = ['  File "/root/PlungeRough/freecad_plugin/PlungeRoughGui.py", line 1, in show'] + SIMULATOR_FRAMES
    errors, known = classify(with_frames(lines, frames), old)
    assert known == []
    assert frames[0] in errors and any("already deleted." in e for e in errors)


@pytest.mark.parametrize("path", CAPTURES, ids=os.path.basename)
def test_two_failures_in_a_row_are_two_bugs(path):
    lines, old = capture(path)
    once = with_frames(lines, SIMULATOR_FRAMES)[:-2]  # up to its message
    errors, known = classify(once + once, old)
    assert [bug for bug, _ in known] == ["simulator", "simulator"] and errors == []


@pytest.fixture(scope="module")
def qt():
    """Qt, offscreen, for read() on a document highlighted as the report view's."""
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from PySide import QtCore, QtGui
    app = QtGui.QApplication.instance() or QtGui.QApplication([])

    class Highlighter(QtGui.QSyntaxHighlighter):
        def highlightBlock(self, text):  # red as FreeCAD's report highlighter shows an error
            if "error" in text:
                self.setFormat(0, len(text), QtGui.QColor(QtCore.Qt.red))

    return QtCore, QtGui, Highlighter, app


def report(qt, text):
    QtCore, QtGui, Highlighter, _ = qt
    document = QtGui.QTextDocument()
    document.setPlainText(text)
    highlighter = Highlighter(document)
    highlighter.rehighlight()
    return document, highlighter


TEXT = "a message\nan error\n\nTraceback (most recent call last):\n  File \"x.py\", line 1\nan error again"
FLAGS = [False, True, False, False, False, True]


def test_read_gives_each_line_and_whether_it_shows_red(qt):
    document, _ = report(qt, TEXT)
    assert read(document) == list(zip(TEXT.split("\n"), FLAGS))


def test_read_sees_past_a_stale_wrapper_at_a_lines_layout(qt):
    """PySide handed a QListWidgetItem wrapper for a report line's layout in a
    CI run (a stale one, of a deleted item, at the same address): read() still
    reads that line's colour."""
    from freecad_plugin import uiforms
    QtCore, QtGui, _, _ = qt
    document, _ = report(qt, TEXT)
    sb = uiforms.shiboken()
    address = sb.getCppPointer(document.findBlockByNumber(1).layout())[0]
    gc.collect()  # that layout's own wrapper gone: a wrapper of another class registered there
    stale = sb.wrapInstance(address, QtGui.QListWidgetItem)  # the line's next layout() gives it
    assert read(document) == list(zip(TEXT.split("\n"), FLAGS))
    del stale
