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


def test_the_way_around_runs_at_the_retract_height():
    """A plunge's via points: after its retract, rapids through them at that
    height, then on to the next plunge; the last plunge's are not posted."""
    plunges = [{"x": 1, "y": 2, "z": -50, "approach_z": -39, "retract_z": -39, "via": [[2, 2.5], [7, 2.5]]},
               {"x": 8, "y": 2, "z": -50, "approach_z": -39, "retract_z": 5, "via": [[9, 9]]}]
    cmds = generator.generate(plunges, clearance_height=10, safe_height=5)
    across = [(c.Parameters.get("X"), c.Parameters.get("Y"), z) for c, _, z in heights(cmds)
              if c.Name == "G0" and ("X" in c.Parameters or "Y" in c.Parameters)]
    assert across == [(1, 2, 10), (2, 2.5, -39), (7, 2.5, -39), (8, 2, -39)]


def test_pecked_holes_clear_their_chips():
    """A pecked plunge: down to each peck, up out of the hole (its approach
    height), back to the clearance above the peck, on to z; a dwell at the
    bottom of pecked holes only."""
    plunges = [{"x": 1, "y": 2, "z": -50, "approach_z": 1, "retract_z": 2, "pecks": [-20, -40]},
               {"x": 3, "y": 4, "z": -50, "approach_z": 1, "retract_z": 2}]
    cmds = generator.generate(plunges, clearance_height=10, safe_height=5, rapid_clearance=1.0, dwell=0.5)
    moves = [(c.Name, z) for c, _, z in heights(cmds)]
    first = moves.index(("G1", -20))
    assert moves[first:first + 8] == [("G1", -20), ("G0", 1), ("G0", -19), ("G1", -40), ("G0", 1), ("G0", -39),
                                      ("G1", -50), ("G4", -50)]
    assert [c.Parameters["P"] for c in cmds if c.Name == "G4"] == [0.5]  # the second plunge is one stroke
    # In a canned cycle the pecked plunge is a G83 by the tool's peck depth, the other a G81.
    cycles = [c for c in generator.generate(plunges, 10, 5, canned_cycle=True, peck_depth=20) if c.Name in ("G81", "G83")]
    assert [c.Name for c in cycles] == ["G83", "G81"] and cycles[0].Parameters["Q"] == 20
    with pytest.raises(ValueError, match="dwell"):
        generator.generate(plunges, 10, 5, dwell=-1)


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
