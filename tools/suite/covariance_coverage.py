#!/usr/bin/env python3
"""How often the truth lies inside the metric loops' 95 % covariance
ellipsoid, over a half of the robustness suite, for several factors on the
covariance (the detector's `metric_covariance_scale`).

Each rendered sequence of the half (scripts/robustness_suite.sh renders them)
is run once as a robot with odometry and a calibrated camera has it:
bowg_evaluate with the drifting odometry (--odometry, --odometry-poses) and
the intrinsics, so that loops get a metric translation. A factor s on the
covariance divides every loop's squared Mahalanobis error by s, so that one
run answers for every s: its loop poses are written again with their
covariance times s / the factor they were detected with, and bowg_pose_graph
--loop-poses measures them against the rendered truth. The factor to
configure is the smallest whose share reaches 95 % on the tuning half; the
test half then says whether it holds.

usage: covariance_coverage.py --sequences DIR --tools DIR --config FILE --vocabulary FILE
                              --output DIR [--list FILE] [--half tuning]
                              [--detected-scale 1] [--scales 1,2,4] [--csv FILE]
"""
import argparse
import csv
import os
import re
import subprocess
import sys
import tempfile

import numpy

COVARIANCE = ["cxx", "cxy", "cxz", "cyy", "cyz", "czz"]


def fail(message):
    sys.exit("covariance_coverage: " + message)


def sequences_of(list_path, sequences, half):
    """(name, rate) of the rendered sequences of `half` in the suite's list."""
    try:
        with open(list_path) as f:
            lines = f.read().splitlines()
    except OSError as e:
        fail("cannot read %s: %s" % (list_path, e))
    chosen = []
    for line in lines:
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        fields = [x.strip() for x in line.split("|")]
        if len(fields) != 5 or fields[1] != half or fields[3] != "render":
            continue
        argv = fields[4].split()
        rate = argv[argv.index("--rate") + 1] if "--rate" in argv else "2"
        folder = os.path.join(sequences, fields[0])
        if os.path.exists(os.path.join(folder, "poses.csv")):
            chosen.append((fields[0], rate))
    return chosen


def detect(a, name, rate):
    """The loops and loop poses of `name` (cached in the output folder)."""
    sequence = os.path.join(a.sequences, name)
    result = os.path.join(a.output, name)
    if os.path.exists(os.path.join(result, "loop_poses_configured.csv")):
        return result
    os.makedirs(result, exist_ok=True)
    command = [os.path.join(a.tools, "bowg_evaluate"), "--images", sequence, "--rate", rate,
               "--gt", os.path.join(sequence, "ground_truth.txt"),
               "--odometry", os.path.join(sequence, "odometry.csv"),
               "--odometry-poses", os.path.join(sequence, "odometry.csv"),
               "--intrinsics", os.path.join(sequence, "intrinsics.csv"),
               "--vocabulary", a.vocabulary, "--config", a.config, "--rows", "configured",
               "--quiet", "--output", result]
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True)
    if done.returncode != 0:
        fail("%s failed:\n%s" % (" ".join(command), done.stdout[-2000:]))
    return result


def usable(r):
    """Whether a row's 3x3 covariance, as written to the file, is one that a
    pose graph takes: positive definite, and not so wide (a bootstrap that
    diverged: sigma beyond 1 m) that rounding breaks that."""
    try:
        xx, xy, xz, yy, yz, zz = (float(r[c]) for c in COVARIANCE)
    except ValueError:
        return False
    c = numpy.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    if not numpy.all(numpy.isfinite(c)) or max(xx, yy, zz) > 1.0:
        return False
    try:
        numpy.linalg.cholesky(c)
    except numpy.linalg.LinAlgError:
        return False
    return True


def scaled_copy(path, factor, out):
    """`path`'s loop poses with every covariance cell times `factor`; a
    metric loop whose covariance is not usable() is left out. Returns how
    many."""
    with open(path) as f:
        reader = csv.DictReader(f)
        fields = reader.fieldnames
        rows = list(reader)
    missing = [c for c in COVARIANCE if c not in (fields or [])]
    if missing:
        fail("%s has no column %s" % (path, missing[0]))
    with open(out, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        left_out = 0
        for r in rows:
            if r["metric_status"] == "estimated" and not usable(r):
                left_out += 1
                continue
            for c in COVARIANCE:
                if r[c] not in ("", "nan"):
                    r[c] = repr(float(r[c]) * factor)
            writer.writerow(r)
    return left_out


def coverage(tools, sequence_dir, result_dir, loop_poses):
    """(metric loops, loops inside the 95 % ellipsoid) as bowg_pose_graph counts them."""
    command = [os.path.join(tools, "bowg_pose_graph"),
               "--truth", os.path.join(sequence_dir, "poses.csv"),
               "--odometry", os.path.join(sequence_dir, "odometry.csv"),
               "--loops", os.path.join(result_dir, "detections_configured.csv"),
               "--loop-poses", loop_poses,
               "--output", os.path.join(os.path.dirname(loop_poses), "graph")]
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True)
    if done.returncode != 0:
        fail("%s failed:\n%s" % (" ".join(command), done.stdout))
    loops = re.search(r"metric loops\s*: (\d+) of", done.stdout)
    inside = re.search(r"ellipsoid: ([0-9.]+) %", done.stdout)
    if not loops or not inside:
        fail("no coverage in the output of %s:\n%s" % (" ".join(command), done.stdout))
    n = int(loops.group(1))
    return n, round(float(inside.group(1)) / 100.0 * n)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--sequences", required=True, help="the suite's rendered sequences")
    p.add_argument("--tools", required=True, help="folder with bowg_evaluate and bowg_pose_graph")
    p.add_argument("--config", required=True)
    p.add_argument("--vocabulary", required=True)
    p.add_argument("--output", required=True, help="detections per sequence (reused)")
    p.add_argument("--list", default=os.path.join(here, "robustness_suite.txt"))
    p.add_argument("--half", default="tuning")
    p.add_argument("--detected-scale", type=float, default=1.0,
                   help="the metric_covariance_scale of --config")
    p.add_argument("--scales", default="1,1.5,2,3,4,6,8")
    p.add_argument("--csv")
    a = p.parse_args()
    scales = [float(s) for s in a.scales.split(",")]
    totals = {s: [0, 0] for s in scales}
    table = []
    chosen = sequences_of(a.list, a.sequences, a.half)
    if not chosen:
        fail("no rendered sequence of the %s half in %s" % (a.half, a.sequences))
    with tempfile.TemporaryDirectory() as scratch:
        for name, rate in chosen:
            result = detect(a, name, rate)
            sequence = os.path.join(a.sequences, name)
            for s in scales:
                copy = os.path.join(scratch, "loop_poses.csv")
                left_out = scaled_copy(os.path.join(result, "loop_poses_configured.csv"),
                                       s / a.detected_scale, copy)
                n, inside = coverage(a.tools, sequence, result, copy)
                n += left_out  # counted as outside: the honest share is not flattered
                totals[s][0] += n
                totals[s][1] += inside
                table.append((name, s, n, inside))
    print("%s half (%s): truth inside the 95 %% ellipsoid by factor on the covariance"
          % (a.half, ", ".join(n for n, _ in chosen)))
    print("%-8s %8s %8s %8s" % ("factor", "loops", "inside", "share"))
    for s in scales:
        n, inside = totals[s]
        print("%-8g %8d %8d %8.3f" % (s, n, inside, inside / n if n else float("nan")))
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["sequence", "factor", "metric_loops", "inside_95"])
            w.writerows(table)


if __name__ == "__main__":
    main()
