#!/usr/bin/env python3
"""Collects the robustness suite's bowg_evaluate summaries into one table.

For every sequence, input mode and detector row: what the detector publishes
at the configured threshold (precision, recall, true and false loops) and,
as a second figure, the recall at 100 % precision of the PR sweep. On a
sequence without revisits every loop is false. Then per half, row and mode:
the minimum and median recall at the threshold, the lowest precision, the
false loops, and the minimum and median recall at 100 % precision. Prints
the tables, writes them as CSV and, when matplotlib is there, as a bar plot
(one panel per mode).

usage: suite_report.py --results DIR --rows bow,paper,distribution
                       --csv FILE [--plot FILE] NAME:HALF:MODE [NAME:HALF:MODE ...]
"""
import argparse
import math
import os
import re
import statistics
import sys

MODES = ("positions", "odometer", "images")


class Result:
    """One row of one summary.txt."""

    def __init__(self, precision, recall, tp, fp, r_full, loops):
        self.precision, self.recall, self.tp, self.fp = precision, recall, tp, fp
        self.r_full, self.loops = r_full, loops


def parse_summary(path, rows):
    """Returns (revisits, {row: Result}) of one summary.txt."""
    try:
        with open(path) as f:
            text = f.read()
    except OSError as e:
        sys.exit("suite_report: cannot read %s: %s" % (path, e))
    m = re.search(r"\((\d+) queries with a revisit\)", text)
    revisits = int(m.group(1)) if m else 0
    result = {}
    for row in rows:
        # With ground truth: "<row> precision recall F1 TP FP R@100%P (thr) loops".
        m = re.search(r"^%s\s+(\S+)\s+(\S+)\s+\S+\s+(\d+)\s+(\d+)\s+(\S+)\s+\(\s*\S+\)\s+(\d+)\s*$"
                      % re.escape(row), text, re.M)
        if m:
            result[row] = Result(float(m.group(1)), float(m.group(2)), int(m.group(3)),
                                 int(m.group(4)), float(m.group(5)), int(m.group(6)))
            continue
        # Without: "<row>: status=count ...": every loop is unverified.
        m = re.search(r"^%s:(.*)$" % re.escape(row), text, re.M)
        if m:
            loops = re.search(r"loop_detected=(\d+)", m.group(1))
            n = int(loops.group(1)) if loops else 0
            result[row] = Result(float("nan"), float("nan"), 0, n, float("nan"), n)
            continue
        sys.exit("suite_report: %s has no result for row %s" % (path, row))
    return revisits, result


def cell(revisits, r):
    """precision, recall, false loops, R@100%P of one sequence, mode and row."""
    if r is None:
        return "%25s" % "-"
    if revisits == 0:
        return "%5s %5s %5d %7s" % ("-", "-", r.fp, "-")
    return "%5.3f %5.3f %5d %7.3f" % (r.precision, r.recall, r.fp, r.r_full)


def summary_line(half, row, mode, entries):
    """One line per half, row and mode; entries: [(revisits, Result)]."""
    with_revisits = [r for n, r in entries if n > 0]
    without = [r for n, r in entries if n == 0]
    false_with = sum(r.fp for r in with_revisits)
    false_without = sum(r.fp for r in without)
    text = "%-6s %-12s %-9s " % (half, row, mode)
    if with_revisits:
        recalls = [r.recall for r in with_revisits]
        fulls = [r.r_full for r in with_revisits]
        text += ("at the threshold: recall min %.3f median %.3f, precision min %.3f, "
                 "%d false loops on %d sequences; R@100%%P min %.3f median %.3f; "
                 % (min(recalls), statistics.median(recalls),
                    min(r.precision for r in with_revisits), false_with, len(with_revisits),
                    min(fulls), statistics.median(fulls)))
    return text + "%d loops on %d sequences without revisits" % (false_without, len(without))


def write_csv(path, table, rows):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write("sequence,half,mode,revisits,row,precision,recall,true_loops,false_loops,"
                "recall_at_100p,loops\n")
        for name, half, mode, revisits, result in table:
            for row in rows:
                r = result[row]
                number = (lambda v: "" if revisits == 0 or math.isnan(v) else "%.4f" % v)
                f.write("%s,%s,%s,%d,%s,%s,%s,%d,%d,%s,%d\n"
                        % (name, half, mode, revisits, row, number(r.precision),
                           number(r.recall), r.tp, r.fp, number(r.r_full), r.loops))
    os.replace(tmp, path)


def plot(path, table, rows, modes):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("suite_report: matplotlib absent, no plot (scripts/install_deps.sh installs it)")
        return
    names = []
    for name, half, _, _, _ in table:
        if (name, half) not in names:
            names.append((name, half))
    fig, axes = plt.subplots(len(modes), 1, figsize=(max(8, 0.75 * len(names) + 3),
                                                     3.2 * len(modes) + 1.2), squeeze=False)
    width = 0.8 / len(rows)
    lookup = {(t[0], t[2]): t for t in table}
    for ax, mode in zip(axes[:, 0], modes):
        for i, row in enumerate(rows):
            xs, ys, labels = [], [], []
            for j, (name, _) in enumerate(names):
                t = lookup.get((name, mode))
                if t is None:
                    continue
                r = t[4][row]
                xs.append(j + i * width)
                ys.append(0.0 if t[3] == 0 else r.recall)
                labels.append("%d FP" % r.fp if r.fp else ("no loop" if t[3] == 0 else "%.2f" % r.recall))
            bars = ax.bar(xs, ys, width, label=row)
            for x, y, label, bar in zip(xs, ys, labels, bars):
                if label:
                    bad = label.endswith("FP")
                    ax.text(x, y + 0.02, label, ha="center", va="bottom", rotation=90,
                            fontsize=6, color="red" if bad else
                            ("green" if label == "no loop" else "black"))
        ax.set_xticks([j + 0.4 - width / 2 for j in range(len(names))])
        ax.set_xticklabels(["%s (%s)" % n for n in names], rotation=60, ha="right", fontsize=7)
        ax.set_ylim(0, 1.3)
        ax.set_yticks([0, 0.2, 0.4, 0.6, 0.8, 1.0])
        ax.set_ylabel("recall at the threshold")
        ax.set_title("%s mode: recall at the preset's threshold (bars); red: false loops "
                     "there; sequences without revisits: their loops (all false)" % mode,
                     fontsize=9)
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    fig.tight_layout()
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--results", required=True)
    ap.add_argument("--rows", required=True)
    ap.add_argument("--csv", required=True)
    ap.add_argument("--plot")
    ap.add_argument("runs", nargs="+", help="NAME:HALF:MODE")
    a = ap.parse_args()
    rows = a.rows.split(",")
    table = []
    for item in a.runs:
        parts = item.split(":")
        if len(parts) != 3 or parts[2] not in MODES:
            sys.exit("suite_report: '%s' is not NAME:HALF:MODE (modes: %s)" % (item, ", ".join(MODES)))
        name, half, mode = parts
        revisits, result = parse_summary(os.path.join(a.results, name, mode, "summary.txt"), rows)
        table.append((name, half, mode, revisits, result))
    modes = [m for m in MODES if any(t[2] == m for t in table)]
    names = []
    for t in table:
        if (t[0], t[1], t[3]) not in names:
            names.append((t[0], t[1], t[3]))
    lookup = {(t[0], t[2]): t[4] for t in table}
    lines = []
    for row in rows:
        lines.append("%s: at the threshold precision, recall, false loops; then R@100%%P" % row)
        lines.append("%-24s %-6s %8s  " % ("sequence", "half", "revisits") +
                     "  ".join("%-25s" % m for m in modes))
        for name, half, revisits in names:
            cells = "  ".join(cell(revisits, lookup.get((name, m), {}).get(row)) for m in modes)
            lines.append("%-24s %-6s %8d  %s" % (name, half, revisits, cells))
        lines.append("")
    for half in ("tuning", "test"):
        for row in rows:
            for mode in modes:
                entries = [(t[3], t[4][row]) for t in table if t[1] == half and t[2] == mode]
                if entries:
                    lines.append(summary_line(half, row, mode, entries))
    print("\n".join(lines))
    write_csv(a.csv, table, rows)
    if a.plot:
        plot(a.plot, table, rows, modes)


if __name__ == "__main__":
    main()
