#!/usr/bin/env python3
"""Collects the re-inspection suite's bowg_evaluate summaries into one table.

For every pair and input mode, at the configured threshold: the loops across
missions (a query of the later survey closing into the earlier survey or the
loaded map): precision, recall, true and false loops and the queries with a
true match there (positives); and all loops (within a survey too): precision,
recall, false loops. A pair without positives (another network: kind
"other") has no recall; all its cross-mission loops are false. Then per half
and mode: the median and minimum cross-mission recall over the pairs with
positives and the cross-mission false loops of every pair. Prints the tables
and writes them as CSV.

usage: reinspection_report.py --results DIR --csv FILE NAME:HALF:KIND:MODE [...]
"""
import argparse
import os
import re
import statistics
import sys

MODES = ("positions", "odometer", "images")
ROW = "configured"


def parse_summary(path):
    """Returns (cross, overall): cross = (precision, recall, tp, fp, positives),
    overall = (precision, recall, tp, fp) of the configured row."""
    try:
        with open(path) as f:
            text = f.read()
    except OSError as e:
        sys.exit("reinspection_report: cannot read %s: %s" % (path, e))
    # All loops: "<row> precision recall F1 TP FP R@100%P (thr) loops".
    m = re.search(r"^%s\s+(\S+)\s+(\S+)\s+\S+\s+(\d+)\s+(\d+)\s+\S+\s+\(\s*\S+\)\s+\d+\s*$"
                  % ROW, text, re.M)
    if not m:
        sys.exit("reinspection_report: %s has no result for row %s" % (path, ROW))
    overall = (float(m.group(1)), float(m.group(2)), int(m.group(3)), int(m.group(4)))
    # Across missions: "<row> precision recall TP FP positives", after its heading.
    part = text.split("\nacross missions", 1)
    if len(part) < 2:
        sys.exit("reinspection_report: %s has no 'across missions' table" % path)
    m = re.search(r"^%s\s+(\S+)\s+(\S+)\s+(\d+)\s+(\d+)\s+(\d+)\s*$" % ROW, part[1], re.M)
    if not m:
        sys.exit("reinspection_report: %s: no across-missions line for row %s" % (path, ROW))
    cross = (float(m.group(1)), float(m.group(2)), int(m.group(3)), int(m.group(4)),
             int(m.group(5)))
    return cross, overall


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--results", required=True)
    ap.add_argument("--csv", required=True)
    ap.add_argument("runs", nargs="+", help="NAME:HALF:KIND:MODE")
    a = ap.parse_args()
    table = []
    for item in a.runs:
        parts = item.split(":")
        if len(parts) != 4 or parts[3] not in MODES:
            sys.exit("reinspection_report: '%s' is not NAME:HALF:KIND:MODE" % item)
        name, half, kind, mode = parts
        cross, overall = parse_summary(os.path.join(a.results, name, mode, "summary.txt"))
        table.append((name, half, kind, mode, cross, overall))

    def fmt(value, positives):
        return "%6s" % "-" if positives == 0 else "%6.3f" % value

    lines = ["across missions (later survey into the earlier one or the map) and all loops, "
             "configured row at the preset's threshold",
             "%-24s %-6s %-5s %-9s | %6s %6s %4s %4s %9s | %6s %6s %5s"
             % ("pair", "half", "kind", "mode", "prec", "recall", "TP", "FP", "positives",
                "prec", "recall", "FP")]
    for name, half, kind, mode, c, o in table:
        # No loop across missions: no precision to speak of.
        prec = "%6s" % "-" if c[2] + c[3] == 0 else "%6.3f" % c[0]
        lines.append("%-24s %-6s %-5s %-9s | %s %s %4d %4d %9d | %6.3f %6.3f %5d"
                     % (name, half, kind, mode, prec, fmt(c[1], c[4]), c[2], c[3], c[4],
                        o[0], o[1], o[3]))
    lines.append("")
    for half in ("tuning", "test"):
        for mode in MODES:
            rows = [t for t in table if t[1] == half and t[3] == mode]
            if not rows:
                continue
            recalls = [t[4][1] for t in rows if t[4][4] > 0]
            text = "%-6s %-9s cross-mission recall " % (half, mode)
            if recalls:
                text += "median %.3f min %.3f over %d pairs with positives" % (
                    statistics.median(recalls), min(recalls), len(recalls))
            else:
                text += "- (no pair with positives)"
            text += "; cross-mission false loops %d on %d pairs" % (
                sum(t[4][3] for t in rows), len(rows))
            lines.append(text)
    print("\n".join(lines))

    tmp = a.csv + ".tmp"
    with open(tmp, "w") as f:
        f.write("pair,half,kind,mode,cross_precision,cross_recall,cross_true_loops,"
                "cross_false_loops,cross_positives,precision,recall,false_loops\n")
        for name, half, kind, mode, c, o in table:
            f.write("%s,%s,%s,%s,%s,%s,%d,%d,%d,%.4f,%.4f,%d\n"
                    % (name, half, kind, mode,
                       "" if c[2] + c[3] == 0 else "%.4f" % c[0],
                       "" if c[4] == 0 else "%.4f" % c[1], c[2], c[3], c[4], o[0], o[1], o[3]))
    os.replace(tmp, a.csv)


if __name__ == "__main__":
    main()
