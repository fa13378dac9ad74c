"""Plunges to Path commands: plain data in, a list of Path.Command out.

The first layer of the Plunge Rough operation, as FreeCAD's own generators
(Generators/drill_generator.py): no document objects, so it is testable alone.
"""
import Path


def generate(plunges, clearance_height, safe_height, canned_cycle=False, peck_depth=0.0, return_level="G98",
             rapid_clearance=1.0, dwell=0.0):
    """Commands for one tool's plunges, in order.

    plunges: sequence of (x, y, z) stop points, or of the plan's plunge dicts
    (x, y, z, and approach_z, retract_z, lead_out, lead_out_z, pecks from the
    planner's stock simulation). The tool starts and ends at the clearance height. With explicit
    moves it rapids to each plunge at the previous retract height, rapids down
    to the approach height (the safe height for tuples), feeds to z (a pecked
    hole: to each peck, rapid up to the approach height to clear the chips,
    rapid back to rapid_clearance above the peck; then dwell seconds at the
    bottom), feeds up to lead_out_z if given, feeds along the lead-out,
    rapids up to the retract height and through `via` at that height (the
    way around standing material to the next plunge; the feed rates are the tool controller's,
    set afterwards by PathFeedRate). With canned_cycle, each plunge is a G81,
    or a G83 pecking by peck_depth (a plunge dict: where the plan pecks it; a
    tuple: every one when peck_depth > 0), with the retract plane at the safe
    height, inside G98/G99 ... G80; the rapid to X Y comes first, so that the
    cycle itself is a vertical move.
    """
    if safe_height > clearance_height:
        raise ValueError("the safe height is above the clearance height")
    if peck_depth < 0:
        raise ValueError("the peck depth must not be negative")
    if dwell < 0:
        raise ValueError("the dwell must not be negative")
    if return_level not in ("G98", "G99"):
        raise ValueError("return level must be G98 or G99")
    cmds = []
    if not plunges:
        return cmds
    moves = [_move(p, safe_height, peck_depth) for p in plunges]
    plunges = [(m["x"], m["y"], m["z"]) for m in moves]
    for x, y, z in plunges:
        if z >= safe_height:
            raise ValueError("a plunge at (%g, %g) stops at %g, not below the safe height" % (x, y, z))
    cmds.append(Path.Command("G0", {"Z": clearance_height}))
    if canned_cycle:
        x, y, _ = plunges[0]
        cmds.append(Path.Command("G0", {"X": x, "Y": y}))
        cmds.append(Path.Command("G0", {"Z": safe_height}))
        cmds.append(Path.Command(return_level))
        for m in moves:
            x, y, z = m["x"], m["y"], m["z"]
            cmds.append(Path.Command("G0", {"X": x, "Y": y}))
            params = {"X": x, "Y": y, "Z": z, "R": safe_height}
            if m["pecked"] and peck_depth > 0:
                params["Q"] = peck_depth
                cmds.append(Path.Command("G83", params))
            else:
                cmds.append(Path.Command("G81", params))
        cmds.append(Path.Command("G80"))
    else:
        cmds.append(Path.Command("G0", {"X": moves[0]["x"], "Y": moves[0]["y"]}))
        cmds.append(Path.Command("G0", {"Z": safe_height}))
        at = safe_height
        for i, m in enumerate(moves):
            if i:
                cmds.append(Path.Command("G0", {"X": m["x"], "Y": m["y"]}))
            if m["approach_z"] < at:
                cmds.append(Path.Command("G0", {"Z": m["approach_z"]}))
            for peck in m["pecks"]:  # out of the hole to clear the chips, back to just above
                cmds.append(Path.Command("G1", {"Z": peck}))
                cmds.append(Path.Command("G0", {"Z": m["approach_z"]}))
                cmds.append(Path.Command("G0", {"Z": min(m["approach_z"], peck + rapid_clearance)}))
            cmds.append(Path.Command("G1", {"Z": m["z"]}))
            if m["pecks"] and dwell > 0:
                cmds.append(Path.Command("G4", {"P": dwell}))
            if m["lead_out_z"] is not None:
                cmds.append(Path.Command("G1", {"Z": m["lead_out_z"]}))
            if m["lead_out"] is not None:
                cmds.append(Path.Command("G1", {"X": m["lead_out"][0], "Y": m["lead_out"][1]}))
            # The last plunge of the operation leaves at the safe height.
            at = safe_height if i == len(moves) - 1 else max(m["retract_z"], m["z"])
            cmds.append(Path.Command("G0", {"Z": at}))
            if i < len(moves) - 1:  # the way around standing material, at that height
                cmds.extend(Path.Command("G0", {"X": v[0], "Y": v[1]}) for v in m["via"])
    cmds.append(Path.Command("G0", {"Z": clearance_height}))
    return cmds


def _move(p, safe_height, peck_depth):
    """A plunge as a dict with its heights, pecks and lead-out (a tuple: at the
    safe height, pecked in the canned cycle when peck_depth > 0)."""
    if isinstance(p, dict):
        lead = p.get("lead_out")
        return {"x": p["x"], "y": p["y"], "z": p["z"],
                "approach_z": min(p.get("approach_z", safe_height), safe_height),
                "retract_z": min(p.get("retract_z", safe_height), safe_height),
                "lead_out": tuple(lead) if lead is not None else None,
                "lead_out_z": p.get("lead_out_z") if lead is not None else None,
                "pecks": list(p.get("pecks", [])), "pecked": bool(p.get("pecks")),
                "via": [tuple(v) for v in p.get("via", [])]}
    x, y, z = p
    return {"x": x, "y": y, "z": z, "approach_z": safe_height, "retract_z": safe_height, "lead_out": None,
            "lead_out_z": None, "pecks": [], "pecked": peck_depth > 0, "via": []}
