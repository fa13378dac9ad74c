"""The main job inside FreeCAD's GUI (run by resources/examples/run_example.sh
under a virtual display), with the installed addon, made as a user makes it:
the example part (free-form wall, free-form island, B-spline floor), a Job from
the CAM (1.0) / Path (0.20) workbench's Job command, three plunger tool
controllers from their own tool bit files, Plunge Rough on the floor face,
recompute, post with the linuxcnc post. Writes into $PLUNGE_OUT (default ./out):
  plunge_example.FCStd   the document, with its view providers: open it in
                         FreeCAD, simulate, edit, post;
  plunge_rough.ngc       the posted G-code;
  plunge_rough.svg       the plan's pictures: the plan; -stock.svg the stock left;
                         -heights.svg the stop heights;
  summary.txt            plunges per tool, coverage, travel, estimated time;
  demo_input.json        the planner's input for the operation (demo_floor.brep: its floor);
  bits/                  the tool bit files;
  deep_pocket.*          the second demo, where plunging pays: a 75 mm deep
                         die pocket (deep_pocket_summary.txt, .ngc, .svg, -stock.svg, .FCStd).
A failure is written to demo_error.txt (the GUI has no terminal)."""
import json
import os
import shutil
import sys
import traceback

import FreeCAD

HERE = os.environ.get("PLUNGE_EXAMPLES") or os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)  # example_part; the addon is the installed one
OUT = os.path.abspath(os.environ.get("PLUNGE_OUT", "out"))


def copy_pictures(op, stem):
    """The operation's pictures into OUT: stem.svg (the plan), stem-stock.svg, stem-heights.svg."""
    from freecad_plugin import plan_files
    for _, name, _ in plan_files.PICTURES:
        path = plan_files.plan_picture(op, name)
        if os.path.exists(path):
            shutil.copyfile(path, os.path.join(OUT, stem + name[len("plan"):]))


def main():
    import FreeCADGui
    import example_part
    import plunge
    from freecad_plugin import PlungeRough, PlungeRoughGui, compat, compat_gui

    os.makedirs(OUT, exist_ok=True)
    # A machinist's unit schema for this session (mm, mm/min): the workbench
    # otherwise warns in a modal box. The user's preference is left alone.
    FreeCAD.Units.setSchema(6)
    FreeCADGui.activateWorkbench(compat_gui.workbench_name())
    doc = FreeCAD.newDocument("PlungeExample")
    part = doc.addObject("Part::Feature", "Part")
    part.Shape = example_part.freeform_part(sculptured=True)
    doc.recompute()
    job = compat_gui.job_gui().Create([part], openTaskPanel=False)
    # The post the docs name, so that File > Export or the Post command of the
    # saved demo writes what the docs show (a new Job takes the first post listed).
    job.PostProcessor = "linuxcnc"
    doc.recompute()
    face = example_part.floor_face_name(job.Model.Group[0].Shape, sculptured=True)
    # One tool bit file per plunger, as a tool library keeps them (out/bits/).
    op, tcs = example_part.add_plunge_rough(job, face, (20, 12, 6), bit_folder=os.path.join(OUT, "bits"),
                                            RadialAllowance=0.5, FloorAllowance=0.3)
    PlungeRoughGui.attach_view_providers(op)
    doc.recompute()
    plan = PlungeRough.plan_of(op)
    if plan is None:
        raise RuntimeError("the operation made no plan: " + op.Summary)

    gcode = compat.post_job(job, "linuxcnc", "--no-show-editor")
    with open(os.path.join(OUT, "plunge_rough.ngc"), "w") as f:
        f.write(gcode)
    copy_pictures(op, "plunge_rough")
    doc.saveAs(os.path.join(OUT, "plunge_example.FCStd"))
    # The planner's input for this operation, with its floor faces beside it: the
    # command-line tool plans it again (tests/bench/bench_mills.py does).
    data = json.loads(op.PlanData)["input"]
    if "brep" in data["floor"]:
        shutil.copyfile(data["floor"]["brep"], os.path.join(OUT, "demo_floor.brep"))
        data["floor"]["brep"] = "demo_floor.brep"
    with open(os.path.join(OUT, "demo_input.json"), "w") as f:
        json.dump(data, f, indent=1)

    lines = ["Plunge Rough on %s.%s (FreeCAD %s)" % (job.Model.Group[0].Label, face,
                                                      ".".join(FreeCAD.Version()[:3])),
             op.Summary, "", "operations in the job (each tool cuts its own plunges):"]
    for o in job.Operations.Group:
        tc = o.ToolController
        # Plunges: feeds down (G1 in Z only; a raised lead-out feeds up first,
        # the lead-outs move in X Y) and cycles.
        plunges, z = 0, None
        for c in o.Path.Commands:
            down = c.Name == "G1" and "Z" in c.Parameters and "X" not in c.Parameters and "Y" not in c.Parameters \
                and (z is None or c.Parameters["Z"] < z)
            plunges += c.Name in ("G81", "G83") or down
            z = c.Parameters.get("Z", z) if c.Name in ("G0", "G1") else z
        lines.append("  %-28s T%d %5.1f mm  %3d plunges, plunge feed %s" % (
            o.Label, tc.ToolNumber, float(tc.Tool.Diameter), plunges,
            "%g mm/min" % tc.VertFeed.getValueAs("mm/min").Value))
    lines += ["", "addon: " + os.path.normpath(os.path.dirname(os.path.dirname(PlungeRough.__file__))),
              "planner: " + os.path.normpath(plunge.__file__)]
    with open(os.path.join(OUT, "summary.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    deep_pocket_demo()


def deep_pocket_demo():
    """The second demo, where plunging pays: a 75 mm deep die pocket (Part
    workbench: boxes, fillet, cut), the same three plungers as plunge mills are
    fed (1200 mm/min down, as across), 50 mm flutes, held 90 mm out in 40 mm
    holders, the automatic tool choice on as for every new operation. Writes deep_pocket.ngc, .svg, .FCStd and
    deep_pocket_summary.txt."""
    import FreeCADGui
    import example_part
    from freecad_plugin import PlungeRough, PlungeRoughGui, compat, compat_gui

    doc = FreeCAD.newDocument("PlungeDeepPocket")
    part = example_part.deep_pocket_part(doc)
    for obj in doc.Objects:
        if obj is not part:
            obj.Visibility = False
    job = compat_gui.job_gui().Create([part], openTaskPanel=False)
    job.PostProcessor = "linuxcnc"
    doc.recompute()
    face = example_part.floor_face_name(job.Model.Group[0].Shape, sculptured=False)
    # Held 90 mm out in 40 mm holders: deep enough for the 75 mm pocket, the
    # holders kept clear of its walls.
    op, tcs = example_part.add_plunge_rough(job, face, (20, 12, 6), bit_folder=os.path.join(OUT, "bits"),
                                            RadialAllowance=0.5, FloorAllowance=0.3, StickOut=90.0,
                                            HolderDiameter=40.0)
    for tc in tcs:
        tc.VertFeed = tc.HorizFeed = "1200 mm/min"
    doc.recompute()
    PlungeRoughGui.attach_view_providers(op)
    plan = PlungeRough.plan_of(op)
    if plan is None:
        raise RuntimeError("the deep pocket's operation made no plan: " + op.Summary)
    with open(os.path.join(OUT, "deep_pocket.ngc"), "w") as f:
        f.write(compat.post_job(job, "linuxcnc", "--no-show-editor"))
    copy_pictures(op, "deep_pocket")
    doc.saveAs(os.path.join(OUT, "deep_pocket.FCStd"))
    with open(os.path.join(OUT, "deep_pocket_summary.txt"), "w") as f:
        f.write("Plunge Rough on the deep pocket %s.%s, 75 mm deep (FreeCAD %s)\n%s\n" % (
            job.Model.Group[0].Label, face, ".".join(FreeCAD.Version()[:3]), op.Summary))


try:
    if os.path.exists(os.path.join(OUT, "demo_error.txt")):
        os.remove(os.path.join(OUT, "demo_error.txt"))
    main()
except Exception:
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, "demo_error.txt"), "w") as f:
        f.write(traceback.format_exc())
finally:
    os._exit(0)
