"""The compiled planner as the addon uses it: the `plunge` module beside the
addon, and FreeCAD's progress indicator reporting (and cancelling) a plan.

App side: never imports GUI code.
"""
import FreeCAD


def planner():
    """The core planner (the compiled `plunge` module beside the addon)."""
    try:
        import plunge
    except ImportError as e:
        raise ValueError("the planner module is not installed (%s); run the README's main command" % e)
    return plunge


# What FreeCAD's progress indicator raises when the user aborts (not an Exception).
ABORT = getattr(FreeCAD.Base, "FreeCADAbort", KeyboardInterrupt)


class PlanProgress:
    """The planner's progress in FreeCAD's progress indicator (the GUI's status
    bar, which keeps the GUI drawn while planning; Esc there asks whether to
    abort, and aborting cancels the plan)."""

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
        self.indicator.next(True)  # raises when the user aborts
        return True

    def stop(self):
        if self.running:
            self.indicator.stop()
            self.running = False
