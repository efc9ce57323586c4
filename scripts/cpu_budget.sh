#!/usr/bin/env bash
# A robot's CPU budget: per-keyframe milliseconds (feature extraction +
# detection) of each preset on the same rendered pipe images, and the share
# of one core their CPU time (OpenCV's worker threads included) takes at 5,
# 10 and 25 keyframes a second (README, "CPU budget"). Rounds alternate the presets, each run alone (--jobs 1) with
# odometer and positions, at the preset's own min_score.
#   ./scripts/cpu_budget.sh
# Environment: BOWG_BUDGET_ROUNDS (default 3), BOWG_BUDGET_PRESETS (files of
# config/, default pipe,pipe_gftt,generic), BOWG_BUDGET_SEQUENCE (a suite
# sequence, default fig8_varspeed_5cm: the peer comparison's),
# BOWG_BUDGET_DIR (outputs, default <repo>/output/cpu_budget), BOWG_WS,
# BOWG_SKIP_BUILD=1, BOWG_SKIP_DEPS=1.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# shellcheck source=suite_lib.sh
source "$repo/scripts/suite_lib.sh"
ws="${BOWG_WS:-$repo/.ws}"
rounds="${BOWG_BUDGET_ROUNDS:-3}"
presets="${BOWG_BUDGET_PRESETS:-pipe,pipe_gftt,generic}"
sequence="${BOWG_BUDGET_SEQUENCE:-fig8_varspeed_5cm}"
out="${BOWG_BUDGET_DIR:-$repo/output/cpu_budget}"
vocabulary="$repo/data/default_vocabulary.bowgvoc"
export PATH="/usr/bin:$PATH"

case "$rounds" in '' | *[!0-9]* | 0) echo "BOWG_BUDGET_ROUNDS must be a positive integer" >&2; exit 2 ;; esac
IFS=',' read -ra names <<<"$presets"
for p in "${names[@]}"; do
  [ -f "$repo/config/$p.yaml" ] || { echo "cpu_budget: no preset config/$p.yaml" >&2; exit 2; }
done
if [ "${BOWG_SKIP_DEPS:-0}" != 1 ]; then "$repo/scripts/install_deps.sh"; fi
if [ "${BOWG_SKIP_BUILD:-0}" != 1 ]; then
  log="${TMPDIR:-/tmp}/bowg_cpu_budget_build.log"
  echo "== build (log $log)"
  BOWG_WS="$ws" "$repo/scripts/build.sh" bowg_generate_pipe_sequence bowg_evaluate >"$log" 2>&1 ||
    { tail -n 40 "$log" >&2; echo "cpu_budget: build failed" >&2; exit 1; }
fi
tools="$ws/devel/lib/bowg_ros"
mkdir -p "$out/runs"

# The sequence, rendered (and cached) by the robustness suite.
BOWG_WS="$ws" BOWG_SKIP_DEPS=1 BOWG_SKIP_BUILD=1 BOWG_SUITE_ONLY="^$sequence\$" \
  BOWG_SUITE_RENDER_ONLY=1 BOWG_SUITE_DIR="$out/suite" "$repo/scripts/robustness_suite.sh" \
  >"$out/suite.log"
seq_dir="$out/suite/sequences/$sequence"
[ -s "$seq_dir/ground_truth.txt" ] || { echo "cpu_budget: no sequence $sequence" >&2; exit 1; }
rate="$(sed -n 's/.*--rate \([0-9.]*\).*/\1/p' "$seq_dir/generator.stamp")"

runs=()
echo "== $sequence: $rounds rounds of ${names[*]}"
for i in $(seq 1 "$rounds"); do
  for p in "${names[@]}"; do
    config="$repo/config/$p.yaml"
    min_score="$(preset_min_score "$config")"
    "$tools/bowg_evaluate" --images "$seq_dir" --rate "$rate" --gt "$seq_dir/ground_truth.txt" \
      --odometry "$seq_dir/odometry.csv" --odometry-poses "$seq_dir/odometry.csv" \
      --vocabulary "$vocabulary" --config "$config" --thresholds "$min_score" --jobs 1 --quiet \
      --output "$out/runs/${p}_$i" >"$out/runs_${p}_$i.log" 2>&1 ||
      { tail -n 20 "$out/runs_${p}_$i.log" >&2; exit 1; }
    runs+=("$p:$out/runs/${p}_$i")
  done
done
/usr/bin/python3 "$repo/tools/bench/cpu_budget.py" --csv "$out/cpu_budget.csv" "${runs[@]}"
