#!/usr/bin/env bash
# README command 1: install, build, then the quick subset of the robustness
# suite (docs/evaluation.md, "Robustness suite"): in-pipe sequences the
# preset was never tuned on (other speeds, spacings, rolls, a wall quilted
# from real sewer frames, a route without revisits) and the real sewer frames,
# each run through pure bag of words, the paper's BoWG as written and
# config/pipe.yaml; prints the table (recall at 100 % precision, false loops).
#   ./scripts/demo.sh                   # workspace <repo>/.ws, outputs in <repo>/output/demo
#   BOWG_WS=/tmp/ws ./scripts/demo.sh   # another catkin workspace
# Environment: BOWG_WS (workspace), BOWG_JOBS (build jobs, default nproc),
# BOWG_DEMO_DIR (outputs, default <repo>/output/demo), BOWG_SKIP_DEPS=1 (do
# not run install_deps.sh), BOWG_DEMO_THRESHOLDS (min_score values of the
# exact PR sweep), BOWG_CLEAN_FRAMES=1 (remove the rendered frames at the
# end). The whole suite, the README's table: scripts/robustness_suite.sh.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"
out="${BOWG_DEMO_DIR:-$repo/output/demo}"
export PATH="/usr/bin:$PATH"
start=$(date +%s)

if [ "${BOWG_SKIP_DEPS:-0}" != 1 ]; then
  echo "== 1/3 dependencies (scripts/install_deps.sh)"
  "$repo/scripts/install_deps.sh"
fi

# The log inside the workspace: one per checkout, not one /tmp file that
# every checkout's demo overwrites.
log="$ws/logs/demo_build.log"
echo "== 2/3 build (scripts/build.sh, workspace $ws; log $log)"
BOWG_WS="$ws" BOWG_BUILD_LOG="$log" \
  "$repo/scripts/build.sh" bowg_generate_pipe_sequence bowg_evaluate
echo "   built in $(( $(date +%s) - start )) s"

echo "== 3/3 robustness suite, quick subset (scripts/robustness_suite.sh, outputs in $out)"
if [ -n "${BOWG_DEMO_THRESHOLDS:-}" ]; then export BOWG_SUITE_THRESHOLDS="$BOWG_DEMO_THRESHOLDS"; fi
BOWG_WS="$ws" BOWG_SKIP_DEPS=1 BOWG_SKIP_BUILD=1 BOWG_SUITE_QUICK=1 BOWG_SUITE_DIR="$out" \
  "$repo/scripts/robustness_suite.sh"

# Which numbers these are: the quick subset's, not the README's table.
list="$repo/tools/suite/robustness_suite.txt"
quick_names="$(awk -F'|' '!/^[[:space:]]*(#|$)/ { gsub(/[[:space:]]/, "", $1); gsub(/[[:space:]]/, "", $3);
  n++; if ($3 == "yes") { q++; names = names (q > 1 ? ", " : "") $1 } }
  END { printf "%d of the %d sequences (%s)", q, n, names }' "$list")"
echo
echo "These numbers are the quick subset's: $quick_names, marked 'yes' in"
echo "tools/suite/robustness_suite.txt. The README's table (min and median over the whole test"
echo "half) comes from every sequence: ./scripts/robustness_suite.sh (much longer)."

# The rendered frames stay as the suite's cache (a rerun skips rendering),
# unless asked to go: say where they are and what they take.
frames="$out/sequences"
size="$(du -sh "$frames" 2>/dev/null | cut -f1)"
if [ "${BOWG_CLEAN_FRAMES:-0}" = 1 ]; then
  rm -rf "$frames"
  echo "frames:    $frames removed (${size:-0}; BOWG_CLEAN_FRAMES=1)"
else
  echo "frames:    $frames/<sequence>/frame_*.png, ${size:-0} on disk, kept so that a rerun"
  echo "           skips rendering (BOWG_CLEAN_FRAMES=1 removes them at the end)"
fi
echo "demo done in $(( $(date +%s) - start )) s"
echo "table:     $out/suite.csv (plot $out/suite.png)"
echo "per run:   $out/results/<sequence>/summary.txt, pr_curve.png, keyframes_<row>.csv"
