#!/usr/bin/env python3
"""Ratios ours / DLoopDetector from alternated timing rounds (scripts/peer_benchmark.sh).

Each argument is one round, NAME:PEER_RUN:OURS_OUTPUT: a `peer.sh run` folder
(its summary.json) and a `bowg_evaluate` output folder (its summary.txt), made
one after the other on the same images. Per round the ratio ours / peer of the
per-keyframe detection time (mean and max; ours = detector_total, the peer =
detectLoop: both without feature extraction), of the feature time (mean)
and of the whole keyframe (features + detection, mean: what a robot pays);
per sequence the median [min-max] of those ratios over its rounds, beside the
target (docs/benchmarks.md), and the loops each found at its operating point.
Ratios, not absolute times: on a shared machine both sides of an alternated
pair slow down together.

usage: peer_ratios.py [--csv FILE] NAME:PEER_RUN:OURS_OUTPUT [...]
"""
import argparse
import json
import os
import re
import statistics
import sys

sys.dont_write_bytecode = True  # no __pycache__ beside the sources
import summary_timing  # noqa: E402 (after the line above)
from csv_rows import write_rows_atomically  # noqa: E402

# Measure -> (target ratio ours / peer, what the target says).
TARGETS = {
    "detection mean": (1.0 / 3.0, "<= 1/3"),
    "detection max": (1.0 / 3.0, "<= 1/3"),
    "features mean": (1.0, "<= 1"),
    "whole-keyframe mean": (0.5, "<= 0.5"),
}


def fail(message):
    summary_timing.fail("peer_ratios", message)


def parse_ours(folder):
    """{'detection': {mean, max}, 'features': {mean, max}, 'tp': n, 'fp': n} of one summary.txt."""
    path = os.path.join(folder, "summary.txt")
    text = summary_timing.read_text("peer_ratios", path)
    stats = {key: summary_timing.stage_timing("peer_ratios", path, text, name)
             for name, key in (("detector_total", "detection"), ("features", "features"))}
    # The row table: "row precision recall F1 TP FP ..." then one line per row.
    m = re.search(r"^\S+\s+[\d.]+\s+[\d.]+\s+[\d.]+\s+(\d+)\s+(\d+)\s", text, re.M)
    if not m:
        fail("%s: no detection row" % path)
    stats["tp"], stats["fp"] = int(m.group(1)), int(m.group(2))
    return stats


def parse_peer(folder):
    path = os.path.join(folder, "summary.json")
    try:
        with open(path) as f:
            s = json.load(f)
    except (OSError, ValueError) as e:
        fail("cannot read %s: %s" % (path, e))
    try:
        run = [r for r in s["runs"] if r["alpha"] == s["timing_alpha"]]
        return {"detection": {"mean": s["detect"]["mean"], "max": s["detect"]["max"]},
                "features": {"mean": s["features"]["mean"], "max": s["features"]["max"]},
                "tp": run[0]["tp"] if run else -1, "fp": run[0]["fp"] if run else -1}
    except (KeyError, TypeError, IndexError) as e:
        fail("%s: missing field %s" % (path, e))


def per_keyframe(stats, part, stat):
    """One side's figure of a round: a stage's, or the whole keyframe's mean."""
    if part == "whole-keyframe":
        return stats["features"][stat] + stats["detection"][stat]
    return stats[part][stat]


def ratio(a, b):
    return a / b if b > 0 else float("nan")


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--csv")
    ap.add_argument("rounds", nargs="+", metavar="NAME:PEER_RUN:OURS_OUTPUT")
    args = ap.parse_args(argv)
    by_sequence = {}
    for spec in args.rounds:
        parts = spec.split(":")
        if len(parts) != 3 or not all(parts):
            fail("a round is NAME:PEER_RUN:OURS_OUTPUT, got '%s'" % spec)
        by_sequence.setdefault(parts[0], []).append((parse_peer(parts[1]), parse_ours(parts[2])))

    rows = []
    for name, pairs in by_sequence.items():
        for measure in TARGETS:
            part, stat = measure.split()
            peers = [per_keyframe(p, part, stat) for p, _ in pairs]
            ours = [per_keyframe(o, part, stat) for _, o in pairs]
            ratios = [ratio(o, p) for p, o in zip(peers, ours)]
            target, target_text = TARGETS[measure]
            med = statistics.median(ratios)
            rows.append({
                "sequence": name, "measure": measure + " ms", "rounds": len(pairs),
                "peer": statistics.median(peers), "ours": statistics.median(ours),
                "ratio": med, "ratio_min": min(ratios), "ratio_max": max(ratios),
                "target": target_text, "met": "yes" if med <= target else "no",
            })
        p, o = pairs[0]
        rows.append({"sequence": name, "measure": "loops TP/FP at the operating point",
                     "rounds": 1, "peer": "%d/%d" % (p["tp"], p["fp"]),
                     "ours": "%d/%d" % (o["tp"], o["fp"]), "ratio": "", "ratio_min": "",
                     "ratio_max": "", "target": "", "met": ""})

    print("| sequence | measure | DLoopDetector | ours | ratio ours/peer, median [min-max] "
          "| target | met |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        if r["ratio"] == "":
            print("| %s | %s | %s | %s | | | |" % (r["sequence"], r["measure"], r["peer"], r["ours"]))
        else:
            print("| %s | %s | %.2f | %.2f | %.2f [%.2f-%.2f] (%d rounds) | %s | %s |" % (
                r["sequence"], r["measure"], r["peer"], r["ours"], r["ratio"], r["ratio_min"],
                r["ratio_max"], r["rounds"], r["target"], r["met"]))
    if args.csv:
        write_rows_atomically(args.csv, rows)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
