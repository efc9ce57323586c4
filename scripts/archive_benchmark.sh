#!/usr/bin/env bash
# A network's archive as the reference map (docs/benchmarks.md, "Archive of
# 10^6 keyframes as a reference map"): builds bowg_archive_bench (Release,
# standalone engine build), writes a map of N synthetic keyframes once, then
# loads it in fresh processes and times live keyframes against it. Prints
# query time per keyframe, memory per keyframe of the loaded map and the load
# time against their targets. Not run by CI or any test: the full size takes
# tens of GB of disk and most of the machine's RAM.
#
#   scripts/archive_benchmark.sh [KEYFRAMES] [OUT_DIR]
#     KEYFRAMES  map size (default 1000000: 40 km of pipe at 4 cm)
#     OUT_DIR    where the map and the outputs go (default /tmp/bowg_archive;
#                the map file is ~42 kB a keyframe, and its descriptors take
#                16 kB a keyframe of scratch space while it is built)
#   BOWG_ARCHIVE_BUILD  build directory (default <repo>/.ws/bench, run_benchmarks.sh's)
#   BOWG_ARCHIVE_LOADS  fresh-process loads and timings (default 2)
#   BOWG_JOBS           make jobs (default 1)
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
keyframes="${1:-1000000}"
out="${2:-/tmp/bowg_archive}"
build="${BOWG_ARCHIVE_BUILD:-$repo/.ws/bench}"
loads="${BOWG_ARCHIVE_LOADS:-2}"
mkdir -p "$out"

# The map file (~84 bytes a feature, ~500 features a keyframe) and the
# descriptors' scratch file beside it while it is built (32 bytes a feature).
need_mb=$((keyframes * 60 / 1000))
free_mb=$(df -Pm "$out" | awk 'NR == 2 {print $4}')
if [ "$free_mb" -lt "$need_mb" ]; then
  echo "archive_benchmark: ~$need_mb MB needed in $out, $free_mb MB free" >&2
  exit 1
fi

cmake -S "$repo/engine" -B "$build" -DCMAKE_BUILD_TYPE=Release -DBOWG_ENGINE_TESTS=OFF \
  -DBOWG_ENGINE_BENCHMARKS=ON > "$out/cmake.log"
make -C "$build" -j"${BOWG_JOBS:-1}" bowg_archive_bench > "$out/make.log"
bench="$build/bowg_archive_bench"
# The map file is larger than a robot's database is allowed by default.
export BOWG_MAX_DATABASE_MB=$((need_mb * 2 + 1024))

echo "== build: $keyframes keyframes into $out/archive.bowgdb"
/usr/bin/time -f "build_wall_s %e" "$bench" build --keyframes "$keyframes" --dir "$out" 2>&1 |
  tee "$out/build.txt"
for i in $(seq "$loads"); do
  echo "== fresh process $i: load, memory, live keyframes"
  "$bench" query --dir "$out" | tee "$out/query_$i.txt"
done

echo "== against the targets ($keyframes keyframes; loads and timings: median of $loads)"
python3 - "$out" "$loads" <<'EOF'
import statistics, sys
out, loads = sys.argv[1], int(sys.argv[2])
def read(path):
    figures = {}
    with open(path) as f:
        for line in f:
            parts = line.split()
            try:
                figures[parts[0]] = float(parts[1])
            except (IndexError, ValueError):
                pass  # progress lines
    return figures
runs = [read(f"{out}/query_{i}.txt") for i in range(1, loads + 1)]
build = read(f"{out}/build.txt")
def med(key): return statistics.median(r[key] for r in runs)
rows = [
    ("query per live keyframe, mean", "<= 5 ms", f"{med('query_mean_ms'):.2f} ms", med('query_mean_ms') <= 5),
    ("query per live keyframe, max", "-", f"{med('query_max_ms'):.2f} ms", None),
    ("memoryBytes() / size of the loaded map", "<= 12,000 bytes",
     f"{med('memory_bytes_per_keyframe'):,.0f} bytes", med('memory_bytes_per_keyframe') <= 12000),
    ("resident set growth over the load, per keyframe", "<= 12,000 bytes",
     f"{med('rss_growth_per_keyframe'):,.0f} bytes", med('rss_growth_per_keyframe') <= 12000),
    ("load in a fresh process", "<= 10 s", f"{med('load_s'):.2f} s", med('load_s') <= 10),
]
print(f"| figure | target | measured | met |\n|---|---|---|---|")
for name, target, value, met in rows:
    print(f"| {name} | {target} | {value} | {'-' if met is None else 'yes' if met else 'no'} |")
r = runs[0]
print(f"map: {build['keyframes']:.0f} keyframes, {build['features_per_keyframe']:.1f} features a keyframe, "
      f"file {build['file_bytes'] / 1e9:.2f} GB ({build['file_bytes'] / build['keyframes']:,.0f} bytes a keyframe)")
print("memoryBytes() per keyframe: " + ", ".join(
    f"{k.replace('_bytes_per_keyframe', '')} {r[k]:,.0f}" for k in
    ["descriptor_bytes_per_keyframe", "word_bytes_per_keyframe", "point_bytes_per_keyframe",
     "entry_record_bytes_per_keyframe", "group_table_bytes_per_keyframe",
     "distribution_and_odometer_bytes_per_keyframe", "inverse_index_bytes_per_keyframe"]))
print(f"stages (first run), ms: transform {r['transform_ms']:.2f}, word groups {r['word_groups_ms']:.2f}, "
      f"query {r['query_stage_ms']:.2f}, islands {r['islands_ms']:.2f}, verification {r['verification_ms']:.2f}; "
      f"candidates {r['candidates']:.0f}, loops {r['loops']:.0%}")
print(f"peak resident set: build {build['build_peak_rss_bytes'] / 2**30:.2f} GiB, "
      f"load {r['load_peak_rss_bytes'] / 2**30:.2f} GiB")
EOF
