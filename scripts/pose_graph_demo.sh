#!/usr/bin/env bash
# The pose-graph example on a rendered pipe network (docs/pose_graph.md):
# renders a sequence with drifting odometry (the suite's fig8_varspeed_5cm:
# the T-junction network, speed changing between passes), runs the detector
# on it (config/pipe.yaml, the default vocabulary, the drifting odometry's
# metres driven), then bowg_pose_graph, and prints the trajectory error
# without and with the loops (at the match's place; metric where measured),
# the metric translations' error, with a plot.
#   ./scripts/pose_graph_demo.sh            # outputs in <repo>/output/pose_graph
# Environment: BOWG_WS (workspace), BOWG_JOBS, BOWG_SKIP_DEPS=1,
# BOWG_SKIP_BUILD=1 with BOWG_TOOLS_DIR (prebuilt tools), BOWG_POSE_GRAPH_DIR
# (outputs), BOWG_POSE_GRAPH_ARGS (generator options instead of the default
# sequence's), BOWG_CLEAN_FRAMES=1 (remove the rendered frames at the end).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"
out="${BOWG_POSE_GRAPH_DIR:-$repo/output/pose_graph}"
args="${BOWG_POSE_GRAPH_ARGS:---seed 12 --rate 4 --speed-variation 0.7 --marks-per-metre 8}"
export PATH="/usr/bin:$PATH"
start=$(date +%s)

if [ "${BOWG_SKIP_DEPS:-0}" != 1 ]; then
  echo "== dependencies (scripts/install_deps.sh)"
  "$repo/scripts/install_deps.sh"
fi
if [ "${BOWG_SKIP_BUILD:-0}" != 1 ]; then
  # The log inside the workspace: one per checkout.
  log="$ws/logs/pose_graph_build.log"
  echo "== build (workspace $ws; log $log)"
  BOWG_WS="$ws" BOWG_BUILD_LOG="$log" \
    "$repo/scripts/build.sh" bowg_generate_pipe_sequence bowg_evaluate bowg_pose_graph
fi
tools="${BOWG_TOOLS_DIR:-$ws/devel/lib/bowg_ros}"

rm -rf "$out"; mkdir -p "$out"
echo "== render ($args)"
read -ra argv <<<"$args"
"$tools/bowg_generate_pipe_sequence" --images "$out/sequence" --gt "$out/ground_truth.txt" \
  "${argv[@]}" >"$out/generate.log" 2>&1 || { tail -n 20 "$out/generate.log" >&2; exit 1; }
grep -E '^(ground truth|odometry):' "$out/generate.log" | sed 's/ ->.*//; s/^/   /' || true
rate=2
for i in "${!argv[@]}"; do [ "${argv[$i]}" != --rate ] || rate="${argv[$((i + 1))]}"; done

# The detector sees what a robot has: the drifting odometry's metres driven
# (odometry.csv, with its slip) and the camera's intrinsics, so that loops
# get a metric translation.
echo "== detect (bowg_evaluate, config/pipe.yaml)"
"$tools/bowg_evaluate" --images "$out/sequence" --rate "$rate" --gt "$out/ground_truth.txt" \
  --odometry "$out/sequence/odometry.csv" --odometry-poses "$out/sequence/odometry.csv" \
  --intrinsics "$out/sequence/intrinsics.csv" \
  --vocabulary "$repo/data/default_vocabulary.bowgvoc" --config "$repo/config/pipe.yaml" \
  --rows configured --quiet --output "$out/detection" \
  >"$out/detection.log" 2>&1 || { tail -n 20 "$out/detection.log" >&2; exit 1; }
sed -n '/^row /,/^$/p' "$out/detection/summary.txt" | sed '/^$/d; s/^/   /'

echo "== pose graph, every loop at the match's place (bowg_pose_graph)"
"$tools/bowg_pose_graph" --truth "$out/sequence/poses.csv" --odometry "$out/sequence/odometry.csv" \
  --loops "$out/detection/detections_configured.csv" --output "$out/graph_same_place" |
  grep -v '^outputs' | sed 's/^/   /'
echo "== pose graph, metric loops where the detector measured them (--loop-poses)"
"$tools/bowg_pose_graph" --truth "$out/sequence/poses.csv" --odometry "$out/sequence/odometry.csv" \
  --loops "$out/detection/detections_configured.csv" \
  --loop-poses "$out/detection/loop_poses_configured.csv" --output "$out/graph" | sed 's/^/   /'
echo
# The rendered frames are needed only by the detection above.
size="$(du -sh "$out/sequence" 2>/dev/null | cut -f1)"
if [ "${BOWG_CLEAN_FRAMES:-0}" = 1 ]; then
  find "$out/sequence" -name 'frame_*.png' -delete
  echo "frames: removed from $out/sequence (${size:-0}; BOWG_CLEAN_FRAMES=1)"
else
  echo "frames: $out/sequence/frame_*.png, ${size:-0} on disk (BOWG_CLEAN_FRAMES=1 removes them)"
fi
echo "pose-graph demo done in $(( $(date +%s) - start )) s; plot: $out/graph/trajectories.png"
