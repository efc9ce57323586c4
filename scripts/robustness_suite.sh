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
case "$half" in tuning|test|all) ;; *) echo "BOWG_SUITE_HALF must be tuning, test or all" >&2; exit 2 ;; esac
IFS=',' read -ra mode_list <<<"$modes"
for m in "${mode_list[@]}"; do
  case "$m" in positions|odometer|images) ;;
    *) echo "BOWG_SUITE_MODES: unknown mode '$m' (positions, odometer, images)" >&2; exit 2 ;;
  esac
done

if [ "${BOWG_SKIP_DEPS:-0}" != 1 ]; then "$repo/scripts/install_deps.sh"; fi
if [ "${BOWG_SKIP_BUILD:-0}" != 1 ]; then
  # The log inside the workspace: one per checkout.
  log="$ws/logs/suite_build.log"
  echo "== build (scripts/build.sh, workspace $ws; log $log)"
  BOWG_WS="$ws" BOWG_BUILD_LOG="$log" \
    "$repo/scripts/build.sh" bowg_generate_pipe_sequence bowg_evaluate
fi
tools="${BOWG_TOOLS_DIR:-$ws/devel/lib/bowg_ros}"
generator_hash="$(sha256sum "$tools/bowg_generate_pipe_sequence" | cut -d' ' -f1)"
mkdir -p "$out/sequences" "$out/results"
trim() { local s="$1"; s="${s#"${s%%[![:space:]]*}"}"; echo "${s%"${s##*[![:space:]]}"}"; }

ran=()
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
    # Shared texture folders are named relative to the shared data folder.
    read -ra argv <<<"$args"
    for i in "${!argv[@]}"; do
      if [ "${argv[$i]}" = --texture-images ]; then argv[$((i + 1))]="$shared/${argv[$((i + 1))]}"; fi
    done
    if [[ " $args " == *" --texture-images "* ]] && [ ! -d "$shared" ]; then
      echo "-- $name: skipped, needs $shared (absent)"; continue
    fi
    rate=2
    for i in "${!argv[@]}"; do [ "${argv[$i]}" != --rate ] || rate="${argv[$((i + 1))]}"; done
    stamp="$generator_hash ${argv[*]}"
    if [ ! -s "$seq_dir/ground_truth.txt" ] || [ "$(cat "$seq_dir/generator.stamp" 2>/dev/null)" != "$stamp" ]; then
      echo "== $name: render ($args)"
      rm -rf "$seq_dir"; mkdir -p "$seq_dir"
      t0=$(date +%s)
      "$tools/bowg_generate_pipe_sequence" --images "$seq_dir" --gt "$seq_dir/ground_truth.txt" \
        "${argv[@]}" >"$seq_dir/generate.log" 2>&1 || { tail -n 20 "$seq_dir/generate.log" >&2; exit 1; }
      echo "$stamp" >"$seq_dir/generator.stamp"
      # The generator's closing summary (render time, revisits).
      echo "   $(grep -E '^(render|ground truth):' "$seq_dir/generate.log" | sed 's/ ->.*//' | paste -sd ';' - | sed 's/;/; /g') ($(( $(date +%s) - t0 )) s)"
    fi
    # What the robot's odometry gives in each mode, all from the generator's
    # drifting odometry.csv (slip, slip noise, heading drift): its path length
    # as the odometer (the windows in metres, recent_exclusion_m) and its
    # dead-reckoned positions (the odometry gates, odometry_gate_m).
    images="$seq_dir"
    seq_modes=("${mode_list[@]}")
  else
    read -r folder gt_spec <<<"$args"
    if [ ! -d "$shared/$folder" ]; then echo "-- $name: skipped, $shared/$folder is absent"; continue; fi
    images="$shared/$folder"; rate=1; gt=()
    [ "$gt_spec" = none ] || gt=(--gt "$repo/$gt_spec")
    # Real frames come without odometry: images only.
    seq_modes=(images)
  fi
  for mode in "${seq_modes[@]}"; do
    [[ ",$modes," == *",$mode,"* ]] || continue
    inputs=()
    if [ "$source" = render ]; then
      inputs=(--gt "$seq_dir/ground_truth.txt")
      case "$mode" in
        positions) inputs+=(--odometry "$seq_dir/odometry.csv" --odometry-poses "$seq_dir/odometry.csv") ;;
        odometer) inputs+=(--odometry "$seq_dir/odometry.csv") ;;
      esac
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
