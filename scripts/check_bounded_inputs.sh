#!/usr/bin/env bash
# Every loader against inputs it must refuse quickly and cheaply: FIFOs,
# directories, /dev/zero links and sparse 3 GiB files named as every
# vocabulary format (.bin .txt .dbow3 .yml .bowgvoc) and as a database, a
# 3 MB gzip bomb (.yml.gz, 3 GiB inflated) and a 30000 x 30000 PNG in an
# image folder, replayed against bowg_convert_vocabulary, bowg_evaluate and
# the live nodelet (loop_detector_node's start-up with ~vocabulary_path and
# ~database_load_path, and its ~load_database service, under a roscore of its
# own). Prints a table (case | program | outcome | seconds | peak MB over the
# program's baseline) and exits non-zero when a case is accepted, hangs
# (10 s), crashes, is refused without naming the file, or takes more than 1 s
# or 100 MB over the program refusing a missing file
# (scripts/check_bounded_inputs.py says exactly how).
#   scripts/check_bounded_inputs.sh [WORKSPACE]     (default <repo>/.ws)
# Builds nothing: the workspace must hold the three programs and the
# package's Python service types, as a full scripts/build.sh leaves it
# (or: scripts/build.sh bowg_convert_vocabulary bowg_evaluate
# loop_detector_node bowg_ros_nodelet bowg_ros_generate_messages_py).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${1:-${BOWG_WS:-$repo/.ws}}"
export PATH="/usr/bin:$PATH"
[ -f "$ws/devel/setup.bash" ] || { echo "check_bounded_inputs: no workspace at $ws" >&2; exit 1; }
# catkin's environment hooks read unset variables.
set +u
# shellcheck disable=SC1091
source "$ws/devel/setup.bash"
set -u
exec python3 "$repo/scripts/check_bounded_inputs.py" "$ws" "$repo"
