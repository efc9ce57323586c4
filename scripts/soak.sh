#!/usr/bin/env bash
# The long run: a 17,565-keyframe in-pipe sequence (the paper's largest run;
# a circuit driven ~50 times, 4 cm spacing, speed varying) through
# bowg_evaluate with config/pipe.yaml, for time per keyframe and memory
# against the database size (docs/benchmarks.md, "Long run").
#   ./scripts/soak.sh              # outputs in <repo>/output/soak (~3 GB of frames)
# Environment: BOWG_WS, BOWG_SKIP_DEPS=1, BOWG_SKIP_BUILD=1, BOWG_SOAK_DIR,
# BOWG_SOAK_FRAMES (default 17565).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"
out="${BOWG_SOAK_DIR:-$repo/output/soak}"
frames="${BOWG_SOAK_FRAMES:-17565}"
export PATH="/usr/bin:$PATH"
start=$(date +%s)

if [ "${BOWG_SKIP_DEPS:-0}" != 1 ]; then "$repo/scripts/install_deps.sh"; fi
if [ "${BOWG_SKIP_BUILD:-0}" != 1 ]; then
  echo "== build (workspace $ws; log ${TMPDIR:-/tmp}/bowg_soak_build.log)"
  BOWG_WS="$ws" BOWG_BUILD_LOG="${TMPDIR:-/tmp}/bowg_soak_build.log" \
    "$repo/scripts/build.sh" bowg_generate_pipe_sequence bowg_evaluate
fi
tools="$ws/devel/lib/bowg_ros"
args=(--seed 28 --route circuit --laps 60 --rate 5 --speed-variation 0.4 --marks-per-metre 8
  --frames "$frames")
seq="$out/sequence"
stamp="$(sha256sum "$tools/bowg_generate_pipe_sequence" | cut -d' ' -f1) ${args[*]}"
if [ ! -s "$seq/ground_truth.txt" ] || [ "$(cat "$seq/generator.stamp" 2>/dev/null)" != "$stamp" ]; then
  echo "== render ${args[*]} (cached in $seq)"
  rm -rf "$seq"; mkdir -p "$seq"
  "$tools/bowg_generate_pipe_sequence" --images "$seq" --gt "$seq/ground_truth.txt" "${args[@]}" \
    >"$out/generate.log" 2>&1 || { tail -n 20 "$out/generate.log" >&2; exit 1; }
  echo "$stamp" >"$seq/generator.stamp"
fi
echo "== bowg_evaluate (config/pipe.yaml, one run)"
"$tools/bowg_evaluate" --images "$seq" --rate 5 --gt "$seq/ground_truth.txt" \
  --odometry "$seq/poses.csv" --odometry-poses "$seq/odometry.csv" --vocabulary "$repo/data/default_vocabulary.bowgvoc" \
  --config "$repo/config/pipe.yaml" --rows configured --quiet --output "$out/evaluation" \
  >"$out/evaluation.log" 2>&1 || { tail -n 20 "$out/evaluation.log" >&2; exit 1; }
sed -n '/^row /,/^$/p; /^detector time vs/,/^$/p; /^memory growth/,/^$/p' \
  "$out/evaluation/summary.txt"
echo "soak done in $(( $(date +%s) - start )) s; per 1000 keyframes: " \
  "$out/evaluation/memory_vs_database_size.csv, $out/evaluation/time_vs_database_size.csv"
