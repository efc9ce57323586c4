#!/usr/bin/env bash
# The robustness suite (docs/evaluation.md, "Robustness suite"): renders the
# sequences of tools/suite/robustness_suite.txt (cached) and runs pure bag of
# words, the paper's method as written and the configured method over each,
# in every input mode a robot may have: the odometry's positions and odometer
# ("positions"), an odometer alone ("odometer", metres driven: a cable
# counter), and no odometry at all ("images"). Prints one table: per
# sequence, mode and row the precision, recall and false loops at the
# preset's own threshold (what the nodelet publishes) and the recall at
# 100 % precision of the exact PR sweep, then the minimum and median per
# half, mode and row; writes suite.csv and suite.png; then the last row's
# recall by the revisits' distance to the earlier pass's nearest keyframe
# (tools/suite/revisit_offsets.py, revisit_offsets.csv, positions mode).
#   ./scripts/robustness_suite.sh                       # every sequence
#   BOWG_SUITE_HALF=tuning ./scripts/robustness_suite.sh  # only the tuning half
#   BOWG_SUITE_QUICK=1 ./scripts/robustness_suite.sh      # README command 1's subset
# Environment: BOWG_WS (workspace), BOWG_SUITE_DIR (outputs, default
# <repo>/output/suite), BOWG_SUITE_HALF (tuning, test or all), BOWG_SUITE_QUICK,
# BOWG_SUITE_ONLY (regular expression on sequence names), BOWG_SUITE_CONFIG
# (default config/pipe.yaml), BOWG_SUITE_ROWS (default paper_bow,paper,configured),
# BOWG_SUITE_MODES (default positions,odometer,images), BOWG_SUITE_THRESHOLDS
# (min_score values of the sweep), BOWG_SHARED_DATA
# (default <repo>/../shared/data), BOWG_SUITE_LIST (another sequence list, same
# format), BOWG_TOOLS_DIR (the built tools, default <workspace>/devel/lib/bowg_ros),
# BOWG_SUITE_RENDER_ONLY=1 (render the selected sequences into
# <BOWG_SUITE_DIR>/sequences, evaluate nothing: the benchmarks' inputs),
# BOWG_SKIP_BUILD=1, BOWG_SKIP_DEPS=1.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"
out="${BOWG_SUITE_DIR:-$repo/output/suite}"
shared="${BOWG_SHARED_DATA:-$repo/../shared/data}"
half="${BOWG_SUITE_HALF:-all}"
config="${BOWG_SUITE_CONFIG:-$repo/config/pipe.yaml}"
rows="${BOWG_SUITE_ROWS:-paper_bow,paper,configured}"
modes="${BOWG_SUITE_MODES:-positions,odometer,images}"
thresholds="${BOWG_SUITE_THRESHOLDS:-0.6,0.8,1,1.2,1.4,1.7,2,2.5}"
vocabulary="$repo/data/default_vocabulary.bowgvoc"
list="${BOWG_SUITE_LIST:-$repo/tools/suite/robustness_suite.txt}"
[ -r "$list" ] || { echo "suite: cannot read the sequence list $list" >&2; exit 2; }
export PATH="/usr/bin:$PATH"
start=$(date +%s)
source "$repo/scripts/suite_lib.sh"
suite_check_inputs BOWG_SUITE_HALF "$half" BOWG_SUITE_MODES "$modes"
suite_prepare suite_build

ran=()
rendered=()
render_only="${BOWG_SUITE_RENDER_ONLY:-0}"
while IFS= read -r line; do
  case "$line" in ''|'#'*) continue ;; esac
  IFS='|' read -r name seq_half quick source args <<<"$line"
  name="$(trim "$name")"; seq_half="$(trim "$seq_half")"; quick="$(trim "$quick")"
  source="$(trim "$source")"; args="$(trim "$args")"
  [ "$half" = all ] || [ "$half" = "$seq_half" ] || continue
  [ "${BOWG_SUITE_QUICK:-0}" != 1 ] || [ "$quick" = yes ] || continue
  [ -z "${BOWG_SUITE_ONLY:-}" ] || [[ "$name" =~ $BOWG_SUITE_ONLY ]] || continue
  seq_dir="$out/sequences/$name"
  if [ "$source" = render ]; then
    render "$seq_dir" "$args" 2 "render|ground truth" || { echo "-- $name: skipped, needs $shared (absent)"; continue; }
    if [ "$render_only" = 1 ]; then rendered+=("$seq_dir"); continue; fi
    images="$seq_dir"
    seq_modes=("${mode_list[@]}")
  else
    if [ "$render_only" = 1 ]; then continue; fi  # real frames: nothing to render
    read -r folder gt_spec <<<"$args"
    if [ ! -d "$shared/$folder" ]; then echo "-- $name: skipped, $shared/$folder is absent"; continue; fi
    images="$shared/$folder"; rate=1; gt=()
    [ "$gt_spec" = none ] || gt=(--gt "$repo/$gt_spec")
    # Real frames come without odometry: images only.
    seq_modes=(images)
  fi
  for mode in "${seq_modes[@]}"; do
    [[ ",$modes," == *",$mode,"* ]] || continue
    if [ "$source" = render ]; then
      mode_inputs "$seq_dir" "$mode"
      inputs+=(--gt "$seq_dir/ground_truth.txt")
    else
      inputs=("${gt[@]}")
    fi
    echo "== $name ($seq_half, $mode): bowg_evaluate --rows $rows"
    t0=$(date +%s)
    result="$out/results/$name/$mode"
    mkdir -p "$result"
    "$tools/bowg_evaluate" --images "$images" --rate "$rate" "${inputs[@]}" --vocabulary "$vocabulary" \
      --config "$config" --rows "$rows" --thresholds "$thresholds" --quiet \
      --output "$result" >"$result.log" 2>&1 ||
      { tail -n 20 "$result.log" >&2; exit 1; }
    # Its result table (one line per row) as it comes, not only at the end.
    sed -n '/^row /,/^$/p' "$result/summary.txt" | sed '/^$/d; s/^/   /'
    echo "   ($(( $(date +%s) - t0 )) s)"
    ran+=("$name:$seq_half:$mode")
  done
done <"$list"

if [ "$render_only" = 1 ]; then
  [ ${#rendered[@]} -gt 0 ] || { echo "suite: no rendered sequence selected" >&2; exit 1; }
  printf 'rendered: %s\n' "${rendered[@]}"
  exit 0
fi
[ ${#ran[@]} -gt 0 ] || { echo "suite: no sequence selected" >&2; exit 1; }
/usr/bin/python3 "$repo/tools/suite/suite_report.py" --results "$out/results" --rows "$rows" \
  --csv "$out/suite.csv" --plot "$out/suite.png" "${ran[@]}"
# Where recall is lost: revisit queries by their distance to the earlier
# pass's nearest keyframe of the same place (rendered sequences, last row,
# the first mode run).
last_row="${rows##*,}"
names=()
for item in "${ran[@]}"; do
  [ "${item##*:}" = "${mode_list[0]}" ] && names+=("${item%%:*}")
done
if [ ${#names[@]} -gt 0 ]; then
  /usr/bin/python3 "$repo/tools/suite/revisit_offsets.py" --suite "$out" --row "$last_row" \
    --mode "${mode_list[0]}" --csv "$out/revisit_offsets.csv" "${names[@]}" ||
    echo "suite: no revisit offsets (see above)"
fi
echo "suite done in $(( $(date +%s) - start )) s; table: $out/suite.csv, plot: $out/suite.png"
