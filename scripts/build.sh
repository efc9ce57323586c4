#!/usr/bin/env bash
# Builds bowg_ros in a catkin workspace that this script creates itself
# (default: <repo>/.ws, override with BOWG_WS), so nobody has to set one up by
# hand. Extra arguments go to catkin_make (e.g. run_tests, install, or
# -DFOO=bar).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"

# Debian's ROS 1 lives in /usr; a pyenv or venv python first on PATH lacks the
# ROS modules, so put the system interpreter first.
export PATH="/usr/bin:$PATH"

# The package in the workspace: a directory of links into the repository
# (scripts/link_package.sh explains why), synced on every build.
bash "$repo/scripts/link_package.sh" "$ws"

jobs="${BOWG_JOBS:-$(nproc)}"
cd "$ws"
build() {
  catkin_make -j"$jobs" \
    -DCMAKE_BUILD_TYPE="${BOWG_BUILD_TYPE:-Release}" \
    -DCMAKE_CXX_STANDARD=14 \
    -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -DPython3_EXECUTABLE=/usr/bin/python3 \
    -DCATKIN_ENABLE_TESTING=ON \
    "$@"
}
# Quiet mode's terminal: each target built as it is done, and at least every
# 10 s a line with catkin's latest percentage and the time so far, so that a
# minute of compiling one big library does not look like a hang.
progress() {
  local start=$SECONDS last=$SECONDS line pct="[  ?%]" status
  while true; do
    if IFS= read -r -t 10 line; then
      case "$line" in
        "["*"%] Built target "*) echo "   $line"; pct="${line%%]*}]"; last=$SECONDS; continue ;;
        "["*"%]"*) pct="${line%%]*}]" ;;
      esac
    else
      status=$?
      [ "$status" -gt 128 ] || break  # end of the output; > 128: timed out
    fi
    if [ $((SECONDS - last)) -ge 10 ]; then
      echo "   $pct building, $((SECONDS - start)) s"
      last=$SECONDS
    fi
  done
}

if [ -z "${BOWG_BUILD_LOG:-}" ]; then
  build "$@"
else
  # Quiet mode for the demo and the suite: the whole output goes to the log,
  # the terminal sees progress (above), and the log's tail when the build
  # fails.
  mkdir -p "$(dirname "$BOWG_BUILD_LOG")"
  set +e
  build "$@" 2>&1 | tee "$BOWG_BUILD_LOG" | progress
  status=${PIPESTATUS[0]}
  set -e
  if [ "$status" -ne 0 ]; then
    tail -n 40 "$BOWG_BUILD_LOG" >&2
    echo "build failed (log: $BOWG_BUILD_LOG)" >&2
    exit 1
  fi
fi
