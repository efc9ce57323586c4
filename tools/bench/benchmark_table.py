#!/usr/bin/env python3
"""Every speed and memory figure against its target, from one run of scripts/run_benchmarks.sh.

Reads the Google Benchmark JSON of bowg_features_bench and bowg_pipeline_bench,
the fresh-process vocabulary loads (one time in ms per line), and optionally
the ratios against DLoopDetector of scripts/peer_benchmark.sh (its CSV). Prints
one Markdown table (figure, target, measured, ratio, met) and writes it as CSV.
Ratios, not absolute times, where two things are compared: both sides of a
ratio come from the same run of the same machine.

usage: benchmark_table.py --features F.json --pipeline P.json --loads L.txt
                          [--peer peer_ratios.csv] [--csv FILE]
"""
import argparse
import csv
import json
import statistics
import sys

sys.dont_write_bytecode = True  # no __pycache__ beside the sources
from csv_rows import write_rows_atomically  # noqa: E402 (after the line above)


def fail(message):
    sys.exit("benchmark_table: " + message)


def read_benchmarks(path):
    """{name without the iteration suffix: benchmark record} of one JSON output."""
    try:
        with open(path) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        fail("cannot read %s: %s" % (path, e))
    out = {}
    for b in data.get("benchmarks", []):
        name = b.get("run_name", b.get("name", ""))
        out[name.split("/iterations:")[0]] = b
    return out


def field(benchmarks, path, name, key):
    if name not in benchmarks:
        fail("%s: no benchmark %s" % (path, name))
    if key not in benchmarks[name]:
        fail("%s: benchmark %s has no %s" % (path, name, key))
    return float(benchmarks[name][key])


def ms(record_value, unit):
    return record_value * {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[unit]


def cpu_ms(benchmarks, path, name):
    return ms(field(benchmarks, path, name, "cpu_time"), benchmarks[name].get("time_unit", "ns"))


def row(figure, target, measured, ratio, met):
    return {"figure": figure, "target": target, "measured": measured,
            "ratio": "" if ratio is None else "%.2f" % ratio,
            "met": "-" if met is None else "yes" if met else "no"}


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--features", required=True)
    ap.add_argument("--pipeline", required=True)
    ap.add_argument("--loads", required=True)
    ap.add_argument("--peer")
    ap.add_argument("--csv")
    args = ap.parse_args(argv)
    rows = []

    f = read_benchmarks(args.features)
    gftt = cpu_ms(f, args.features, "BM_GfttOrientedOrb")
    orb = cpu_ms(f, args.features, "BM_OrbMultiScaleOriented")
    ratio = gftt / orb
    rows.append(row("pipe features (GFTT + oriented descriptors) / OpenCV ORB-500, CPU per image",
                    "<= 1 (goal 0.5)", "%.2f / %.2f ms (%d / %d features)" % (
                        gftt, orb, field(f, args.features, "BM_GfttOrientedOrb", "features"),
                        field(f, args.features, "BM_OrbMultiScaleOriented", "features")),
                    ratio, ratio <= 1.0))

    p = read_benchmarks(args.pipeline)
    # The scale targets on the trained case with the pipe preset's place
    # index: both sizes time revisits (engine/bench/pipeline_bench.cpp).
    trained = "BM_PipelineTrained/%d/3"
    mean_1k = field(p, args.pipeline, trained % 1000, "total_mean")
    mean_20k = field(p, args.pipeline, trained % 20000, "total_mean")
    max_20k = field(p, args.pipeline, trained % 20000, "total_max")
    case = "trained vocabulary, 3 keyframes a place indexed"
    rows.append(row("per-keyframe pipeline after features, 20,000 keyframes (%s), mean" % case,
                    "< 5 ms", "%.2f ms" % mean_20k, None, mean_20k < 5.0))
    rows.append(row("same, max", "< 15 ms", "%.2f ms" % max_20k, None, max_20k < 15.0))
    growth = mean_20k / mean_1k
    rows.append(row("time per keyframe, 20,000 / 1,000 keyframes (%s)" % case, "<= 1.5",
                    "%.2f / %.2f ms" % (mean_20k, mean_1k), growth, growth <= 1.5))
    # The stress case, without a target: a random vocabulary, every keyframe
    # indexed, and no revisit among the first 1,000 keyframes.
    stress_1k = field(p, args.pipeline, "BM_Pipeline/1000", "total_mean")
    stress_20k = field(p, args.pipeline, "BM_Pipeline/20000", "total_mean")
    rows.append(row("stress case: time per keyframe, 20,000 / 1,000 keyframes (random "
                    "vocabulary, every keyframe indexed, no revisit at 1,000)", "-",
                    "%.2f / %.2f ms" % (stress_20k, stress_1k), stress_20k / stress_1k, None))
    m = "BM_Memory500Features"
    rss = field(p, args.pipeline, m, "rss_growth_per_keyframe")
    estimate = field(p, args.pipeline, m, "estimate_growth_per_keyframe")
    features = field(p, args.pipeline, m, "features")
    rows.append(row("resident set growth per keyframe, ~500 features (3,000 -> 6,000 keyframes)",
                    "<= 25,000 bytes", "%.0f bytes (%.1f features)" % (rss, features),
                    rss / 25000.0, rss <= 25000.0))
    error = estimate / rss - 1.0 if rss > 0 else float("inf")
    rows.append(row("memoryBytes() growth against the resident set growth", "within 5 %",
                    "%.0f / %.0f bytes (%+.1f %%)" % (estimate, rss, 100.0 * error), None,
                    abs(error) <= 0.05))

    try:
        with open(args.loads) as fh:
            loads = [float(line.split()[0]) for line in fh if line.strip()]
    except (OSError, ValueError, IndexError) as e:
        fail("cannot read the load times in %s: %s" % (args.loads, e))
    if not loads:
        fail("%s: no load times" % args.loads)
    median = statistics.median(loads)
    rows.append(row("k=10 L=6 vocabulary load in a fresh process, median of %d" % len(loads),
                    "<= 50 ms", "%.1f ms (min %.1f, max %.1f)" % (median, min(loads), max(loads)),
                    None, median <= 50.0))

    if args.peer:
        try:
            with open(args.peer, newline="") as fh:
                peer = list(csv.DictReader(fh))
        except OSError as e:
            fail("cannot read %s: %s" % (args.peer, e))
        for r in peer:
            if not r.get("ratio"):
                continue  # the loops row: no target
            try:
                value = float(r["ratio"])
                rows.append(row("%s, %s: ours / DLoopDetector (median of %s rounds)" % (
                    r["sequence"], r["measure"], r["rounds"]), r["target"],
                    "%.2f / %.2f ms" % (float(r["ours"]), float(r["peer"])), value,
                    r["met"] == "yes"))
            except (KeyError, ValueError) as e:
                fail("%s: bad row %s (%s)" % (args.peer, r, e))

    print("| figure | target | measured | ratio | met |")
    print("|---|---|---|---|---|")
    for r in rows:
        print("| %s | %s | %s | %s | %s |" % (r["figure"], r["target"], r["measured"], r["ratio"],
                                             r["met"]))
    if args.csv:
        write_rows_atomically(args.csv, rows)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
