"""The pictures of an operation's last plan, in its own folder: the planner
draws them, the panel's buttons and the docs show them. App side, no GUI."""
import os
import tempfile

# The plan's pictures, one per question: (key in the planner's result, file, title).
PICTURES = (("svg", "plan.svg", "The plan"),
            ("svg_stock", "plan-stock.svg", "Stock left"),
            ("svg_heights", "plan-heights.svg", "Stop heights"))


def plan_folder(obj, create=True):
    """The operation's own folder for its floor BREP and plan pictures."""
    workdir = os.path.join(tempfile.gettempdir(), "plungerough-%s-%s" % (obj.Document.Name, obj.Name))
    if create:
        os.makedirs(workdir, exist_ok=True)
    return workdir


def write_pictures(workdir, plan):
    """The planner's pictures into the operation's folder (taken out of the plan);
    a view the plan has not (stop heights over a flat floor) is removed."""
    for key, name, _ in PICTURES:
        path = os.path.join(workdir, name)
        picture = plan.pop(key, None)
        if picture is None:
            if os.path.exists(path):
                os.remove(path)
            continue
        with open(path, "w") as f:
            f.write(picture)


def plan_picture(obj, name="plan.svg"):
    """Path of one picture of the operation's last plan (plan.svg: the plan)."""
    return os.path.join(plan_folder(obj, create=False), name)
