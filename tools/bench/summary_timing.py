"""The per-keyframe timing table of a bowg_evaluate summary.txt.

`bowg_evaluate` ends its summary with "per-keyframe timing (ms): mean /
median / p95 / max" and one line per stage ("features", "detector_total",
...). Used by the peer comparison (peer_ratios.py) and the CPU budget
(cpu_budget.py).
"""
import re
import sys


def fail(tool, message):
    sys.exit("%s: %s" % (tool, message))


def read_text(tool, path):
    try:
        with open(path) as f:
            return f.read()
    except OSError as e:
        fail(tool, "cannot read %s: %s" % (path, e))


def stage_timing(tool, path, text, stage):
    """{'mean', 'median', 'p95', 'max'} in ms of one stage of summary.txt's text."""
    timing = text.split("per-keyframe timing", 1)
    if len(timing) != 2:
        fail(tool, "%s: no per-keyframe timing" % path)
    m = re.search(r"^\s+%s\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s*$" % re.escape(stage),
                  timing[1], re.M)
    if not m:
        fail(tool, "%s: no %s timing" % (path, stage))
    return dict(zip(("mean", "median", "p95", "max"), (float(g) for g in m.groups())))
