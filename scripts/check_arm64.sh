#!/usr/bin/env bash
# The engine on arm64: cross-builds the ROS-free engine and its unit tests
# with Debian's aarch64 toolchain against Debian's arm64 OpenCV
# (scripts/arm64_sysroot.sh), then runs every test under qemu-user. On arm64
# every SIMD path takes its portable twin, so the tests that check those
# twins against their references run there too.
# Usage: scripts/check_arm64.sh [DIR]   (default: <workspace>/arm64)
# Each test writes its gtest XML into BOWG_ARM64_RESULTS (default
# DIR/test_results), where catkin_test_results can count them.
# Exit status: 0 all passed, 3 some test failed (its XML says which), any
# other: the toolchain, the sysroot or the build failed.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:$PATH"
dir="${1:-${BOWG_WS:-$repo/.ws}/arm64}"
mkdir -p "$dir"
dir="$(cd "$dir" && pwd)"
results="${BOWG_ARM64_RESULTS:-$dir/test_results}"
jobs="${BOWG_JOBS:-$(nproc)}"

for tool in aarch64-linux-gnu-g++ qemu-aarch64; do
  if ! command -v "$tool" > /dev/null; then
    echo "check_arm64: $tool is missing: run scripts/install_deps.sh" >&2
    exit 1
  fi
done

bash "$repo/scripts/arm64_sysroot.sh" "$dir"

build="$dir/build"
log="$dir/build.log"
echo "check_arm64: cross-building the engine and its tests in $build (log: $log)"
cmake -S "$repo/engine" -B "$build" -DCMAKE_TOOLCHAIN_FILE="$repo/cmake/cross/aarch64-linux-gnu.cmake" \
  -DBOWG_ARM64_SYSROOT="$dir/sysroot" -DBOWG_ENGINE_BENCHMARKS=OFF -DCMAKE_CXX_STANDARD=14 \
  -DCMAKE_BUILD_TYPE=Release > "$log" 2>&1 || { tail -n 40 "$log"; exit 1; }
make -C "$build" -j"$jobs" >> "$log" 2>&1 || { tail -n 60 "$log"; exit 1; }

# A host binary would pass every test and prove nothing about arm64.
machine="$(LC_ALL=C readelf -h "$build/bowg_neighbour_count_test" | sed -nE 's/^ *Machine: *//p')"
if [ "$machine" != "AArch64" ]; then
  echo "check_arm64: the tests were built for '$machine', not AArch64" >&2
  exit 1
fi
echo "check_arm64: $(ls "$build"/bowg_*_test | wc -l) test programs built for $machine"

rm -rf "$results"
mkdir -p "$results"
# The tests that compare an AVX2 path with its portable twin need an x86-64
# CPU with AVX2; on arm64 they have nothing to compare and are left out
# (the twins' tests against their references run).
echo "check_arm64: running the tests under qemu-aarch64 (not run: *Avx2*, there is no AVX2 on arm64)"
status=0
(cd "$build" && GTEST_OUTPUT="xml:$results/" GTEST_FILTER='-*Avx2*' \
  ctest -j"$jobs" --output-on-failure --timeout 1200) || status=$?
echo "check_arm64: gtest results in $results ($(ls "$results" | wc -l) files)"
[ "$status" -eq 0 ] || exit 3
