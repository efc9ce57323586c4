#!/usr/bin/env bash
# The re-inspection suite: a second survey of a pipe network recognised
# against the first, for the pairs of tools/suite/reinspection_suite.txt
# (renders cached), with the configured method at the preset's own threshold
# (what the nodelet publishes) in every input mode a robot may have: the
# odometry's positions and odometer ("positions"), an odometer alone
# ("odometer", metres driven: a cable counter), and no odometry at all
# ("images"). The figure is the loops across missions (a second-survey query
# closing into the first survey): their precision, recall, true and false
# loops and the queries that have a true match there ("positives").
#   kind "same":  both surveys in one folder (bowg_generate_pipe_sequence
#                 --again), one bowg_evaluate run with --missions.
#   kind "other": two different networks of the same textures: A is run and
#                 saved as a map (--save-map), B is run against it (--map);
#                 B has no place of A, so every loop into the map is false.
# Prints per pair and mode the cross-mission figure and all loops at the
# threshold, then the median cross-mission recall per half and mode; writes
# reinspection.csv (tools/suite/reinspection_report.py).
#   ./scripts/reinspection_suite.sh                             # every pair
#   BOWG_REINSPECTION_HALF=tuning ./scripts/reinspection_suite.sh  # the tuning half
# Environment: BOWG_WS (workspace), BOWG_REINSPECTION_DIR (outputs, default
# <repo>/output/reinspection), BOWG_REINSPECTION_HALF (tuning, test or all),
# BOWG_REINSPECTION_ONLY (regular expression on pair names),
# BOWG_REINSPECTION_MODES (default positions,odometer,images),
# BOWG_REINSPECTION_LIST (another pair list, same format), BOWG_SHARED_DATA
# (default <repo>/../shared/data), BOWG_TOOLS_DIR (the built tools, default
# <workspace>/devel/lib/bowg_ros), BOWG_SKIP_BUILD=1, BOWG_SKIP_DEPS=1.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"
out="${BOWG_REINSPECTION_DIR:-$repo/output/reinspection}"
shared="${BOWG_SHARED_DATA:-$repo/../shared/data}"
half="${BOWG_REINSPECTION_HALF:-all}"
modes="${BOWG_REINSPECTION_MODES:-positions,odometer,images}"
# The preset's own threshold is what is reported; the sweep around it is kept
# in each run's summary.txt and pr_curves.csv.
config="$repo/config/pipe.yaml"
thresholds="0.6,0.8,1,1.2,1.4,1.7,2,2.5"
vocabulary="$repo/data/default_vocabulary.bowgvoc"
list="${BOWG_REINSPECTION_LIST:-$repo/tools/suite/reinspection_suite.txt}"
[ -r "$list" ] || { echo "reinspection: cannot read the pair list $list" >&2; exit 2; }
export PATH="/usr/bin:$PATH"
start=$(date +%s)
source "$repo/scripts/suite_lib.sh"
suite_check_inputs BOWG_REINSPECTION_HALF "$half" BOWG_REINSPECTION_MODES "$modes"
suite_prepare reinspection_build

# evaluate RESULT DIR RATE ARGS...: one bowg_evaluate run of the configured
# method into RESULT (log next to it).
evaluate() {
  local result="$1" dir="$2" r="$3"
  shift 3
  mkdir -p "$result"
  "$tools/bowg_evaluate" --images "$dir" --rate "$r" --vocabulary "$vocabulary" \
    --config "$config" --rows configured --thresholds "$thresholds" --quiet \
    --output "$result" "$@" >"$result.log" 2>&1 ||
    { tail -n 20 "$result.log" >&2; exit 1; }
}

ran=()
while IFS= read -r line; do
  case "$line" in ''|'#'*) continue ;; esac
  IFS='|' read -r name pair_half kind args <<<"$line"
  name="$(trim "$name")"; pair_half="$(trim "$pair_half")"; kind="$(trim "$kind")"
  [ "$half" = all ] || [ "$half" = "$pair_half" ] || continue
  [ -z "${BOWG_REINSPECTION_ONLY:-}" ] || [[ "$name" =~ $BOWG_REINSPECTION_ONLY ]] || continue
  echo "== $name ($pair_half, $kind)"
  seq_dir="$out/sequences/$name"
  case "$kind" in
    same)
      args="$(trim "$args")"
      render "$seq_dir" "$args" 10 "frames|ground truth|missions" || { echo "-- $name: skipped, needs $shared (absent)"; continue; }
      for mode in "${mode_list[@]}"; do
        mode_inputs "$seq_dir" "$mode"
        t0=$(date +%s)
        result="$out/results/$name/$mode"
        evaluate "$result" "$seq_dir" "$rate" --gt "$seq_dir/ground_truth.txt" \
          --missions "$seq_dir/missions.csv" "${inputs[@]}"
        echo "   $mode: $(sed -n '/^across missions/,/^$/p' "$result/summary.txt" | grep '^configured' | tr -s ' ') ($(( $(date +%s) - t0 )) s)"
        ran+=("$name:$pair_half:$kind:$mode")
      done
      ;;
    other)
      args_a="$(trim "${args%%||*}")"; args_b="$(trim "${args#*||}")"
      if [ "$args_a" = "$args" ]; then echo "reinspection: $name: 'other' needs two argument sets (A || B)" >&2; exit 2; fi
      render "$seq_dir/A" "$args_a" 10 "frames|ground truth|missions" || { echo "-- $name: skipped, needs $shared (absent)"; continue; }
      rate_a="$rate"
      render "$seq_dir/B" "$args_b" 10 "frames|ground truth|missions" || { echo "-- $name: skipped, needs $shared (absent)"; continue; }
      for mode in "${mode_list[@]}"; do
        t0=$(date +%s)
        result="$out/results/$name/$mode"
        # The map: network A's survey in the same mode, saved as the detector
        # file of its (only) row.
        mode_inputs "$seq_dir/A" "$mode"
        evaluate "$result/A" "$seq_dir/A" "$rate_a" --gt "$seq_dir/A/ground_truth.txt" \
          "${inputs[@]}" --save-map "$result/A.map"
        # Network B against it: B's ground truth has no frame of A, so every
        # loop into the map is false; B's own revisits are scored as usual.
        # (B's odometer starts at 0 again: bowg_evaluate continues it from
        # the map's, as the nodelet does after a load.)
        mode_inputs "$seq_dir/B" "$mode"
        evaluate "$result" "$seq_dir/B" "$rate" --gt "$seq_dir/B/ground_truth.txt" \
          "${inputs[@]}" --map "$result/A.map"
        echo "   $mode: $(sed -n '/^across missions/,/^$/p' "$result/summary.txt" | grep '^configured' | tr -s ' ') ($(( $(date +%s) - t0 )) s)"
        ran+=("$name:$pair_half:$kind:$mode")
      done
      ;;
    *) echo "reinspection: $name: unknown kind '$kind' (same, other)" >&2; exit 2 ;;
  esac
done <"$list"

[ ${#ran[@]} -gt 0 ] || { echo "reinspection: no pair run" >&2; exit 1; }
/usr/bin/python3 "$repo/tools/suite/reinspection_report.py" --results "$out/results" \
  --csv "$out/reinspection.csv" "${ran[@]}"
echo "reinspection suite done in $(( $(date +%s) - start )) s; table: $out/reinspection.csv"
