"""Headless FreeCAD tests: run inside freecadcmd (see tests/CMakeLists.txt), which is
Debian's python3 with FreeCAD's modules. The addon is imported from the source
tree, the planner from the build tree."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
BUILD = os.environ.get("PLUNGE_BUILD_DIR", os.path.join(ROOT, "build"))
# The bundle's suite (bundle_suite.py): the addon is the one FreeCAD loaded
# from its profile's Mod folder, where the bundle was unzipped, and it plans
# through the bundle's program; of the source tree only the tests are used.
ADDON = os.environ.get("PLUNGE_ADDON")
# tests/python: the G-code checker (machine_check.py) and geometry checks.
for p in (os.path.join(ROOT, "tests", "python"), HERE) + (() if ADDON else (ROOT, os.path.join(BUILD, "cpp"))):
    if p not in sys.path:
        sys.path.insert(0, p)

import FreeCAD  # noqa: E402
import pytest  # noqa: E402

import parts  # noqa: E402
from freecad_plugin import PlungeRough  # noqa: E402

if ADDON:
    assert os.path.dirname(os.path.dirname(os.path.abspath(PlungeRough.__file__))) == os.path.abspath(ADDON), \
        "the addon under test is %s, not the bundle's" % PlungeRough.__file__


def pytest_configure(config):
    config.addinivalue_line("markers", "bundle: an end-to-end case the bundle's suite runs too (bundle_suite.py)")



@pytest.fixture
def doc():
    d = FreeCAD.newDocument("PlungeTest")
    name = d.Name
    yield d
    if name in FreeCAD.listDocuments():
        FreeCAD.closeDocument(name)


def build_op(doc, shape, sculptured, diameters=(20, 12, 6), canned=False, peck=0.0, radial=0.5, floor=0.3):
    """A job on the shape with one plunger tool controller per diameter and a
    Plunge Rough op on its floor face, recomputed."""
    job = parts.make_job(doc, shape)
    op, tcs = parts.add_plunge_rough(job, parts.floor_face_name(job.Model.Group[0].Shape, sculptured), diameters,
                                     RadialAllowance=radial, FloorAllowance=floor, UseCannedCycle=canned,
                                     PeckDepth=peck)
    return job, op, tcs
