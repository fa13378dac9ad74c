"""The main job, headless in FreeCAD (freecadcmd), with the installed addon:
the example part (free-form wall, free-form island, B-spline floor), a Job with
three plunger tool controllers, Plunge Rough on the floor face, recompute, post
with the linuxcnc post. Writes into $PLUNGE_OUT (default ./out):
  plunge_example.FCStd   the document (open it in FreeCAD to simulate),
  plunge_rough.ngc       the posted G-code,
  plunge_rough.svg       the plan picture,
  summary.txt            plunges per tool, coverage, travel, estimated time.
Run by resources/examples/run_example.sh."""
import os
import shutil
import sys

import FreeCAD

HERE = os.path.dirname(os.path.abspath(__file__)) if "__file__" in globals() else os.environ["PLUNGE_EXAMPLES"]
sys.path.insert(0, HERE)
OUT = os.path.abspath(os.environ.get("PLUNGE_OUT", "out"))


def fail(message):
    sys.stderr.write("freecad_demo: %s\n" % message)
    sys.stderr.flush()
    os._exit(1)


def main():
    import example_part
    import plunge
    from freecad_plugin import PlungeRough, compat

    os.makedirs(OUT, exist_ok=True)
    doc = FreeCAD.newDocument("PlungeExample")
    job = example_part.make_job(doc, example_part.freeform_part(sculptured=True))
    face = example_part.floor_face_name(job.Model.Group[0].Shape, sculptured=True)
    # One tool bit file per plunger, as a tool library keeps them (out/bits/).
    op, tcs = example_part.add_plunge_rough(job, face, (20, 12, 6), bit_folder=os.path.join(OUT, "bits"),
                                            RadialAllowance=0.5, FloorAllowance=0.3)
    plan = PlungeRough.plan_of(op)
    if plan is None:
        fail("the operation made no plan: " + op.Summary)

    gcode = compat.post_job(job, "linuxcnc", "--no-show-editor")
    with open(os.path.join(OUT, "plunge_rough.ngc"), "w") as f:
        f.write(gcode)
    shutil.copyfile(PlungeRough.plan_picture(op), os.path.join(OUT, "plunge_rough.svg"))
    doc.saveAs(os.path.join(OUT, "plunge_example.FCStd"))

    lines = ["Plunge Rough on %s.%s (FreeCAD %s)" % (job.Model.Group[0].Label, face,
                                                      ".".join(FreeCAD.Version()[:3])),
             op.Summary, "", "operations in the job (each tool cuts its own plunges):"]
    for o in job.Operations.Group:
        tc = o.ToolController
        plunges = sum(1 for c in o.Path.Commands if c.Name in ("G1", "G81", "G83"))
        lines.append("  %-28s T%d %5.1f mm  %3d plunges, plunge feed %s" % (
            o.Label, tc.ToolNumber, float(tc.Tool.Diameter), plunges,
            "%g mm/min" % tc.VertFeed.getValueAs("mm/min").Value))
    lines += ["", "addon: " + os.path.normpath(os.path.dirname(os.path.dirname(PlungeRough.__file__))),
              "planner: " + os.path.normpath(plunge.__file__)]
    with open(os.path.join(OUT, "summary.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    print("wrote %s: plunge_rough.ngc, plunge_rough.svg, summary.txt, plunge_example.FCStd" % OUT)


try:
    main()
except Exception as e:  # one line, non-zero exit
    fail("%s: %s" % (type(e).__name__, e))
sys.stdout.flush()
os._exit(0)
