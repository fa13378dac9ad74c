"""Reading G-code and Path commands back: plunges per tool, rapids and their heights."""
# The G-code checker's reader (tests/python/machine_check.py): blocks of posted
# G-code as (codes, words) with comments removed.
from machine_check import parse as parse_gcode  # noqa: E402,F401


def replay(blocks, safe_z):
    """Plunges [(tool, x, y, z)] and rapids that crossed below safe_z, from G-code blocks.

    Understands G0/G1 (modal), G81/G83 with G98 (return to the initial level) and T/M6.
    A feed down at the X Y of the last plunge with no move sideways since (a
    pecked hole after clearing its chips) goes on with that plunge: its z is
    the deepest."""
    in_hole = False
    tool = None
    pending = None
    x = y = z = None
    motion = None
    plunges, low_rapids = [], []
    canned = None
    for codes, w in blocks:
        if "M6" in codes:
            in_hole = False
        if "M6" in codes and "T" in w:
            tool = int(w["T"])
        elif "T" in w and not codes:
            pending = int(w["T"])
        if "M6" in codes and "T" not in w and pending is not None:
            tool = pending
        for c in codes:
            if c in ("G0", "G1", "G81", "G82", "G83"):
                motion = c
            if c == "G80":
                motion = canned = None
        if not any(k in w for k in "XYZ"):
            continue
        nx, ny, nz = w.get("X", x), w.get("Y", y), w.get("Z", z)
        if (nx, ny) != (x, y):
            in_hole = False
        if motion == "G0":
            if (nx, ny) != (x, y) and z is not None and z < safe_z - 1e-6:
                low_rapids.append((x, y, z, nx, ny))
            x, y, z = nx, ny, nz
        elif motion == "G1":
            if nz is not None and z is not None and nz < z and (nx, ny) == (x, y):
                if in_hole and plunges and plunges[-1][1:3] == (nx, ny) and nz < plunges[-1][3]:
                    plunges[-1] = (tool, nx, ny, nz)
                else:
                    plunges.append((tool, nx, ny, nz))
                in_hole = True
            x, y, z = nx, ny, nz
        elif motion in ("G81", "G82", "G83"):
            if canned is None:
                canned = z  # G98: back to the level where the cycle began
            plunges.append((tool, nx, ny, nz))
            x, y = nx, ny
            z = canned
    return plunges, low_rapids


def path_blocks(op):
    """An operation's Path commands as blocks."""
    return [([c.Name], {k.upper(): v for k, v in c.Parameters.items()}) for c in op.Path.Commands
            if not c.Name.startswith("(")]


def job_program(job):
    """A Job's operations as one G-code text: a tool change at each operation's
    tool controller, then its Path commands (what the post writes, unformatted)."""
    lines = []
    for op in job.Operations.Group:
        if not getattr(op, "Active", True) or not hasattr(op, "Path"):
            continue
        lines.append("T%d M6" % int(op.ToolController.ToolNumber))
        for c in op.Path.Commands:
            if c.Name.startswith("("):
                continue
            words = " ".join("%s%.4f" % (k.upper(), v) for k, v in c.Parameters.items() if k.upper() in "XYZRQ")
            lines.append("%s %s" % (c.Name, words))
    return "\n".join(lines) + "\n"
