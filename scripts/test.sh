#!/usr/bin/env bash
# README command 2: set up, build and run every test on a fresh Debian 12
# machine. Exits non-zero if anything fails. Run from anywhere.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"
export PATH="/usr/bin:$PATH"

echo "== install dependencies"
bash "$repo/scripts/install_deps.sh"

echo "== static checks"
bash "$repo/scripts/check_engine_is_ros_free.sh"
# catkin_lint must see the package under its own name, and walk its real
# folders (it does not follow the workspace package's per-entry links): lint
# through a scratch link named bowg_ros. No --ignore: the two deliberate
# exceptions are pragmas in CMakeLists.txt, each with its reason.
lint_dir="$(mktemp -d "${TMPDIR:-/tmp}/bowg_lint.XXXXXX")"
ln -s "$repo" "$lint_dir/bowg_ros"
lint_status=0
catkin_lint -W2 --strict "$lint_dir/bowg_ros" || lint_status=$?
rm "$lint_dir/bowg_ros" && rmdir "$lint_dir"
[ "$lint_status" -eq 0 ] || exit 1

echo "== build (C++14) and tests"
bash "$repo/scripts/build.sh"
bash "$repo/scripts/build.sh" tests
# catkin_make run_tests exits 0 even when tests fail: the verdict comes from
# catkin_test_results below.
bash "$repo/scripts/build.sh" run_tests -j1 || true

echo "== arm64: the engine cross-built with Debian's aarch64 toolchain, its unit tests under qemu-user"
# Their gtest results join the others', so catkin_test_results counts them
# (and their failures); status 3 means only that some of them failed.
arm64_status=0
BOWG_ARM64_RESULTS="$ws/build/test_results/bowg_ros_arm64" bash "$repo/scripts/check_arm64.sh" "$ws/arm64" \
  || arm64_status=$?
arm64_failed=0
[ "$arm64_status" -eq 0 ] || [ "$arm64_status" -eq 3 ] || arm64_failed=1

echo "== bounded inputs: special files, huge files and bombs against the converter, the evaluator and the node"
bounded_failed=0
bash "$repo/scripts/check_bounded_inputs.sh" "$ws" || bounded_failed=1

echo "== workspace: the package as a directory of links, rosrun without a file system loop"
link_failed=0
bash "$repo/scripts/check_workspace_link.sh" || link_failed=1

echo "== install space: catkin_make install, then roslaunch and rosrun from it alone"
install_failed=0
bash "$repo/scripts/check_install_space.sh" || install_failed=1

echo "== ThreadSanitizer: the nodelet's threads (live tuning, persistence, services during processing)"
tsan_failed=0
bash "$repo/scripts/check_thread_sanitizer.sh" || tsan_failed=1

echo "== AddressSanitizer/UBSan: file loaders, persistence, image headers and upstream features on bad input"
asan_dir="$ws/asan"
cmake -S "$repo/engine" -B "$asan_dir" -DBOWG_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DBOWG_ENGINE_BENCHMARKS=OFF -DCMAKE_CXX_STANDARD=14 > "$asan_dir.log" 2>&1 \
  || { cat "$asan_dir.log"; exit 1; }
asan_tests=(bowg_vocabulary_io_test bowg_vocabulary_io_bad_input_test bowg_detector_file_test
  bowg_detector_file_versions_test bowg_detector_file_bad_input_test bowg_detector_file_forged_test
  bowg_brief_pattern_test bowg_image_header_test bowg_image_decoding_test bowg_feature_arrays_test
  bowg_word_groups_test bowg_word_group_scores_test bowg_saved_detector_test bowg_atomic_file_test)
make -C "$asan_dir" -j"${BOWG_JOBS:-$(nproc)}" "${asan_tests[@]}" >> "$asan_dir.log" 2>&1 \
  || { tail -n 50 "$asan_dir.log"; exit 1; }
asan_failed=0
for t in "${asan_tests[@]}"; do
  # UBSan stops at its first report, so that undefined behaviour fails the test.
  if ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
      "$asan_dir/$t" --gtest_brief=1 > "$asan_dir/$t.log" 2>&1; then
    echo "asan: $t ok"
  else
    echo "asan: $t FAILED"; tail -n 40 "$asan_dir/$t.log"; asan_failed=$((asan_failed + 1))
  fi
done

echo "== AddressSanitizer/UBSan: the ROS layer's gtests and the tools' end-to-end tests"
asan_ros_failed=0
bash "$repo/scripts/check_address_sanitizer.sh" || asan_ros_failed=1

echo "== libFuzzer: every file loader, image decoding and the features input, ${BOWG_FUZZ_SECONDS:-30} s each (scripts/fuzz.sh)"
fuzz_failed=0
BOWG_SKIP_DEPS=1 BOWG_FUZZ_DIR="$ws/fuzz" bash "$repo/scripts/fuzz.sh" "${BOWG_FUZZ_SECONDS:-30}" \
  || fuzz_failed=1
echo "== results"
set +e
summary=$(catkin_test_results --verbose "$ws/build/test_results" 2>&1)
status=$?
set -e
echo "$summary"
# A plain closing line for CI: "N passed, N failed".
line=$(echo "$summary" | grep -E '^Summary:' | tail -n 1)
tests=$(echo "$line" | sed -nE 's/.* ([0-9]+) tests.*/\1/p')
errors=$(echo "$line" | sed -nE 's/.* ([0-9]+) errors.*/\1/p')
failures=$(echo "$line" | sed -nE 's/.* ([0-9]+) failures.*/\1/p')
skipped=$(echo "$line" | sed -nE 's/.* ([0-9]+) skipped.*/\1/p')
if [ -z "$tests" ] || [ "$tests" -eq 0 ]; then
  echo "FAIL: no test ran" >&2
  exit 1
fi
# Besides catkin's tests (the arm64 ones among them): the asan tests, the ROS layer's and tools' ASan
# check, the bounded-inputs replay, the fuzz run, the workspace, the install
# space and the ThreadSanitizer checks.
bad=$(( ${errors:-0} + ${failures:-0} + asan_failed + asan_ros_failed + bounded_failed
  + fuzz_failed + link_failed + install_failed + tsan_failed + arm64_failed ))
echo "$(( tests + ${#asan_tests[@]} + 6 - bad - ${skipped:-0} )) passed, $bad failed, ${skipped:-0} skipped"
[ "$asan_failed" -eq 0 ] || exit 1
[ "$asan_ros_failed" -eq 0 ] || exit 1
[ "$fuzz_failed" -eq 0 ] || exit 1
[ "$link_failed" -eq 0 ] || exit 1
[ "$install_failed" -eq 0 ] || exit 1
[ "$tsan_failed" -eq 0 ] || exit 1
[ "$bounded_failed" -eq 0 ] || exit 1
[ "$arm64_status" -eq 0 ] || exit 1
exit $status
