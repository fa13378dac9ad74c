import os
import sys

import pytest


def pytest_addoption(parser):
    parser.addoption("--build-dir", default=os.environ.get("PLUNGE_BUILD_DIR", "build"),
                     help="CMake build directory holding cpp/plunge-rough and the plunge module")


@pytest.fixture(scope="session")
def build_dir(request):
    return os.path.abspath(request.config.getoption("--build-dir"))


@pytest.fixture(scope="session")
def cli(build_dir):
    path = os.path.join(build_dir, "cpp", "plunge-rough")
    assert os.path.exists(path), "build the project first: " + path
    return path


@pytest.fixture(scope="session")
def plunge(build_dir):
    sys.path.insert(0, os.path.join(build_dir, "cpp"))
    import plunge as module
    return module


SHAPES = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "data", "shapes")


def load_shape(name):
    """A test shape's planner input (tests/data/shapes/NAME.json)."""
    import json
    with open(os.path.join(SHAPES, name + ".json")) as f:
        return json.load(f)


def limited(data, fraction):
    """A copy of a planner input with every tool's max_engagement = fraction x its diameter."""
    import json
    data = json.loads(json.dumps(data))
    for t in data["tools"]:
        t["max_engagement"] = fraction * t["diameter"]
    return data
