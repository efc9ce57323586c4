#!/usr/bin/env bash
# Detection and feature time against the reference peer, DLoopDetector over
# DBoW2 (../shared/peer), on the same images with the same vocabulary, in one
# run: timing rounds alternate peer and ours, each at its operating point and
# alone on the machine, and the table gives the median over the rounds of the
# per-round ratio ours / peer (mean and max per keyframe), beside the target.
#   ./scripts/peer_benchmark.sh
# docs/benchmarks.md ("Against DLoopDetector") records a run.
# Environment: BOWG_PEER_KIT (default <repo>/../shared/peer), BOWG_PEER_ROUNDS
# (default 5), BOWG_PEER_SEQUENCES (suite sequences, default
# fig8_varspeed_5cm,circuit_15cm_roll30), BOWG_PEER_ALPHA (DLoopDetector's
# alpha, default its 0.3), BOWG_PEER_DIR (outputs, default
# <repo>/output/peer), BOWG_WS, BOWG_SKIP_BUILD=1, BOWG_SKIP_DEPS=1.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"
kit="${BOWG_PEER_KIT:-$repo/../shared/peer}"
rounds="${BOWG_PEER_ROUNDS:-5}"
sequences="${BOWG_PEER_SEQUENCES:-fig8_varspeed_5cm,circuit_15cm_roll30}"
alpha="${BOWG_PEER_ALPHA:-0.3}"
out="${BOWG_PEER_DIR:-$repo/output/peer}"
config="$repo/config/pipe.yaml"
# Ours at the preset's own threshold only: one run per round, no sweep.
# shellcheck source=suite_lib.sh
source "$repo/scripts/suite_lib.sh"
min_score="$(preset_min_score "$config")"
vocabulary="$repo/data/default_vocabulary.bowgvoc"
export PATH="/usr/bin:$PATH"

if [ ! -x "$kit/peer.sh" ]; then
  echo "peer_benchmark: the peer kit is absent ($kit/peer.sh); set BOWG_PEER_KIT" >&2
  exit 2
fi
case "$rounds" in '' | *[!0-9]* | 0) echo "BOWG_PEER_ROUNDS must be a positive integer" >&2; exit 2 ;; esac
if [ "${BOWG_SKIP_DEPS:-0}" != 1 ]; then "$repo/scripts/install_deps.sh"; fi
if [ "${BOWG_SKIP_BUILD:-0}" != 1 ]; then
  echo "== build (log ${TMPDIR:-/tmp}/bowg_peer_build.log)"
  BOWG_WS="$ws" "$repo/scripts/build.sh" bowg_generate_pipe_sequence bowg_evaluate \
    bowg_convert_vocabulary >"${TMPDIR:-/tmp}/bowg_peer_build.log" 2>&1 ||
    { tail -n 40 "${TMPDIR:-/tmp}/bowg_peer_build.log" >&2; echo "peer_benchmark: build failed" >&2; exit 1; }
  "$kit/peer.sh" build "$ws/peer"
fi
tools="$ws/devel/lib/bowg_ros"
mkdir -p "$out"

# The peer reads DBoW2's YAML: the same tree and weights, converted.
peer_vocabulary="$out/vocabulary_dbow2.yml.gz"
"$tools/bowg_convert_vocabulary" "$vocabulary" "$peer_vocabulary" >"$out/convert.log"

# The sequences, rendered (and cached) by the robustness suite.
only="^($(echo "$sequences" | tr ',' '|'))\$"
BOWG_WS="$ws" BOWG_SKIP_DEPS=1 BOWG_SKIP_BUILD=1 BOWG_SUITE_ONLY="$only" BOWG_SUITE_RENDER_ONLY=1 \
  BOWG_SUITE_DIR="$out/suite" "$repo/scripts/robustness_suite.sh" >"$out/suite.log"

pairs=()
IFS=',' read -ra names <<<"$sequences"
for name in "${names[@]}"; do
  seq_dir="$out/suite/sequences/$name"
  [ -s "$seq_dir/ground_truth.txt" ] || { echo "peer_benchmark: no sequence $name" >&2; exit 1; }
  rate="$(sed -n 's/.*--rate \([0-9.]*\).*/\1/p' "$seq_dir/generator.stamp")"
  # DLoopDetector's candidates: frames at least the ground truth's smallest
  # query-match gap older than the query (its --dislocal, in frames).
  gap="$(awk -F'[:,]' '!/^#/ && NF > 1 { for (i = 2; i <= NF; ++i) if ($i != "" && (m == "" || $1 - $i < m)) m = $1 - $i }
                      END { print (m == "" ? 30 : m) }' "$seq_dir/ground_truth.txt")"
  echo "== $name: $rounds rounds, DLoopDetector alpha $alpha dislocal $gap, ours $config (min_score $min_score)"
  for i in $(seq 1 "$rounds"); do
    "$kit/peer.sh" run --images "$seq_dir" --gt "$seq_dir/ground_truth.txt" \
      --vocabulary "$peer_vocabulary" --alphas "$alpha" --dislocal "$gap" \
      --build "$ws/peer" --out "$out/runs/$name/peer_$i" >"$out/runs_$name.peer_$i.log" 2>&1 ||
      { tail -n 20 "$out/runs_$name.peer_$i.log" >&2; exit 1; }
    "$tools/bowg_evaluate" --images "$seq_dir" --rate "$rate" --gt "$seq_dir/ground_truth.txt" \
      --odometry "$seq_dir/poses.csv" --odometry-poses "$seq_dir/odometry.csv" \
      --vocabulary "$vocabulary" --config "$config" \
      --thresholds "$min_score" --jobs 1 --quiet --output "$out/runs/$name/ours_$i" >/dev/null
    pairs+=("$name:$out/runs/$name/peer_$i:$out/runs/$name/ours_$i")
  done
done
/usr/bin/python3 "$repo/tools/bench/peer_ratios.py" --csv "$out/peer_ratios.csv" "${pairs[@]}"
