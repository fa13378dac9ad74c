"""The planner's input (docs/plan-format.md) from the operation's settings.

Document-free, like generator.py: plain numbers, strings and dicts in, the
plan input dict out. operation_input.settings_of reads the operation's properties
into `Settings`; the pocket's outline, floor and sections come from
geometry.py, the tools from tools.py, the material from rest.py. `check`
refuses what the planner cannot be given, before any of that is computed.
"""
from dataclasses import MISSING, dataclass, fields

# GrowthPattern property values -> the planner's "growth_pattern".
GROWTH_PATTERNS = {"Auto": "auto", "Rows": "rows", "Offsets": "offsets"}

# Strategy property values -> the planner's "strategy" and "grid" input.
STRATEGIES = {
    "Packing": {},
    "Grid (honeycomb)": {"strategy": "grid", "grid": {"pattern": "honeycomb"}},
    "Grid (square)": {"strategy": "grid", "grid": {"pattern": "square"}},
}


@dataclass
class Settings:
    """The operation's properties, in mm, mm/min, seconds and %: each default is
    the operation's own (PlungeRough._addProperties) or, for files from before
    a property, what those files planned with."""
    start_depth: float
    final_depth: float
    safe_height: float
    clearance_height: float
    radial_allowance: float = 0.0
    floor_allowance: float = 0.0
    chord_tolerance: float = 0.01
    include_fillets: bool = True
    min_coverage: float = 99.6  # %
    max_wall_stock: float = 1.0
    max_floor_stock: float = 1.0
    lead_out: float = 0.5
    stock_aware_heights: bool = True
    canned_cycle: bool = False
    peck: bool = True
    peck_depth: float = 0.0  # 0: each tool's own (three diameters)
    dwell: float = 0.0  # s
    strategy: str = "Packing"
    growth_pattern: str = "Auto"
    auto_select: bool = True
    tool_change_time: float = 20.0  # s
    holder_clearance: float = 1.0

    def wall_margin(self):
        """How far past an open side the plunges may reach: as far as the wall
        band guarantee needs to cut up to the edge, and a little more."""
        return self.radial_allowance + self.max_wall_stock + 0.5


# Each property's default, in one place: the operation's properties take theirs from here.
DEFAULTS = {f.name: f.default for f in fields(Settings) if f.default is not MISSING}


def check(settings, tool_lengths):
    """ValueError for heights and bits the planner cannot be given.
    tool_lengths: (label, length in mm or 0 when not known) per plunger."""
    depth = settings.start_depth - settings.final_depth
    for label, length in tool_lengths:
        if length and length < depth:
            raise ValueError("%s is %g mm long, shorter than the pocket is deep (%g mm): use a longer tool"
                             % (label, length, depth))
    if settings.safe_height > settings.clearance_height:
        raise ValueError("the safe height is above the clearance height")
    if settings.start_depth <= settings.final_depth:
        raise ValueError("the start depth must be above the final depth")


def plan_input(settings, tools, time_model, boundary, islands, floor, sections=(), deviation=0.0, material=None,
               part=None):
    """The plan input. tools: the plungers' specs, largest first (tools.spec);
    time_model: the first plunger's rapid rates (tools.time_model); boundary,
    islands, floor, sections: the pocket (geometry.py), whose chords lie up to
    `deviation` mm off its walls; material: what the operations before left
    (rest.material), or None for solid stock from the start depth; part: the
    part's faces around the pocket as a mesh (geometry.part_mesh), or None."""
    data = {
        "version": 1,
        "boundary": boundary,
        "islands": islands,
        "tools": [dict(t) for t in tools],
        "holder_clearance": settings.holder_clearance,
        "time_model": time_model,
        "top_z": settings.start_depth,
        "safe_z": settings.safe_height,
        "floor": floor,
        # The final depth is the deepest any plunge goes.
        "final_depth": settings.final_depth,
        # The chords of a discretised free-form wall may lie off it by the
        # measured deviation: keeping that much more from the walls never gouges.
        "allowance": {"radial": settings.radial_allowance + deviation + 1e-6, "floor": settings.floor_allowance},
        "min_coverage": settings.min_coverage / 100.0,
        "max_wall_stock": settings.max_wall_stock,
        "max_floor_stock": settings.max_floor_stock,
        # Lead-outs and stock-aware heights are explicit moves: a canned cycle has neither.
        "lead_out": 0.0 if settings.canned_cycle else settings.lead_out,
        "stock_aware_heights": bool(settings.stock_aware_heights and not settings.canned_cycle),
        "peck": bool(settings.peck),
        "growth_pattern": GROWTH_PATTERNS.get(settings.growth_pattern, "auto"),
    }
    if sections:
        data["sections"] = list(sections)
    if material is not None:
        data["material"] = material
    if part is not None:
        data["part"] = {"mesh": part}
    if settings.dwell > 0 and not settings.canned_cycle:
        data["peck_dwell"] = settings.dwell
    if settings.peck_depth > 0:
        for tool in data["tools"]:
            tool["peck_depth"] = settings.peck_depth
    data.update(STRATEGIES.get(settings.strategy, {}))
    if settings.auto_select:
        data["tool_library"] = data.pop("tools")
        data["tools"] = "auto"
    return data
