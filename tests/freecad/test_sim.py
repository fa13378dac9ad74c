"""The job in FreeCAD's voxel simulator: each tool cuts its own plunges with the
tool controller's own tool solid (as the simulator GUI does), and the removed
material is what the plan removes."""
import math

import FreeCAD
import Mesh
import Path
import pytest

import parts
from conftest import build_op
from freecad_plugin import PlungeRough, compat


def expand(cmds):
    """Canned cycles as the simulator GUI expands them (it does so itself, too)."""
    out = []
    for c in cmds:
        if c.Name in ("G81", "G82", "G83"):
            p = c.Parameters
            out += [Path.Command("G0", {"X": p["X"], "Y": p["Y"], "Z": p["R"]}),
                    Path.Command("G1", {"X": p["X"], "Y": p["Y"], "Z": p["Z"]}),
                    Path.Command("G1", {"X": p["X"], "Y": p["Y"], "Z": p["R"]})]
        elif c.Name in ("G0", "G1"):
            out.append(c)
    return out


def simulate(job, resolution, start_z):
    """The job's operations in FreeCAD's voxel simulator, each with its tool
    controller's own tool solid (as the simulator GUI takes it), from start_z
    above the origin: the result meshes."""
    sim = compat.voxel_simulator()
    sim.BeginSimulation(job.Stock.Shape, resolution)
    for o in job.Operations.Group:
        sim.SetToolShape(o.ToolController.Tool.Shape, 0.05)
        pos = FreeCAD.Placement(FreeCAD.Vector(0, 0, start_z), FreeCAD.Rotation())
        for c in expand(o.Path.Commands):
            pos = sim.ApplyCommand(pos, c)
    return [Mesh.Mesh(m) for m in sim.GetResultMesh()]


def height_map(meshes, xs, ys, top):
    """The simulated material's top at every grid point: the highest mesh hit of a
    downward ray (PathSim's outer and inner meshes are not closed solids)."""
    h = {}
    for x in xs:
        for y in ys:
            z = None
            for m in meshes:
                for point in m.nearestFacetOnRay((x, y, top + 10), (0, 0, -1)).values():
                    z = point[2] if z is None else max(z, point[2])
            h[(x, y)] = z
    return h


@pytest.mark.bundle
@pytest.mark.parametrize("canned", [False, True])
def test_each_tool_cuts_its_own_plunges(doc, canned):
    job, op, tcs = build_op(doc, parts.islands_part(), sculptured=False, diameters=(24, 14), canned=canned)
    stock = job.Stock.Shape
    resolution = 0.5
    for o in job.Operations.Group:
        tool = o.ToolController.Tool
        # The solid FreeCAD built for the bit is as wide as the bit says.
        assert abs(tool.Shape.BoundBox.XLength - float(tool.Diameter)) < 1e-6
    meshes = simulate(job, resolution, op.ClearanceHeight.Value)
    # What the plan removes: down to the lowest stop of the disks over each point.
    plan = PlungeRough.plan_of(op)["plunges"]
    box = stock.BoundBox
    xs = [box.XMin + 0.5 + i for i in range(int(box.XLength) - 1)]
    ys = [box.YMin + 0.5 + j for j in range(int(box.YLength) - 1)]
    simulated = height_map(meshes, xs, ys, box.ZMax)
    compared = wrong = 0
    for (x, y), z in simulated.items():
        edges = [abs(math.hypot(x - p["x"], y - p["y"]) - p["diameter"] / 2) for p in plan]
        if min(edges) < 2 * resolution:
            continue  # a voxel's width from a disk's edge: either answer is right
        inside = [p["z"] for p in plan if math.hypot(x - p["x"], y - p["y"]) < p["diameter"] / 2]
        expected = min(inside) if inside else box.ZMax
        compared += 1
        wrong += z is None or abs(z - expected) > resolution
    assert compared > 5000
    assert wrong <= 0.005 * compared, (wrong, compared)
