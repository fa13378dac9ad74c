"""The plan input of a Plunge Rough operation in its document: the selected
floor faces and their checks, the properties as plan_input.Settings, the
pocket's geometry (geometry.py), the material before it (rest.py) and the
plungers (tools.py), put together by the document-free plan_input.py.

App side: never imports GUI code.
"""
import FreeCAD
import Part

from freecad_plugin import companions, geometry, plan_input, rest, tools
from freecad_plugin.compat import PathUtils

translate = FreeCAD.Qt.translate


def _mm(obj, name, default):
    """A length property in mm, or default for files from before it."""
    value = getattr(obj, name, None)
    return float(value.Value) if value is not None else default


def mount_of(obj):
    """The operation's stick-out and holder diameter in mm (files from before
    them: not known, 0), for the bits that do not carry their own."""
    return tools.Mount(_mm(obj, "StickOut", 0.0), _mm(obj, "HolderDiameter", 0.0))


def selected_faces(obj, tcs):
    """The selected floor faces as (name, face); ValueError naming what stops the
    operation from planning: its tool controllers, an edge selected, a deleted companion."""
    # With the automatic choice the operation itself takes the largest plunger
    # the plan uses (activate_companions); otherwise its tool controller is the largest.
    if tcs and obj.ToolController != tcs[0] and not (obj.AutoSelectTools and obj.ToolController in tcs):
        raise ValueError(translate("PlungeRough", "the operation's tool controller must be its largest plunger (%s)")
                         % tcs[0].Label)
    faces = []
    for base, subs in obj.Base:
        for sub in subs:
            if not sub.startswith("Face"):
                raise ValueError(translate("PlungeRough", "%s.%s is not a face: select the pocket's floor face")
                                 % (base.Label, sub))
            faces.append(("%s.%s" % (base.Label, sub), base.Shape.getElement(sub)))
    if not faces:
        return faces
    diameters = [tools.diameter(tc) for tc in tcs]
    if len(set(diameters)) != len(diameters):
        raise ValueError(translate("PlungeRough", "two plunger tool controllers have the same diameter"))
    # Each further plunger cuts through its companion operation: without it
    # its plunges would silently be missing from the simulation and G-code.
    have = {comp.ToolController for comp in companions.companions(obj)}
    missing = [tc for tc in tcs[1:] if tc not in have]
    if missing:
        raise ValueError(translate("PlungeRough", "the operation of plunger %s was deleted, so its plunges would "
                                   "not be cut: untick it in the plunger list (or tick it again)")
                         % ", ".join(tc.Label for tc in missing))
    return faces


def settings_of(obj):
    """The operation's properties as plan_input.Settings (files from before a
    property: what they planned with)."""
    d = plan_input.DEFAULTS
    return plan_input.Settings(
        start_depth=obj.StartDepth.Value, final_depth=obj.FinalDepth.Value, safe_height=obj.SafeHeight.Value,
        clearance_height=obj.ClearanceHeight.Value, radial_allowance=obj.RadialAllowance.Value,
        floor_allowance=obj.FloorAllowance.Value, chord_tolerance=obj.ChordTolerance.Value,
        include_fillets=bool(obj.IncludeFillets), min_coverage=obj.MinCoverage,
        max_wall_stock=obj.MaxWallStock.Value, max_floor_stock=obj.MaxFloorStock.Value, lead_out=obj.LeadOut.Value,
        stock_aware_heights=bool(obj.StockAwareHeights), canned_cycle=bool(obj.UseCannedCycle),
        peck=bool(obj.PeckEnabled), peck_depth=obj.PeckDepth.Value, dwell=obj.DwellTime, strategy=obj.Strategy,
        growth_pattern=getattr(obj, "GrowthPattern", "Auto"), auto_select=bool(obj.AutoSelectTools),
        tool_change_time=getattr(obj, "ToolChangeTime", d["tool_change_time"]),
        holder_clearance=_mm(obj, "HolderClearance", d["holder_clearance"]))


def model_of(obj):
    """The part the selected faces belong to (walls, fillets and open sides are
    found on it)."""
    shapes = [base.Shape for base, subs in obj.Base if subs]
    return shapes[0] if len(shapes) == 1 else Part.makeCompound(shapes)


def build_input(obj, tcs, faces, workdir, notes=None, floors=("z", "brep")):
    """The planner's input (docs/plan-format.md) for the operation's properties,
    its plunger tool controllers (largest first) and its floor faces (with the
    part's fillets and open sides, geometry.pocket). The settings are checked
    first, before the geometry. Writes nothing but a sculptured floor's BREP
    into workdir; ValueError names a bad setting or face. notes: a list that
    gets what the summary should say of the pocket."""
    settings = settings_of(obj)
    plan_input.check(settings, [(tc.Label, tools.bit_length(tc.Tool, "Length")) for tc in tcs])
    model = model_of(obj)
    names = ", ".join(name for name, _ in faces)
    try:
        pocket = geometry.pocket(faces, settings.chord_tolerance, settings.include_fillets, settings.wall_margin(),
                                 model)
        # Where the pocket widens above its floor, the wall band is kept there too.
        sections, deviation = geometry.sections(model, pocket, settings.start_depth, settings.max_wall_stock) \
            if settings.max_wall_stock > 0 else ([], 0.0)
        part = geometry.part_mesh(model, pocket)
    except geometry.GeometryError:
        raise
    except Exception as e:  # OpenCASCADE's or Python's own, on faces the geometry did not foresee
        raise geometry.GeometryError(
            translate("PlungeRough", "the part around %s could not be read as a pocket (%s: %s): select the "
                      "pocket's floor faces again, or refine the part (Part > Refine shape) and select them there")
            % (names, type(e).__name__, e))
    if notes is not None:
        notes.extend(pocket.notes())
    xs = [p[0] for p in pocket.boundary]
    ys = [p[1] for p in pocket.boundary]
    material, rest_notes = rest.material(obj, PathUtils.findParentJob(obj), tcs,
                                         ((min(xs), min(ys)), (max(xs), max(ys))), settings.start_depth)
    if notes is not None:
        notes.extend(rest_notes)
    mount = mount_of(obj)
    return plan_input.plan_input(
        settings, [tools.spec(tc, obj.MaxEngagement, obj.MinEngagement, mount) for tc in tcs],
        # Rapids and retracts at the first plunger's rapid rates, as the post runs them.
        tools.time_model(tcs[0], settings.tool_change_time),
        pocket.boundary, pocket.islands, geometry.floor_spec(pocket, settings.final_depth, workdir, floors),
        sections, max(deviation, pocket.deviation), material, part)
