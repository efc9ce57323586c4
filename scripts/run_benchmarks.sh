#!/usr/bin/env bash
# Builds the engine's Google Benchmark programs (Release, standalone engine
# build) and runs them; results go to stdout and to OUT_DIR (default
# output/benchmarks). Where the peer kit is present (../shared/peer, or
# BOWG_PEER_KIT), scripts/peer_benchmark.sh runs too (BOWG_BENCH_PEER=0 skips
# it). Ends with one table of every figure against its target
# (tools/bench/benchmark_table.py; also OUT_DIR/targets.csv).
# docs/benchmarks.md records a run of this script.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BOWG_BENCH_BUILD:-$repo/.ws/bench}"
out="${OUT_DIR:-$repo/output/benchmarks}"
mkdir -p "$out"
bash "$repo/scripts/install_deps.sh"
cmake -S "$repo/engine" -B "$build" -DCMAKE_BUILD_TYPE=Release -DBOWG_ENGINE_TESTS=OFF \
  -DBOWG_ENGINE_BENCHMARKS=ON > "$out/cmake.log"
make -C "$build" -j"${BOWG_JOBS:-$(nproc)}" bowg_features_bench bowg_vocabulary_bench bowg_normaliser_history_bench \
  bowg_pipeline_bench bowg_verification_bench bowg_word_groups_bench bowg_vocabulary_load_once_bench \
  bowg_orb_stages_bench > "$out/make.log"
for b in features vocabulary normaliser_history verification word_groups pipeline; do
  echo "== bowg_${b}_bench"
  "$build/bowg_${b}_bench" --benchmark_out="$out/${b}.json" --benchmark_out_format=json \
    "$@" | tee "$out/${b}.txt"
done

# The k=10 L=6 vocabulary loaded in fresh processes (a node's start-up):
# median of 11 against the 50 ms target.
echo "== bowg_vocabulary_load_once_bench (11 fresh processes)"
voc="$(mktemp --suffix=.bowgvoc)"
trap 'rm -f "$voc"' EXIT
"$build/bowg_vocabulary_load_once_bench" --make-k10l6 "$voc"
for i in $(seq 11); do "$build/bowg_vocabulary_load_once_bench" "$voc"; done | tee "$out/vocabulary_load_once.txt" |
  sort -n | awk '{ms[NR] = $1} END {printf "median %.1f ms, min %.1f, max %.1f (target <= 50 ms)\n", ms[6], ms[1], ms[NR]}'

peer_args=()
kit="${BOWG_PEER_KIT:-$repo/../shared/peer}"
if [ "${BOWG_BENCH_PEER:-1}" != 0 ] && [ -x "$kit/peer.sh" ]; then
  echo "== scripts/peer_benchmark.sh"
  BOWG_SKIP_DEPS=1 BOWG_PEER_KIT="$kit" BOWG_PEER_DIR="$out/peer" "$repo/scripts/peer_benchmark.sh"
  peer_args=(--peer "$out/peer/peer_ratios.csv")
elif [ "${BOWG_BENCH_PEER:-1}" != 0 ]; then
  echo "== no peer kit at $kit: the table has no DLoopDetector rows"
fi

# Where OpenCV's ORB spends the preset's FAST threshold 10 against the
# peer's 20, on the peer comparison's rendered circuit where it ran (the
# features rows above), else on a synthetic texture.
circuit="$out/peer/suite/sequences/circuit_15cm_roll30"
echo "== bowg_orb_stages_bench ($( [ -d "$circuit" ] && echo "$circuit" || echo "synthetic texture"))"
if [ -d "$circuit" ]; then export BOWG_BENCH_IMAGES="$circuit"; fi
"$build/bowg_orb_stages_bench" --benchmark_out="$out/orb_stages.json" --benchmark_out_format=json \
  "$@" | tee "$out/orb_stages.txt"
unset BOWG_BENCH_IMAGES

echo "== every figure against its target"
/usr/bin/python3 "$repo/tools/bench/benchmark_table.py" --features "$out/features.json" \
  --pipeline "$out/pipeline.json" --loads "$out/vocabulary_load_once.txt" "${peer_args[@]}" \
  --csv "$out/targets.csv"
