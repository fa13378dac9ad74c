"""Shared by bench_mesh.py and bench_tray.py: a Plunge Rough operation
recomputed as users get it, through the README's install (the module, the
floor as BREP faces) and through the Linux bundle's program (the floor as a
mesh), unzipped from dist/ as a user unzips it."""
import os
import time
import zipfile

from freecad_plugin import PlungeRough, planner

PLANNERS = (("module, BREP floor", False), ("bundle's program, mesh floor", True))


def program_timed(program, data, repeat, folder):
    """The program's own plan of the same input, run standalone (`plunge-rough
    plan`) `repeat` times: its seconds each, start to exit."""
    import json
    import subprocess
    path = os.path.join(folder, "bench-input.json")
    with open(path, "w") as f:
        json.dump(data, f)
    seconds = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run([program, "plan", path, "-o", os.path.join(folder, "bench-plan.json")], check=True,
                       capture_output=True)
        seconds.append(time.perf_counter() - start)
    return seconds


def bundle_program(root):
    """The Linux bundle's program, unzipped into build/bench-bundle."""
    unzipped = os.path.join(root, "build", "bench-bundle")
    with zipfile.ZipFile(os.path.join(root, "dist", "PlungeRough-linux-x86_64.zip")) as z:
        z.extractall(unzipped)
    program = os.path.join(unzipped, "PlungeRough", "bin", "plunge-rough")
    os.chmod(program, 0o755)  # zipfile drops it, as the Addon Manager's unzip does
    return program


def recompute_timed(doc, op, program, repeat):
    """Plans through `program` (None: the module) `repeat` times: the whole
    recomputes' seconds, the planner's own, and the last plan."""
    if program:
        os.environ[planner.ENVIRONMENT] = program
    else:
        os.environ.pop(planner.ENVIRONMENT, None)
    whole, planning = [], []
    for _ in range(repeat):
        op.touch()
        start = time.perf_counter()
        doc.recompute()
        whole.append(time.perf_counter() - start)
        plan = PlungeRough.plan_of(op)
        assert plan is not None, op.Summary
        planning.append(plan["stats"]["planning_seconds"])
    return whole, planning, plan
