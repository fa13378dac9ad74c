"""The bundle's suite checks what it runs on (bundle_suite.py): the addon that
FreeCAD loaded from the profile's Mod folder, its program found in its bin/
(the universal zip's: bin/<os>-<arch>/ of this machine; its execute bit given
back), no compiled module, and floors of faces sent as
meshes. Runs only there."""
import os
import stat

import pytest

from conftest import ADDON
from freecad_plugin import planner

pytestmark = [pytest.mark.bundle, pytest.mark.skipif(not ADDON, reason="the bundle's suite only")]


def test_the_addon_is_the_bundles_and_plans_through_its_program():
    import freecad_plugin
    assert os.path.dirname(os.path.dirname(os.path.abspath(freecad_plugin.__file__))) == os.path.abspath(ADDON)
    with pytest.raises(ImportError):
        import plunge  # noqa: F401
    found = planner.planner()
    if os.environ.get(planner.ENVIRONMENT):  # the Windows bundle under wine (bundle_suite.py)
        assert found.where == planner.ENVIRONMENT and found.argv[0] == "wine"
        assert found.argv[-1] == os.path.join(ADDON, "bin", "plunge-rough.exe")
        assert found.about()["system"] == "windows"
    else:
        # A platform's zip: bin/; the universal zip: this machine's bin/<os>-<arch>/.
        universal = os.path.join(ADDON, "bin", planner.platform_tag(), planner.PROGRAM)
        program = universal if os.path.isfile(universal) else os.path.join(ADDON, "bin", planner.PROGRAM)
        assert found.argv == [program] and found.where == "the addon's bin"
        assert found.about()["platform"] == planner.platform_tag()
        # Unzipped without its execute bit, given back when the addon started.
        assert os.stat(program).st_mode & stat.S_IXUSR
    # Built without OpenCASCADE: the faces of a floor go to it as a mesh.
    assert "mesh" in found.floors and "brep" not in found.floors
