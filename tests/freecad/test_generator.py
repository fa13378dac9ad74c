"""The pure generator: plunges in, Path commands out."""
import pytest

from freecad_plugin import generator


def heights(cmds, current=None):
    """(command, z before, z after) for every command."""
    out = []
    z = current
    for c in cmds:
        before = z
        if "Z" in c.Parameters and c.Name in ("G0", "G1"):
            z = c.Parameters["Z"]
        out.append((c, before, z))
    return out


def test_explicit_moves():
    cmds = generator.generate([(1, 2, -5), (3, 4, -6)], clearance_height=10, safe_height=5)
    names = [c.Name for c in cmds]
    assert names == ["G0", "G0", "G0", "G1", "G0", "G0", "G1", "G0", "G0"]
    assert cmds[0].Parameters == {"Z": 10.0}
    assert cmds[-1].Parameters == {"Z": 10.0}
    feeds = [c for c in cmds if c.Name == "G1"]
    assert [(c.Parameters["Z"]) for c in feeds] == [-5, -6]
    for c, before, _ in heights(cmds):
        if c.Name == "G0" and ("X" in c.Parameters or "Y" in c.Parameters):
            assert before >= 5  # rapids across only at or above the safe height


def test_plan_moves_with_lead_outs():
    """The plan's own heights and lead-outs: a raised lead-out feeds up first, then out."""
    plunges = [{"x": 1, "y": 2, "z": -5, "approach_z": 1, "retract_z": 2, "lead_out": [1.5, 2]},
               {"x": 3, "y": 4, "z": -6, "approach_z": 1, "retract_z": 2, "lead_out": [3, 4.5], "lead_out_z": -5.6}]
    cmds = generator.generate(plunges, clearance_height=10, safe_height=5)
    feeds = [(c.Parameters.get("X"), c.Parameters.get("Y"), z) for c, _, z in heights(cmds) if c.Name == "G1"]
    assert feeds == [(None, None, -5), (1.5, 2, -5), (None, None, -6), (None, None, -5.6), (3, 4.5, -5.6)]


@pytest.mark.parametrize("peck,cycle", [(0.0, "G81"), (2.0, "G83")])
def test_canned_cycles(peck, cycle):
    cmds = generator.generate([(1, 2, -5), (3, 4, -6)], 10, 5, canned_cycle=True, peck_depth=peck)
    names = [c.Name for c in cmds]
    assert names[:4] == ["G0", "G0", "G0", "G98"] and names[-2:] == ["G80", "G0"]
    cycles = [c for c in cmds if c.Name == cycle]
    assert len(cycles) == 2
    for c, (x, y, z) in zip(cycles, [(1, 2, -5), (3, 4, -6)]):
        assert (c.Parameters["X"], c.Parameters["Y"], c.Parameters["Z"], c.Parameters["R"]) == (x, y, z, 5)
        if peck:
            assert c.Parameters["Q"] == peck
    # Each cycle follows a rapid to its own X Y, so the cycle is a vertical move.
    for i, c in enumerate(cmds):
        if c.Name == cycle:
            assert cmds[i - 1].Name == "G0" and cmds[i - 1].Parameters["X"] == c.Parameters["X"]


def test_nothing_and_bad_input():
    assert generator.generate([], 10, 5) == []
    with pytest.raises(ValueError, match="safe height is above"):
        generator.generate([(0, 0, -1)], 5, 10)
    with pytest.raises(ValueError, match="not below the safe height"):
        generator.generate([(0, 0, 7)], 10, 5)
    with pytest.raises(ValueError, match="peck"):
        generator.generate([(0, 0, -1)], 10, 5, True, -1.0)
