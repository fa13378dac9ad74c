"""The compiled planner as the addon uses it: the `plunge` module beside the
addon, and FreeCAD's progress indicator reporting (and cancelling) a plan.

App side: never imports GUI code.
"""
import os

import FreeCAD

ADDON = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def install_command(addon=ADDON):
    """The one command that builds the planner and installs it (and the
    plunge-mill bits) for this FreeCAD, from a clone of the repository (an
    Addon Manager install is one); None for an installed copy, which has no
    sources to build from."""
    if not os.path.exists(os.path.join(addon, "resources", "setup.sh")):
        return None
    return "sh '%s/resources/install_addon.sh' --build" % addon


def missing_planner_message(error=None, addon=ADDON):
    """What the user reads when the compiled planner is not beside the addon."""
    why = " (%s)" % error if error else ""
    command = install_command(addon)
    if command:
        return ("the compiled planner (the plunge module) is not installed beside the addon in %s%s: build and "
                "install it for this FreeCAD, as root on Debian: %s" % (addon, why, command))
    return ("the compiled planner (the plunge module) is not installed beside the addon in %s%s: install the addon "
            "again from a clone of PlungeRough (its README's main command)" % (addon, why))


def planner():
    """The core planner (the compiled `plunge` module beside the addon)."""
    try:
        import plunge
    except ImportError as e:
        raise ValueError(missing_planner_message(e))
    return plunge


# What FreeCAD raises when the user aborts (not an Exception).
ABORT = getattr(FreeCAD.Base, "FreeCADAbort", KeyboardInterrupt)


def is_abort(error):
    """Whether an exception is the user's abort: FreeCAD's own, or the
    progress indicator's RuntimeError when it is the outermost one (a
    recompute with the "can abort" preference off)."""
    return isinstance(error, ABORT) or (isinstance(error, RuntimeError) and "abort progress indicator" in str(error))


class PlanProgress:
    """The planner's progress in FreeCAD's progress indicator (the GUI's status
    bar, which keeps the GUI drawn while planning). Esc asks whether to abort;
    aborting cancels the plan. Inside a recompute the document's own indicator
    is the outermost one and ignores this one's steps (FreeCAD 0.20 to 1.1):
    FreeCAD.checkAbort() is what processes events and raises the abort there,
    on every FreeCAD version (in freecadcmd it does nothing)."""

    def __init__(self, label):
        self.label = label
        self.stage = None
        self.indicator = FreeCAD.Base.ProgressIndicator()
        self.running = False

    def __call__(self, fraction, stage):
        if stage != self.stage:  # one busy indicator per stage, named by it
            self.stop()
            self.indicator.start("%s: %s (%d %%)" % (self.label, stage, round(100 * fraction)), 0)
            self.running = True
            self.stage = stage
        self.indicator.next(True)  # raises when the user aborts an outermost indicator
        check = getattr(FreeCAD, "checkAbort", None)
        if check is not None:
            check()  # raises FreeCADAbort once the user pressed Esc and confirmed
        return True

    def stop(self):
        if self.running:
            self.indicator.stop()
            self.running = False
