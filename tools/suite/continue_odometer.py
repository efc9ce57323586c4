#!/usr/bin/env python3
"""Writes a survey's odometer continued after an earlier survey's.

A detector keeps one odometer that never decreases; a saved map ends at the
earlier survey's metres, and a new survey's odometer starts at 0. As a robot
that adds its cable counter's total to the map's, the odometer of LATER (the
path length of its odometry file's x,y,z, as bowg_evaluate --odometry reads
it) is written after the path length of EARLIER's plus 1 m (the drive from
one network to the other; the map keeps its last odometer to more digits
than the CSV has, so an equal first value could read as a decrease), as
frame,odometer.

usage: continue_odometer.py EARLIER_ODOMETRY_CSV LATER_ODOMETRY_CSV OUT_CSV
"""
import csv
import math
import os
import sys


def path_lengths(path):
    """(frame, metres driven up to it) per row of a frame,x,y,z CSV."""
    out, total, last = [], 0.0, None
    with open(path) as f:
        for row in csv.DictReader(f):
            p = (float(row["x"]), float(row["y"]), float(row["z"]))
            if last is not None:
                total += math.dist(p, last)
            out.append((int(row["frame"]), total))
            last = p
    return out


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__.strip().splitlines()[-1])
    earlier, later, target = sys.argv[1:]
    offset = path_lengths(earlier)[-1][1] + 1.0
    tmp = target + ".tmp"
    with open(tmp, "w") as f:
        f.write("frame,odometer\n")
        for frame, metres in path_lengths(later):
            f.write("%d,%.6f\n" % (frame, offset + metres))
    os.replace(tmp, target)


if __name__ == "__main__":
    main()
