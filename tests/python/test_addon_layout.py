"""The addon's modules as docs/architecture.md lists them, in FreeCAD CAM's
layers: App modules never import GUI ones, no two modules import each other
(directly or round a longer circle, lazy imports included), the constants are
a leaf, and the document-free modules import no FreeCAD. Read from the source
(ast), as test_layers reads the C++ includes."""
import ast
import os
import re

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PLUGIN = os.path.join(ROOT, "freecad_plugin")
GUI = {"command", "compat_gui", "PlungeRoughGui", "rest_gui", "uiforms"}
MODULES = sorted(f[:-3] for f in os.listdir(PLUGIN) if f.endswith(".py") and f != "__init__.py")


def imports(module):
    """(addon modules, other top-level modules) the module imports anywhere in it."""
    tree = ast.parse(open(os.path.join(PLUGIN, module + ".py")).read())
    ours, others = set(), set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module:
            if node.module == "freecad_plugin":
                ours |= {a.name for a in node.names}
            elif node.module.startswith("freecad_plugin."):
                ours.add(node.module.split(".")[1])
            else:
                others.add(node.module.split(".")[0])
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("freecad_plugin."):
                    ours.add(a.name.split(".")[1])
                else:
                    others.add(a.name.split(".")[0])
    return ours, others


GRAPH = {m: imports(m)[0] for m in MODULES}


def test_the_architecture_page_lists_every_module():
    page = open(os.path.join(ROOT, "docs", "architecture.md")).read()
    table = page.split("<!-- addon -->", 1)[1].split("<!-- /addon -->", 1)[0]
    listed = re.findall(r"^\| `([A-Za-z_]+)\.py` \|", table, re.M)
    assert sorted(listed) == MODULES
    for m in listed:  # the GUI modules are marked so
        row = re.search(r"^\| `%s\.py` \|(.*)$" % m, table, re.M).group(1)
        assert ("(GUI)" in row) == (m in GUI), m


def test_app_modules_never_import_gui_ones():
    for m in MODULES:
        if m not in GUI:
            assert not GRAPH[m] & GUI, (m, GRAPH[m] & GUI)
            assert "FreeCADGui" not in imports(m)[1], m


def test_no_import_circle():
    def walk(m, path):
        for n in sorted(GRAPH.get(m, ())):
            assert n not in path, " -> ".join(path + [n])
            walk(n, path + [n])
    for m in MODULES:
        walk(m, [m])


def test_the_constants_are_a_leaf_and_the_pure_modules_import_no_document():
    assert not GRAPH["constants"] and imports("constants")[1] <= {"os", "PySide"}
    assert not GRAPH["plan_input"] and imports("plan_input")[1] <= {"dataclasses"}
    assert not GRAPH["generator"] and imports("generator")[1] <= {"Path", "math"}


def test_the_operation_module_is_the_proxy():
    lines = open(os.path.join(PLUGIN, "PlungeRough.py")).read().count("\n")
    assert lines <= 400, lines


def test_one_version_everywhere():
    """package.xml's version is the planner's (CMake's project version) and
    CHANGELOG.md's newest entry; package.xml sets no maximum FreeCAD (the
    Addon Manager hides an addon whose freecadmax is below the running one:
    FreeCAD's next release is 26.3)."""
    package = open(os.path.join(ROOT, "package.xml")).read()
    version = re.search(r"<version>([^<]+)</version>", package).group(1)
    cmake = re.search(r"project\(PlungeRough VERSION (\S+)", open(os.path.join(ROOT, "CMakeLists.txt")).read())
    assert cmake and cmake.group(1) == version
    newest = re.search(r"^## (\S+)", open(os.path.join(ROOT, "CHANGELOG.md")).read(), re.MULTILINE)
    assert newest and newest.group(1) == version
    assert "freecadmax" not in package.lower()
