#!/usr/bin/env python3
"""Recall of revisit queries by how far they are from the earlier pass's
nearest keyframe of the same place (the "offset").

A revisit rarely lands exactly on an earlier keyframe: it lands anywhere
between two of them, up to half the keyframe spacing away. The offset is the
distance from the query's position to the nearest of its ground-truth
matches. For each offset bin: the revisit queries, the share the detector
closed correctly (a loop to a true match, the evaluator's `correct` column),
and the inliers of the true candidates that reached RANSAC (status
loop_detected or too_few_inliers with a true match as the candidate).

Reads a suite output folder (scripts/robustness_suite.sh): for every
sequence NAME, sequences/NAME/poses.csv and ground_truth.txt (rendered) and
results/NAME/MODE/keyframes_ROW.csv (MODE: the robot's input mode). Sequences without poses (real frames) or
without revisits are left out.

usage: revisit_offsets.py --suite DIR [--row configured] [--mode positions] [--csv FILE]
                          [NAME ...]
"""
import argparse
import csv
import math
import os
import statistics
import sys

BINS_CM = [0, 1, 2, 3, 4, 5, 8]  # lower edges; the last bin is open


def fail(message):
    sys.exit("revisit_offsets: " + message)


def read_positions(path):
    try:
        with open(path) as f:
            return {int(r["frame"]): (float(r["x"]), float(r["y"]), float(r["z"]))
                    for r in csv.DictReader(f)}
    except (OSError, KeyError, ValueError) as e:
        fail("cannot read positions from %s: %s" % (path, e))


def read_ground_truth(path):
    """{query frame: [matching frames]} of a ground-truth file ("q: m m m")."""
    truth = {}
    try:
        with open(path) as f:
            for line in f:
                line = line.strip()
                if not line or line.startswith("#"):
                    continue
                query, _, matches = line.partition(":")
                truth[int(query)] = [int(m) for m in matches.replace(",", " ").split()]
    except (OSError, ValueError) as e:
        fail("cannot read ground truth %s: %s" % (path, e))
    return truth


def read_keyframes(path):
    try:
        with open(path) as f:
            return {int(r["frame"]): r for r in csv.DictReader(f)}
    except (OSError, KeyError, ValueError) as e:
        fail("cannot read keyframe results %s: %s" % (path, e))


def bin_of(offset_cm):
    return max(i for i, lo in enumerate(BINS_CM) if lo <= offset_cm)


def bin_label(i):
    hi = "%d" % BINS_CM[i + 1] if i + 1 < len(BINS_CM) else ""
    return "%d-%s cm" % (BINS_CM[i], hi) if hi else ">= %d cm" % BINS_CM[i]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--suite", required=True)
    parser.add_argument("--row", default="configured")
    parser.add_argument("--mode", default="positions")
    parser.add_argument("--csv")
    parser.add_argument("names", nargs="*")
    args = parser.parse_args()
    names = args.names or sorted(os.listdir(os.path.join(args.suite, "results")))
    queries = [0] * len(BINS_CM)
    closed = [0] * len(BINS_CM)
    inliers = [[] for _ in BINS_CM]
    used = []
    for name in names:
        seq = os.path.join(args.suite, "sequences", name)
        results = os.path.join(args.suite, "results", name, args.mode,
                               "keyframes_%s.csv" % args.row)
        if not os.path.exists(os.path.join(seq, "poses.csv")):
            continue  # real frames: no positions
        positions = read_positions(os.path.join(seq, "poses.csv"))
        truth = read_ground_truth(os.path.join(seq, "ground_truth.txt"))
        if not truth:
            continue
        keyframes = read_keyframes(results)
        used.append(name)
        for query, matches in truth.items():
            if query not in positions or query not in keyframes or not matches:
                fail("%s: query %d has no position, keyframe result or match" % (name, query))
            offset = min(math.dist(positions[query], positions[m]) for m in matches)
            b = bin_of(100.0 * offset)
            k = keyframes[query]
            queries[b] += 1
            if k["status"] == "loop_detected" and k.get("correct") == "1":
                closed[b] += 1
            if (k["candidate"] and int(k["candidate"]) in matches
                    and k["status"] in ("loop_detected", "too_few_inliers")):
                inliers[b].append(int(k["inliers"]))
    if not used:
        fail("no rendered sequence with revisits under %s" % args.suite)
    rows = []
    for i in range(len(BINS_CM)):
        if queries[i] == 0:
            continue
        median = statistics.median(inliers[i]) if inliers[i] else None
        rows.append((bin_label(i), queries[i], closed[i], closed[i] / queries[i], median,
                     len(inliers[i])))
    print("revisit queries by offset to the nearest true match (%s row, %s mode; %s)"
          % (args.row, args.mode, ", ".join(used)))
    print("(offset: how far the query stood from the earlier pass's nearest keyframe of that "
          "place; a revisit falls between two keyframes, and the further off, the less the "
          "views overlap)")
    print("%-9s %8s %8s %9s %s" % ("offset", "queries", "closed", "recall",
                                    "inliers of verified true candidates: median (n)"))
    for label, n, c, r, median, m in rows:
        print("%-9s %8d %8d %9.2f %s" % (label, n, c, r,
                                          "-" if median is None else "%g (%d)" % (median, m)))
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(["offset", "queries", "closed", "recall", "median_inliers_true",
                        "verified_true"])
            for label, n, c, r, median, m in rows:
                w.writerow([label, n, c, "%.4f" % r, "" if median is None else median, m])


if __name__ == "__main__":
    main()
