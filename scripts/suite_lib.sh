# Sourced by scripts/robustness_suite.sh and scripts/reinspection_suite.sh:
# what both suites do before and around their runs. Expects `repo`, `ws`,
# `out` and `shared` set by the suite. The benchmarks that run a preset at its
# own threshold (peer_benchmark.sh, cpu_budget.sh) source it for
# preset_min_score only.

# preset_min_score CONFIG: the min_score CONFIG sets (what the detector
# applies with odometry); exits 1 naming the file when it sets none.
preset_min_score() {
  local value
  value="$(awk '$1 == "min_score:" { print $2 }' "$1")"
  [ -n "$value" ] || { echo "no min_score in $1" >&2; exit 1; }
  echo "$value"
}

# trim S: S without leading and trailing white space.
trim() { local s="$1"; s="${s#"${s%%[![:space:]]*}"}"; echo "${s%"${s##*[![:space:]]}"}"; }

# suite_check_inputs HALF_VAR HALF MODES_VAR MODES: refuses (exit 2, naming
# the variable) a half other than tuning, test or all and an unknown input
# mode; sets `mode_list`.
suite_check_inputs() {
  local half_var="$1" half_value="$2" modes_var="$3" modes_value="$4" m
  case "$half_value" in tuning|test|all) ;;
    *) echo "$half_var must be tuning, test or all" >&2; exit 2 ;;
  esac
  IFS=',' read -ra mode_list <<<"$modes_value"
  for m in "${mode_list[@]}"; do
    case "$m" in positions|odometer|images) ;;
      *) echo "$modes_var: unknown mode '$m' (positions, odometer, images)" >&2; exit 2 ;;
    esac
  done
}

# suite_prepare LOG_NAME: installs and builds the generator and the evaluator
# (unless BOWG_SKIP_DEPS / BOWG_SKIP_BUILD; the build log is
# <workspace>/logs/LOG_NAME.log, one per checkout); sets `tools` and
# `generator_hash` (renders are cached per generator binary) and makes the
# output folders.
suite_prepare() {
  local log="$ws/logs/$1.log"
  if [ "${BOWG_SKIP_DEPS:-0}" != 1 ]; then "$repo/scripts/install_deps.sh"; fi
  if [ "${BOWG_SKIP_BUILD:-0}" != 1 ]; then
    echo "== build (scripts/build.sh, workspace $ws; log $log)"
    BOWG_WS="$ws" BOWG_BUILD_LOG="$log" \
      "$repo/scripts/build.sh" bowg_generate_pipe_sequence bowg_evaluate
  fi
  tools="${BOWG_TOOLS_DIR:-$ws/devel/lib/bowg_ros}"
  generator_hash="$(sha256sum "$tools/bowg_generate_pipe_sequence" | cut -d' ' -f1)"
  mkdir -p "$out/sequences" "$out/results"
}

# render DIR ARGS DEFAULT_RATE SUMMARY_KEYS: renders the generator arguments
# ARGS into DIR unless DIR holds a render of the same generator binary and
# arguments (its stamp), then prints the generator's closing lines that
# start with SUMMARY_KEYS (a regular expression) and the render's time. Sets
# `rate` (ARGS' --rate, else DEFAULT_RATE). Returns 1 when ARGS need the
# shared data (--texture-images, named relative to it) and it is absent.
render() {
  local dir="$1" args="$2" keys="$4" i stamp t0
  local -a argv
  read -ra argv <<<"$args"
  for i in "${!argv[@]}"; do
    if [ "${argv[$i]}" = --texture-images ]; then
      [ -d "$shared" ] || return 1
      argv[$((i + 1))]="$shared/${argv[$((i + 1))]}"
    fi
  done
  rate="$3"
  for i in "${!argv[@]}"; do [ "${argv[$i]}" != --rate ] || rate="${argv[$((i + 1))]}"; done
  stamp="$generator_hash ${argv[*]}"
  if [ -s "$dir/ground_truth.txt" ] && [ "$(cat "$dir/generator.stamp" 2>/dev/null)" = "$stamp" ]; then
    return 0
  fi
  echo "   render $dir ($args)"
  rm -rf "$dir"; mkdir -p "$dir"
  t0=$(date +%s)
  "$tools/bowg_generate_pipe_sequence" --images "$dir" --gt "$dir/ground_truth.txt" \
    "${argv[@]}" >"$dir/generate.log" 2>&1 || { tail -n 20 "$dir/generate.log" >&2; exit 1; }
  echo "$stamp" >"$dir/generator.stamp"
  echo "   $(grep -E "^($keys):" "$dir/generate.log" | sed 's/ ->.*//' | paste -sd ';' - | sed 's/;/; /g') ($(( $(date +%s) - t0 )) s)"
}

# mode_inputs DIR MODE: sets `inputs`, what the robot's odometry gives in
# MODE, all from the generator's drifting odometry.csv (slip, slip noise,
# heading drift): its path length as the odometer (the windows in metres,
# recent_exclusion_m), its dead-reckoned positions for the odometry gates
# (odometry_gate_m); nothing with images only.
mode_inputs() {
  local dir="$1" mode="$2"
  inputs=()
  case "$mode" in
    positions) inputs=(--odometry "$dir/odometry.csv" --odometry-poses "$dir/odometry.csv") ;;
    odometer) inputs=(--odometry "$dir/odometry.csv") ;;
  esac
}
