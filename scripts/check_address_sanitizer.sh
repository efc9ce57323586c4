#!/usr/bin/env bash
# The ROS layer and the tools under AddressSanitizer and UBSan: builds the
# ROS layer's plain gtests (test/*_test.cpp, no master) and the tools'
# end-to-end tests (tools/apps/test, which run the instrumented tools) with
# -fsanitize=address,undefined (CMake option BOWG_SANITIZE) in a workspace of
# their own (<workspace>/asan_ros, RelWithDebInfo at -O1: the tests' run time
# stays close to a release build's), then runs them. Any sanitizer report, a
# leak included, fails its test. The engine's own gtests under ASan are
# scripts/test.sh's (engine/ built alone).
#   scripts/check_address_sanitizer.sh        (scripts/test.sh runs it)
# Prints "asan: <test> ok (<n> tests)" per test program and a count; exits
# non-zero when one fails.
# Not run here: bowg_tools_bag_agreement_test (a played bag through the
# nodelet, ~5 min in a release build); bowg_tools_robustness_suite_test (it
# passes, but takes ~5 min instrumented against ~1 min, and runs the
# evaluator and the generator that evaluate_cli and generate_pipe_sequence
# run); bowg_tools_startup_test (it loads the nodelet into Debian's nodelet
# manager, which is not instrumented: the ASan runtime cannot enter it
# unless preloaded, as scripts/check_thread_sanitizer.sh does for TSan); and
# the tests of scripts and Python helpers only (peer_ratios, cpu_budget,
# benchmark_table, install_deps: nothing instrumented runs in them).
# Environment: BOWG_WS (workspace; the ASan one is its asan_ros/ folder),
# BOWG_JOBS (build jobs).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"
asan_ws="$ws/asan_ros"
export PATH="/usr/bin:$PATH"

ros_tests=(bounded_queue cfg_matches_table debug_image image_conversion keyframe_gate
  keyframe_thumbnails live_parameters parameter_docs ros_conversions)
tool_tests=(vocabulary_tools evaluate_cli generate_pipe_sequence pose_graph_cli)
targets=()
for t in "${ros_tests[@]}"; do targets+=("bowg_ros_${t}_test"); done
for t in "${tool_tests[@]}"; do targets+=("bowg_tools_${t}_test"); done

start=$SECONDS
echo "-- build with -fsanitize=address,undefined in $asan_ws (log: $asan_ws.log)"
mkdir -p "$asan_ws"
if ! BOWG_WS="$asan_ws" BOWG_BUILD_TYPE=RelWithDebInfo bash "$repo/scripts/build.sh" \
  -DBOWG_SANITIZE=ON -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" "${targets[@]}" \
  > "$asan_ws.log" 2>&1; then
  tail -n 40 "$asan_ws.log" >&2
  echo "check_address_sanitizer: FAIL: the AddressSanitizer build failed" >&2
  exit 1
fi
echo "   built in $(( (SECONDS - start) / 60 )) min $(( (SECONDS - start) % 60 )) s"

# catkin's environment hooks read unset variables.
set +u
# shellcheck disable=SC1091
source "$asan_ws/devel/setup.bash"
set -u
logs="$asan_ws/logs"
mkdir -p "$logs"
# halt_on_error: the first report ends the program with an error status, so a
# report in a tool run by an end-to-end test fails that test too.
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:abort_on_error=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export ROS_LOG_DIR="$logs/ros_log"

run_start=$SECONDS
ok=0
failed=0
for target in "${targets[@]}"; do
  bin="$asan_ws/devel/lib/bowg_ros/$target"
  if [ ! -x "$bin" ]; then
    echo "asan: $target FAILED (not built: $bin)"
    failed=$((failed + 1))
    continue
  fi
  if "$bin" --gtest_brief=1 > "$logs/$target.log" 2>&1; then
    n=$(sed -nE 's/^\[  PASSED  \] ([0-9]+) tests?.*/\1/p' "$logs/$target.log" | tail -n 1)
    echo "asan: $target ok (${n:-0} tests)"
    ok=$((ok + 1))
  else
    echo "asan: $target FAILED (log: $logs/$target.log)"
    grep -E "ERROR: (Address|Leak)Sanitizer|runtime error:|FAILED" "$logs/$target.log" | head -n 20
    tail -n 30 "$logs/$target.log"
    failed=$((failed + 1))
  fi
done
echo "asan: ROS layer and tools: $ok ok, $failed failed (tests ran in $(( SECONDS - run_start )) s)"
[ "$failed" -eq 0 ]
