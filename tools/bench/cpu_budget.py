#!/usr/bin/env python3
"""A robot's CPU budget per preset from timing rounds (scripts/cpu_budget.sh).

Each argument is one round, PRESET:OUTPUT: a `bowg_evaluate --jobs 1` output
folder (its summary.txt). Per preset: the median over its rounds of the
per-keyframe means of feature extraction (wall time, and the process's CPU
time, features_cpu: OpenCV may spread a frame over its worker threads),
detection (detector_total, one thread) and the whole keyframe's CPU time
(features_cpu + detection); the p95 of the whole keyframe (the rounds'
median of features_cpu p95 + detection p95, an upper bound of the
keyframes' own p95); and the share of one core the whole keyframe's mean
CPU time takes at 5, 10 and 25 keyframes a second (mean ms x rate / 1000).

usage: cpu_budget.py [--csv FILE] PRESET:OUTPUT [...]
"""
import argparse
import os
import statistics
import sys

sys.dont_write_bytecode = True  # no __pycache__ beside the sources
import summary_timing  # noqa: E402 (after the line above)
from csv_rows import write_rows_atomically  # noqa: E402

RATES = (5, 10, 25)


def read_round(folder):
    path = os.path.join(folder, "summary.txt")
    text = summary_timing.read_text("cpu_budget", path)
    features = summary_timing.stage_timing("cpu_budget", path, text, "features")
    features_cpu = summary_timing.stage_timing("cpu_budget", path, text, "features_cpu")
    detection = summary_timing.stage_timing("cpu_budget", path, text, "detector_total")
    return {"features": features["mean"], "features_cpu": features_cpu["mean"],
            "detection": detection["mean"],
            "keyframe": features_cpu["mean"] + detection["mean"],
            "keyframe_p95": features_cpu["p95"] + detection["p95"]}


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csv")
    ap.add_argument("rounds", nargs="+", metavar="PRESET:OUTPUT")
    args = ap.parse_args(argv)
    by_preset = {}
    for spec in args.rounds:
        preset, sep, folder = spec.partition(":")
        if not sep or not preset or not folder:
            summary_timing.fail("cpu_budget", "a round is PRESET:OUTPUT, got '%s'" % spec)
        by_preset.setdefault(preset, []).append(read_round(folder))

    rows = []
    for preset, rounds in by_preset.items():
        med = {k: statistics.median(r[k] for r in rounds) for k in rounds[0]}
        row = {"preset": preset, "rounds": len(rounds), "features_ms": med["features"],
               "features_cpu_ms": med["features_cpu"],
               "detection_ms": med["detection"], "keyframe_ms": med["keyframe"],
               "keyframe_p95_ms": med["keyframe_p95"]}
        for rate in RATES:
            row["core_share_at_%d_hz" % rate] = med["keyframe"] * rate / 1000.0
        rows.append(row)

    print("| preset | features ms, wall (CPU) | detection ms | whole keyframe CPU ms, mean (p95) "
          "| share of one core at %s keyframes/s |" % " / ".join(str(r) for r in RATES))
    print("|---|---|---|---|---|")
    for r in rows:
        shares = " / ".join("%.1f %%" % (100 * r["core_share_at_%d_hz" % rate]) for rate in RATES)
        print("| %s | %.2f (%.2f) | %.2f | %.2f (%.2f) | %s |" % (
            r["preset"], r["features_ms"], r["features_cpu_ms"], r["detection_ms"],
            r["keyframe_ms"], r["keyframe_p95_ms"], shares))
    print("(median over %s rounds per preset)" % ", ".join(
        "%s %d" % (r["preset"], r["rounds"]) for r in rows))
    if args.csv:
        write_rows_atomically(args.csv, rows)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
