"""Plunges to Path commands: plain data in, a list of Path.Command out.

The first layer of the Plunge Rough operation, as FreeCAD's own generators
(Generators/drill_generator.py): no document objects, so it is testable alone.
"""
import Path


def generate(plunges, clearance_height, safe_height, canned_cycle=False, peck_depth=0.0, return_level="G98"):
    """Commands for one tool's plunges, in order.

    plunges: sequence of (x, y, z) stop points. The tool starts and ends at the
    clearance height; it rapids between plunges at the safe height and plunges
    from there to z (the feed rate is the tool controller's vertical feed, set
    afterwards by PathFeedRate). With canned_cycle, each plunge is a G81 (or G83
    pecking by peck_depth) with the retract plane at the safe height, inside
    G98/G99 ... G80; the rapid to X Y comes first, so that the cycle itself is a
    vertical move.
    """
    if safe_height > clearance_height:
        raise ValueError("the safe height is above the clearance height")
    if peck_depth < 0:
        raise ValueError("the peck depth must not be negative")
    if return_level not in ("G98", "G99"):
        raise ValueError("return level must be G98 or G99")
    cmds = []
    if not plunges:
        return cmds
    for x, y, z in plunges:
        if z >= safe_height:
            raise ValueError("a plunge at (%g, %g) stops at %g, not below the safe height" % (x, y, z))
    cmds.append(Path.Command("G0", {"Z": clearance_height}))
    if canned_cycle:
        x, y, _ = plunges[0]
        cmds.append(Path.Command("G0", {"X": x, "Y": y}))
        cmds.append(Path.Command("G0", {"Z": safe_height}))
        cmds.append(Path.Command(return_level))
        for x, y, z in plunges:
            cmds.append(Path.Command("G0", {"X": x, "Y": y}))
            params = {"X": x, "Y": y, "Z": z, "R": safe_height}
            if peck_depth > 0:
                params["Q"] = peck_depth
                cmds.append(Path.Command("G83", params))
            else:
                cmds.append(Path.Command("G81", params))
        cmds.append(Path.Command("G80"))
    else:
        first = True
        for x, y, z in plunges:
            cmds.append(Path.Command("G0", {"X": x, "Y": y}))
            if first:
                cmds.append(Path.Command("G0", {"Z": safe_height}))
                first = False
            cmds.append(Path.Command("G1", {"Z": z}))
            cmds.append(Path.Command("G0", {"Z": safe_height}))
    cmds.append(Path.Command("G0", {"Z": clearance_height}))
    return cmds
