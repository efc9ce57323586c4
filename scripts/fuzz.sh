#!/usr/bin/env bash
# Fuzzes every file loader with clang's libFuzzer under ASan/UBSan:
# vocabularies (all seven formats), the database file, the BRIEF pattern, the
# configuration file and the ground truth; and the image decoding path and
# the keyframe_features input (fuzz/, docs/fuzzing.md).
#   scripts/fuzz.sh [seconds per target, default 60]
# Seeds are written by the project's own writers (bowg_fuzz_seeds). A target
# fails on a crash, a sanitizer report, an exception outside the documented
# error types, an input slower than 10 s (a hang) or more than 2 GB of
# memory; the input that did it is kept in <build>/findings/<target>/.
# Environment: BOWG_FUZZ_DIR (build and corpora, default <repo>/.ws/fuzz),
# BOWG_FUZZ_TARGETS (default: all seven), BOWG_FUZZ_RUNS (a number of inputs
# per target instead of a time: the long runs of docs/fuzzing.md),
# BOWG_SKIP_DEPS=1.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:$PATH"
seconds="${1:-60}"
dir="${BOWG_FUZZ_DIR:-$repo/.ws/fuzz}"
all_targets="vocabulary database brief_pattern config ground_truth image features_message"
targets="${BOWG_FUZZ_TARGETS:-$all_targets}"
case "$seconds" in ''|*[!0-9]*) echo "fuzz.sh: seconds must be a whole number" >&2; exit 2 ;; esac
if [ "${BOWG_SKIP_DEPS:-0}" != 1 ]; then bash "$repo/scripts/install_deps.sh"; fi

mkdir -p "$dir"
echo "== fuzz: build (clang, libFuzzer, ASan/UBSan; log $dir/build.log)"
CC=clang CXX=clang++ cmake -S "$repo/fuzz" -B "$dir/build" > "$dir/build.log" 2>&1 \
  || { tail -n 30 "$dir/build.log"; exit 1; }
make -C "$dir/build" -j"${BOWG_JOBS:-$(nproc)}" >> "$dir/build.log" 2>&1 \
  || { tail -n 40 "$dir/build.log"; exit 1; }
rm -rf "$dir/seeds"
"$dir/build/bowg_fuzz_seeds" "$dir/seeds"

limit=(-max_total_time="$seconds")
if [ -n "${BOWG_FUZZ_RUNS:-}" ]; then limit=(-runs="$BOWG_FUZZ_RUNS" -max_total_time=0); fi
failed=0
# The longest input a target is given: images are real camera frames of a
# few MB (the header check must hold for them too); the rest are small.
max_len() {
  case "$1" in
    image) echo 4194304 ;;
    *) echo 65536 ;;
  esac
}
for t in $targets; do
  corpus="$dir/corpus/$t"
  findings="$dir/findings/$t"
  mkdir -p "$corpus" "$findings"
  # -timeout: one input over 10 s is a hang; -rss_limit_mb: memory bound;
  # detect_leaks=0: a loader that throws mid-way is judged by ASan's other
  # checks (leaks are checked by the ASan gtests of scripts/test.sh).
  if ASAN_OPTIONS=detect_leaks=0 "$dir/build/bowg_${t}_fuzz" "$corpus" "$dir/seeds/$t" \
      "${limit[@]}" -timeout=10 -rss_limit_mb=2048 -max_len="$(max_len "$t")" \
      -artifact_prefix="$findings/" -print_final_stats=1 > "$dir/$t.log" 2>&1; then
    runs=$(sed -nE 's/^stat::number_of_executed_units: *([0-9]+).*/\1/p' "$dir/$t.log" | tail -n 1)
    took=$(sed -nE 's/^stat::.*//; s/^Done ([0-9]+) runs in ([0-9]+) second.*/\2/p' "$dir/$t.log" | tail -n 1)
    echo "fuzz: $t ok (${runs:-?} inputs in ${took:-$seconds} s)"
  else
    echo "fuzz: $t FAILED (log $dir/$t.log, input in $findings/)"
    grep -E "ERROR|SUMMARY|terminate|what\(\)" "$dir/$t.log" | head -n 10 || true
    failed=$((failed + 1))
  fi
done
[ "$failed" -eq 0 ] || { echo "fuzz: $failed target(s) failed" >&2; exit 1; }
