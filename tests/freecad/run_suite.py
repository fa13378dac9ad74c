"""pytest inside freecadcmd (Debian's python3 with FreeCAD's modules): the
suite named by PLUNGE_SUITE, "freecad" (headless; "freecad_allowance" its
allowance cases, run beside it), "freecad_gui" (FreeCAD
under xvfb, started by the tests) or "freecad_bundle" (bundle_suite.py). A script file, not `freecadcmd -c`: FreeCAD
1.1 ends with "Application unexpectedly terminated" on a -c argument of 256
characters or more."""
import os
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
SUITES = {
    "freecad": [HERE, "--ignore=" + os.path.join(HERE, "test_gui.py"), "--ignore=" + os.path.join(HERE, "test_allowance.py")],
    # Its longest part, on its own: ctest runs it beside the rest.
    "freecad_allowance": [os.path.join(HERE, "test_allowance.py")],
    "freecad_gui": [os.path.join(HERE, "test_gui.py")],
    # The end-to-end cases, on a bundle unzipped into the profile (bundle_suite.py).
    "freecad_bundle": [HERE, "--ignore=" + os.path.join(HERE, "test_gui.py"), "-m", "bundle"],
}
suite = os.environ.get("PLUNGE_SUITE", "freecad")
code = int(pytest.main(["-q", "-p", "no:cacheprovider", "--durations=15"] + SUITES[suite]))
# FreeCAD 1.1 drops what is still buffered when the script exits: the failures' report.
sys.stdout.flush()
sys.stderr.flush()
sys.exit(code)
