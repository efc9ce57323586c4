#!/usr/bin/env bash
# The nodelet under ThreadSanitizer: builds the engine, the ROS layer and the
# nodelet with -fsanitize=thread (CMake option BOWG_THREAD_SANITIZER) in a
# workspace of their own (<workspace>/tsan), then runs the rostests that
# exercise the nodelet's threads (live tuning, persistence, and services
# called while the worker processes images: test/concurrency.test) with the
# nodelet manager under the ThreadSanitizer runtime. Debian's nodelet manager
# is not instrumented, so the runtime is preloaded into it (the .test files'
# manager_prefix); an instrumented nodelet library cannot load into a process
# without it, so a passing test ran instrumented.
#
# Verdict (test/tsan/tsan_reports.py says exactly how): every race at an access
# of the project's code and every lock-order cycle through a mutex the
# project's code takes fails the check and is printed. Reports of ROS's own
# libraries (not instrumented: their atomics are invisible, so their
# reference counting and internal lock order are reported, also where the
# project's code calls them) are counted and kept, not failed on.
#   scripts/check_thread_sanitizer.sh        (scripts/test.sh runs it)
# Environment: BOWG_WS (workspace; the TSan one is its tsan/ folder),
# BOWG_JOBS (build jobs).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"
tsan_ws="$ws/tsan"
export PATH="/usr/bin:$PATH"
fail() {
  echo "check_thread_sanitizer: FAIL: $*" >&2
  exit 1
}

runtime="$(readlink -f "$(g++ -print-file-name=libtsan.so)")"
[ -f "$runtime" ] || fail "no ThreadSanitizer runtime (libtsan) for g++: install libgcc-12-dev"

# The sorter first, on test/tsan/sample_reports.txt: a race in the engine and
# a lock-order cycle through the nodelet's mutexes are the project's; a
# reference-count release and roscpp's own lock order, both with the
# nodelet's code further down the stack, and roscpp sending a service
# response its serialization template (instantiated for the project's
# service type) allocated on another thread, are ROS's.
sorted_sample="$(python3 "$repo/test/tsan/tsan_reports.py" /nonexistent /nonexistent /dev/null /dev/null \
  "$repo/test/tsan/sample_reports.txt")"
[ "$sorted_sample" = "2 3" ] || fail "test/tsan/tsan_reports.py sorts the sample reports as '$sorted_sample', not '2 3'"

echo "-- build with -fsanitize=thread in $tsan_ws (log: $tsan_ws.log)"
mkdir -p "$tsan_ws"
if ! BOWG_WS="$tsan_ws" BOWG_BUILD_TYPE=RelWithDebInfo bash "$repo/scripts/build.sh" \
  -DBOWG_THREAD_SANITIZER=ON bowg_ros_nodelet bowg_ros_rostest > "$tsan_ws.log" 2>&1; then
  tail -n 40 "$tsan_ws.log" >&2
  fail "the ThreadSanitizer build failed"
fi

reports="$tsan_ws/reports"
rm -rf "$reports"
mkdir -p "$reports"
# catkin's environment hooks read unset variables.
set +u
# shellcheck disable=SC1091
source "$tsan_ws/devel/setup.bash"
set -u
export ROS_LOG_DIR="$reports/ros_log"
export ROS_TEST_RESULTS_DIR="$reports/test_results"
# The manager reports to $reports/tsan.<pid>; the test driver, which links
# the runtime only for the instrumented libraries it shares with the nodelet,
# reports nothing (its own code is not instrumented, so its message traffic
# through roscpp would only give reports of ROS's reference counting).
export TSAN_OPTIONS="report_bugs=0"
manager_prefix="env LD_PRELOAD=$runtime"
manager_prefix+=" TSAN_OPTIONS=log_path=$reports/tsan:halt_on_error=0:second_deadlock_stack=1"

failed=0
for test in live_tuning persistence concurrency; do
  echo "-- rostest $test.test, nodelet manager under ThreadSanitizer"
  if rostest --text bowg_ros "$test.test" manager_prefix:="$manager_prefix" \
    > "$reports/$test.log" 2>&1; then
    echo "   $test: tests passed"
  else
    echo "   $test: FAILED (log: $reports/$test.log)"
    tail -n 40 "$reports/$test.log"
    failed=1
  fi
done

shopt -s nullglob
found=("$reports"/tsan.*)
ours=0
if [ "${#found[@]}" -gt 0 ]; then
  read -r ours ros < <(python3 "$repo/test/tsan/tsan_reports.py" "$repo" "$tsan_ws/devel/lib" \
    "$reports/ours.txt" "$reports/ros_internal.txt" "${found[@]}")
  echo "   reports inside ROS's own libraries (not failed on): $ros ($reports/ros_internal.txt)"
fi
if [ "$ours" -gt 0 ]; then
  head -n 200 "$reports/ours.txt"
  fail "$ours ThreadSanitizer report(s) in the project's code (all in $reports/ours.txt)"
fi
[ "$failed" -eq 0 ] || fail "a rostest failed under ThreadSanitizer"
echo "ThreadSanitizer: live tuning, persistence, services during processing: no report in the project's code"
