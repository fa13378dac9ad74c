"""Everything the addon asks of a tool controller and its tool bit, in one
place: its number (the planner's tool id, in every layer and in the G-code),
diameter, plunge feed, whether it can plunge, the planner's tool for it (shape,
flutes, core, engagement limits from the bit) and the time model's rates.

App side: never imports GUI code.
"""
from freecad_plugin import compat

# Tool bit shapes that can plunge: an end mill's and the plunge mill (plunge_mill.py).
PLUNGER_SHAPES = ("endmill", "ballend", "bullnose", "plungemill")


def number(tc):
    """The tool controller's tool number: the planner's tool id."""
    return int(tc.ToolNumber)


def diameter(tc):
    """The bit's diameter in mm."""
    d = tc.Tool.Diameter
    return float(d.Value if hasattr(d, "Value") else d)


def plunge_feed(tc):
    """The vertical feed in mm/min (0 when the tool controller has none)."""
    return tc.VertFeed.getValueAs("mm/min").Value if hasattr(tc, "VertFeed") else 0.0


def largest_first(tcs):
    return sorted(tcs, key=lambda tc: -diameter(tc))


def by_number(tcs):
    """{tool number: tool controller}."""
    return {number(tc): tc for tc in tcs}


def label(tc):
    """How the page lists a plunger: "T2  20 mm plunger  (20.00 mm)"."""
    return "T%d  %s  (%s)" % (number(tc), tc.Label, tc.Tool.Diameter.UserString)


def is_plunger(tc):
    """A tool controller that can plunge: a flat, ball or bull-nose bit (an end
    mill's shape) or a plunge mill (plunge_mill.py), not a drill, chamfer,
    V-bit, probe, saw or thread mill; and a vertical feed to plunge with. The Job's default tool controller has none."""
    bit = getattr(tc, "Tool", None)
    if bit is None or not hasattr(bit, "Diameter"):
        return False
    shape = compat.bit_shape(bit) or "endmill"
    return shape in PLUNGER_SHAPES and plunge_feed(tc) > 0


def job_plungers(job):
    """The plunger tool controllers of a Job, largest first."""
    tcs = [tc for tc in (job.Tools.Group if job is not None else []) if is_plunger(tc)]
    return largest_first(tcs)


def bit_length(bit, name):
    """A length property of a tool bit in mm (None when the bit has none)."""
    value = getattr(bit, name, None)
    if value is None or isinstance(value, bool):
        return None
    return float(value.Value if hasattr(value, "Value") else value)


class Mount:
    """How the operation says its plungers are held, for bits that do not say:
    stick-out and holder diameter in mm (0: not known)."""

    def __init__(self, stick_out=0.0, holder_diameter=0.0):
        self.stick_out = stick_out
        self.holder_diameter = holder_diameter


def held(tc, tool, bit, mount):
    """The tool as mounted: the bit's own StickOut and HolderDiameter, else
    the operation's (Mount); its ShankDiameter where wider than the cutter (it
    starts at the flutes' top, so only with CuttingEdgeHeight)."""
    stick_out = bit_length(bit, "StickOut") or (mount.stick_out if mount else 0.0)
    if not stick_out or stick_out <= 0:
        return
    flute = tool.get("flute_length")
    if flute and stick_out < flute:
        raise ValueError("%s: its stick-out (%.2f mm) is shorter than its cutting edge height (%.2f mm): the holder "
                         "would sit on the flutes" % (tc.Label, stick_out, flute))
    tool["stick_out"] = stick_out
    holder = bit_length(bit, "HolderDiameter") or (mount.holder_diameter if mount else 0.0)
    if holder and holder > 0:
        tool["holder_diameter"] = holder
    shank = bit_length(bit, "ShankDiameter")
    if shank and shank > tool["diameter"] and flute:
        tool["shank_diameter"] = shank


def spec(tc, max_engagement=100.0, min_engagement=0.0, mount=None):
    """A tool controller as a planner tool: diameter, number, shape, and what the
    bit says of it as a plunge mill: CuttingEdgeHeight (the flute length), and
    when present its own CoreDiameter (it does not cut at its centre; or
    CenterCutting false), MaxEngagement and MinEngagement properties. Without
    those, the operation's limits in % of the diameter (100 and 0: none).
    What holds it: held()."""
    bit = tc.Tool
    diameter = float(bit.Diameter.Value if hasattr(bit.Diameter, "Value") else bit.Diameter)
    tool = {"diameter": diameter, "id": number(tc)}
    feed = plunge_feed(tc)
    if feed > 0:
        tool["feed"] = feed  # plunge feed, for the planner's time estimate
    shape = compat.bit_shape(bit)
    if "ball" in shape:
        tool["shape"] = "ball"
    elif "bull" in shape:
        corner = None
        # FreeCAD 1.1's bull nose has CornerRadius (its shape's own; a FlatRadius
        # left from an older bit file is not drawn), before it FlatRadius.
        if hasattr(bit, "CornerRadius"):
            corner = float(bit.CornerRadius.Value)
        elif hasattr(bit, "FlatRadius"):
            corner = diameter / 2 - float(bit.FlatRadius.Value)
        if corner and 0 < corner <= diameter / 2:
            tool["shape"] = "bull"
            tool["corner_radius"] = corner
    flute = bit_length(bit, "CuttingEdgeHeight")
    if flute and flute > 0:
        tool["flute_length"] = flute
    core = bit_length(bit, "CoreDiameter")
    if getattr(bit, "CenterCutting", True) is False or (core and core > 0):
        if not core or core <= 0:
            raise ValueError("%s does not cut at its centre: give its bit a CoreDiameter" % tc.Label)
        tool["center_cutting"] = False
        tool["core_diameter"] = core
    if not 0 < max_engagement <= 100 or not 0 <= min_engagement < 100:
        raise ValueError("the engagement limits are percentages: max above 0 and up to 100, min from 0 below 100")
    limit = bit_length(bit, "MaxEngagement")
    if limit is None and max_engagement < 100:
        limit = diameter * max_engagement / 100.0
    if limit:
        tool["max_engagement"] = limit
    least = bit_length(bit, "MinEngagement")
    if least is None and min_engagement > 0:
        least = diameter * min_engagement / 100.0
    if least:
        tool["min_engagement"] = least
    held(tc, tool, bit, mount)
    return tool


def time_model(tc, tool_change_seconds=20.0):
    """The planner's time model from a tool controller's rapid rates (defaults
    when unset) and the operation's tool change time."""
    model = {"tool_change_seconds": max(0.0, float(tool_change_seconds))}
    for key, prop in (("rapid_rate", "HorizRapid"), ("retract_rate", "VertRapid")):
        value = getattr(tc, prop).getValueAs("mm/min").Value if hasattr(tc, prop) else 0.0
        if value > 0:
            model[key] = value
    return model


