#!/usr/bin/env python3
"""Collects the robustness suite's bowg_evaluate summaries into one table.

For every sequence: the number of revisit queries and, per detector row,
recall at 100 % precision (sequences with revisits) or the loops found at the
configured threshold (sequences without: every one is false). Then the
minimum and median per half and row. Prints the table, writes it as CSV and,
when matplotlib is there, as a bar plot.

usage: suite_report.py --results DIR --rows bow,paper,distribution
                       --csv FILE [--plot FILE] NAME:HALF [NAME:HALF ...]
"""
import argparse
import os
import re
import statistics
import sys


def parse_summary(path, rows):
    """Returns (revisits, {row: (r_at_full_precision, loops)}) of one summary.txt."""
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
        m = re.search(r"^%s\s+\S+\s+\S+\s+\S+\s+\d+\s+\d+\s+(\S+)\s+\(\s*\S+\)\s+(\d+)\s*$"
                      % re.escape(row), text, re.M)
        if m:
            result[row] = (float(m.group(1)), int(m.group(2)))
            continue
        # Without: "<row>: status=count ...".
        m = re.search(r"^%s:(.*)$" % re.escape(row), text, re.M)
        if m:
            loops = re.search(r"loop_detected=(\d+)", m.group(1))
            result[row] = (float("nan"), int(loops.group(1)) if loops else 0)
            continue
        sys.exit("suite_report: %s has no result for row %s" % (path, row))
    return revisits, result


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--results", required=True)
    ap.add_argument("--rows", required=True)
    ap.add_argument("--csv", required=True)
    ap.add_argument("--plot")
    ap.add_argument("sequences", nargs="+", help="NAME:HALF")
    a = ap.parse_args()
    rows = a.rows.split(",")
    table = []
    for item in a.sequences:
        name, _, half = item.partition(":")
        revisits, result = parse_summary(os.path.join(a.results, name, "summary.txt"), rows)
        table.append((name, half, revisits, result))

    header = "%-24s %-6s %8s " % ("sequence", "half", "revisits")
    # Columns as wide as their row names (the "without_<x>" rows are long).
    widths = [max(8, len(r)) for r in rows]
    header += " ".join("%*s" % (w, r) for w, r in zip(widths, rows)) + "   (R@100%P)"
    header += "   loops (" + ", ".join(rows) + ")"
    lines = [header]
    for name, half, revisits, result in table:
        cells = " ".join("%*s" % (w, "-" if revisits == 0 else "%.3f" % result[r][0])
                         for w, r in zip(widths, rows))
        loops = ", ".join(str(result[r][1]) for r in rows)
        lines.append("%-24s %-6s %8d %s   %s" % (name, half, revisits, cells, loops))
    lines.append("")
    name_width = max([14] + [len(r) for r in rows])
    for half in ("tuning", "test"):
        with_revisits = [t for t in table if t[1] == half and t[2] > 0]
        without = [t for t in table if t[1] == half and t[2] == 0]
        if not with_revisits and not without:
            continue
        for r in rows:
            values = [t[3][r][0] for t in with_revisits]
            false_loops = sum(t[3][r][1] for t in without)
            if values:
                lines.append("%-6s %-*s R@100%%P min %.3f median %.3f over %d sequences; "
                             "%d loops on %d sequences without revisits"
                             % (half, name_width, r, min(values), statistics.median(values), len(values),
                                false_loops, len(without)))
            else:
                lines.append("%-6s %-*s %d loops on %d sequences without revisits"
                             % (half, name_width, r, false_loops, len(without)))
    print("\n".join(lines))

    tmp = a.csv + ".tmp"
    with open(tmp, "w") as f:
        f.write("sequence,half,revisits," + ",".join("%s_recall_at_100p,%s_loops" % (r, r)
                                                    for r in rows) + "\n")
        for name, half, revisits, result in table:
            cells = ",".join("%s,%d" % ("" if revisits == 0 else "%.4f" % result[r][0], result[r][1])
                             for r in rows)
            f.write("%s,%s,%d,%s\n" % (name, half, revisits, cells))
    os.replace(tmp, a.csv)

    if a.plot:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            print("suite_report: matplotlib absent, no plot (scripts/install_deps.sh installs it)")
            return
        shown = [t for t in table if t[2] > 0]
        fig, ax = plt.subplots(figsize=(max(6, 0.9 * len(shown) + 2), 4.5))
        width = 0.8 / len(rows)
        for i, r in enumerate(rows):
            xs = [j + i * width for j in range(len(shown))]
            ax.bar(xs, [t[3][r][0] for t in shown], width, label=r)
        ax.set_xticks([j + 0.4 - width / 2 for j in range(len(shown))])
        ax.set_xticklabels(["%s\n(%s)" % (t[0], t[1]) for t in shown], rotation=60, ha="right",
                           fontsize=7)
        ax.set_ylabel("recall at 100 % precision")
        ax.set_ylim(0, 1)
        ax.axhline(0.4, color="grey", lw=0.8, ls="--")
        ax.legend(fontsize=8)
        ax.set_title("robustness suite")
        fig.tight_layout()
        tmp = a.plot + ".tmp.png"
        fig.savefig(tmp, dpi=110)
        os.replace(tmp, a.plot)


if __name__ == "__main__":
    main()
