#!/usr/bin/env bash
# The install space deploys: `scripts/build.sh install` (catkin_make install
# into <workspace>/install), then, in a clean environment that sources only
# <workspace>/install/setup.bash (no source or devel space on any path):
#   - every installed file is a file of the install space (no link back into
#     the checkout), and the files the launch files, the tools and downstream
#     packages need are there (vocabulary, headers of both trees, messages,
#     plugin description, libraries, tools);
#   - a package built against the install space alone compiles and links with
#     <bowg_ros/...> and <bowg/...> (catkin_package's INCLUDE_DIRS);
#   - `rospack find bowg_ros` is the install space's share folder;
#   - a roscore on a free port, `roslaunch bowg_ros bowg.launch` with no
#     argument (the bundled default vocabulary), the nodelet loaded from the
#     install space's library answers a textured image on /camera/image_raw with
#     a /bowg/keyframe_status (test/install_space_probe.py);
#   - `rosrun bowg_ros bowg_convert_vocabulary --help` exits 0 with its usage.
# Every wait is bounded; roscore and roslaunch are stopped on exit.
#   scripts/check_install_space.sh          (scripts/test.sh runs it)
# Environment: BOWG_WS (workspace), BOWG_JOBS (build jobs).
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${BOWG_WS:-$repo/.ws}"
export PATH="/usr/bin:$PATH"
fail() {
  echo "check_install_space: FAIL: $*" >&2
  exit 1
}

# ---------------------------------------------------------------------------
# The run in the clean environment (the script calls itself through env -i).
if [ "${1:-}" = --in-clean-env ]; then
  inst="$2"
  work="$3"
  probe="$4"
  ws="$5"
  share="$inst/share/bowg_ros"
  pids=()
  manager_pid=""
  stop_all() {
    local n pid
    # Newest first (roslaunch, then roscore): each stops its nodes on SIGINT.
    # Each was started with setsid, so its process group is its own id.
    for ((n = ${#pids[@]} - 1; n >= 0; n--)); do
      pid=${pids[n]}
      kill -INT -- "-$pid" 2> /dev/null || continue
      for _ in $(seq 1 80); do
        kill -0 -- "-$pid" 2> /dev/null || break
        sleep 0.25
      done
      kill -KILL -- "-$pid" 2> /dev/null || true
    done
    # roslaunch puts its nodes in process groups of their own: should it have
    # left the nodelet manager behind, stop it by its id.
    if [ -n "$manager_pid" ] && grep -qa bowg_manager "/proc/$manager_pid/cmdline" 2> /dev/null; then
      kill -KILL "$manager_pid" 2> /dev/null || true
    fi
  }
  trap stop_all EXIT
  show_log() {
    echo "--- $1 (last 40 lines)" >&2
    tail -n 40 "$1" >&2 || true
  }

  # catkin's environment hooks read unset variables.
  set +u
  source "$inst/setup.bash"
  set -u
  for var in ROS_PACKAGE_PATH CMAKE_PREFIX_PATH LD_LIBRARY_PATH PYTHONPATH; do
    IFS=: read -r -a entries <<< "${!var:-}"
    for entry in "${entries[@]}"; do
      case "$entry" in
        "$inst" | "$inst"/*) ;;
        "$ws" | "$ws"/* | "$repo" | "$repo"/*) fail "$var holds $entry (source, devel or build space)" ;;
      esac
    done
  done
  found="$(rospack find bowg_ros)" || fail "rospack find bowg_ros failed"
  [ "$found" = "$share" ] || fail "rospack find bowg_ros: $found, not $share"
  echo "rospack find bowg_ros: $found"

  # rosrun from the install space: --help exits 0, no arguments exits 2.
  set +e
  timeout 60 rosrun bowg_ros bowg_convert_vocabulary --help > "$work/help.out" 2> "$work/help.err"
  status=$?
  timeout 60 rosrun bowg_ros bowg_convert_vocabulary > /dev/null 2>&1
  status_no_args=$?
  set -e
  [ "$status" -eq 0 ] || { cat "$work/help.err" >&2; fail "rosrun bowg_ros bowg_convert_vocabulary --help exited $status"; }
  grep -q '^usage: bowg_convert_vocabulary' "$work/help.out" || fail "bowg_convert_vocabulary --help printed no usage"
  ! grep -q 'File system loop' "$work/help.err" || fail "rosrun reports a file system loop"
  [ "$status_no_args" -eq 2 ] || fail "bowg_convert_vocabulary without arguments exited $status_no_args, not 2"
  echo "rosrun bowg_ros bowg_convert_vocabulary --help: usage, exit 0 (without arguments: 2)"

  # A master of its own on a free port.
  port=""
  for _ in $(seq 1 20); do
    candidate=$((11500 + RANDOM % 400))
    if ! (exec 3<> "/dev/tcp/127.0.0.1/$candidate") 2> /dev/null; then
      port=$candidate
      break
    fi
  done
  [ -n "$port" ] || fail "no free port in 11500-11899"
  export ROS_MASTER_URI="http://127.0.0.1:$port"
  export ROS_HOSTNAME=127.0.0.1
  export ROS_HOME="$work/ros_home"
  setsid roscore -p "$port" > "$work/roscore.log" 2>&1 < /dev/null &
  pids+=($!)
  up=0
  deadline=$((SECONDS + 30))
  while [ "$SECONDS" -lt "$deadline" ]; do
    if timeout 5 rosparam get /run_id > /dev/null 2>&1; then
      up=1
      break
    fi
    kill -0 "${pids[0]}" 2> /dev/null || break
    sleep 0.5
  done
  [ "$up" -eq 1 ] || { show_log "$work/roscore.log"; fail "roscore on port $port did not come up within 30 s"; }
  echo "roscore: $ROS_MASTER_URI"

  # bowg.launch with no argument: the vocabulary is the bundled default.
  setsid roslaunch bowg_ros bowg.launch > "$work/roslaunch.log" 2>&1 < /dev/null &
  pids+=($!)
  # Until advertised, roslaunch gone, a FATAL (e.g. the vocabulary not
  # found), or 60 s.
  advertised=0
  deadline=$((SECONDS + 60))
  while [ "$SECONDS" -lt "$deadline" ]; do
    if timeout 5 rostopic list 2> /dev/null | grep -qx /bowg/keyframe_status; then
      advertised=1
      break
    fi
    kill -0 "${pids[1]}" 2> /dev/null || break
    grep -q 'FATAL' "$work/roslaunch.log" && break
    sleep 0.5
  done
  [ "$advertised" -eq 1 ] \
    || { show_log "$work/roslaunch.log"; fail "/bowg/keyframe_status not advertised (waited up to 60 s; roslaunch bowg_ros bowg.launch log above)"; }
  echo "roslaunch bowg_ros bowg.launch: /bowg/keyframe_status advertised"

  # The plugin came from the install space's library.
  manager_pid="$(timeout 10 rosnode info /bowg_manager 2> /dev/null | sed -nE 's/^Pid: ([0-9]+)$/\1/p')"
  [ -n "$manager_pid" ] || fail "no pid for /bowg_manager (rosnode info)"
  library="$(grep -o '/[^ ]*libbowg_ros_nodelet\.so' "/proc/$manager_pid/maps" | sort -u)"
  [ "$library" = "$inst/lib/libbowg_ros_nodelet.so" ] \
    || fail "the manager loaded '${library:-no libbowg_ros_nodelet.so}', not $inst/lib/libbowg_ros_nodelet.so"
  echo "nodelet library: $library"

  if ! timeout 90 /usr/bin/python3 "$probe" 60; then
    show_log "$work/roslaunch.log"
    fail "no /bowg/keyframe_status for images on /camera/image_raw"
  fi
  timeout 10 rosparam get /bowg/vocabulary_path > "$work/vocabulary_path" \
    || fail "no /bowg/vocabulary_path parameter"
  [ "$(cat "$work/vocabulary_path")" = "$share/data/default_vocabulary.bowgvoc" ] \
    || fail "the nodelet's vocabulary is $(cat "$work/vocabulary_path"), not the install space's default"
  echo "vocabulary: $(cat "$work/vocabulary_path")"
  exit 0
fi

# ---------------------------------------------------------------------------
# Install, check the files, then run in the clean environment.
work="$(mktemp -d "${TMPDIR:-/tmp}/bowg_install_check.XXXXXX")"
trap 'rm -rf "$work"' EXIT
log="$ws/install.log"
echo "install: scripts/build.sh install (log $log)"
mkdir -p "$ws"
ws="$(cd "$ws" && pwd)"
# From scratch: a file left by an earlier install would hide a missing rule.
rm -rf "$ws/install"
if ! bash "$repo/scripts/build.sh" install > "$log" 2>&1; then
  tail -n 40 "$log" >&2
  fail "scripts/build.sh install failed"
fi
inst="$(cd "$ws/install" && pwd)"
share="$inst/share/bowg_ros"

# Nothing installed leads out of the install space.
while IFS= read -r -d '' link; do
  target="$(readlink -f "$link" || true)"
  case "$target" in
    "$inst"/*) ;;
    *) fail "$link is a link to ${target:-nothing} (outside the install space)" ;;
  esac
done < <(find "$inst" -type l -print0)

# What the launch files, the tools and downstream packages need.
required=(
  "$share/package.xml" "$share/nodelet_plugins.xml"
  "$share/launch/bowg.launch" "$share/launch/bowg_nodelet.launch" "$share/launch/evaluate_bag.launch"
  "$share/config/pipe.yaml" "$share/config/pipe_gftt.yaml" "$share/config/generic.yaml"
  "$share/data/default_vocabulary.bowgvoc" "$share/data/README.md"
  "$inst/lib/libbowg_engine.so" "$inst/lib/libbowg_ros.so" "$inst/lib/libbowg_ros_nodelet.so"
  "$inst/include/bowg_ros/LoopClosure.h" "$inst/include/bowg_ros/LoadDatabase.h"
  "$inst/include/bowg_ros/BoWGConfig.h"
  "$inst/lib/python3/dist-packages/bowg_ros/msg/_KeyframeStatus.py"
  "$inst/lib/python3/dist-packages/bowg_ros/cfg/BoWGConfig.py"
)
for f in "$repo"/msg/*.msg "$repo"/srv/*.srv; do
  required+=("$share/${f#"$repo"/}")
done
for f in "$repo"/include/bowg_ros/*.h; do
  required+=("$inst/include/bowg_ros/${f##*/}")
done
while IFS= read -r -d '' f; do
  required+=("$inst/include/${f#"$repo"/engine/include/}")
done < <(find "$repo/engine/include/bowg" -name '*.h' -print0)
# The user-facing executables (tools/CMakeLists.txt, CMakeLists.txt).
for tool in bowg_bag_evaluator bowg_convert_vocabulary bowg_evaluate bowg_generate_pipe_sequence \
    bowg_train_vocabulary loop_detector_node; do
  [ -x "$inst/lib/bowg_ros/$tool" ] || fail "$inst/lib/bowg_ros/$tool is missing or not executable"
done
for f in "${required[@]}"; do
  [ -f "$f" ] || fail "$f is not installed"
done
cmp -s "$repo/data/default_vocabulary.bowgvoc" "$share/data/default_vocabulary.bowgvoc" \
  || fail "the installed default vocabulary differs from data/default_vocabulary.bowgvoc"
# pluginlib resolves the library path of the plugin description in the prefix.
grep -q '<library path="lib/libbowg_ros_nodelet">' "$share/nodelet_plugins.xml" \
  || fail "nodelet_plugins.xml names another library than lib/libbowg_ros_nodelet"
echo "install space $inst: ${#required[@]} files and 6 executables, no link out of it"

# A downstream package against the install space alone: the headers of both
# trees, the messages and the libraries through find_package(catkin ... bowg_ros).
downstream="$work/downstream"
mkdir -p "$downstream/src"
cat > "$downstream/src/CMakeLists.txt" << 'CMAKE'
cmake_minimum_required(VERSION 3.10)
project(bowg_ros_install_consumer CXX)
set(CMAKE_CXX_STANDARD 14)
find_package(catkin REQUIRED COMPONENTS bowg_ros)
include_directories(${catkin_INCLUDE_DIRS})
add_executable(consumer consumer.cpp)
target_link_libraries(consumer ${catkin_LIBRARIES})
CMAKE
cat > "$downstream/src/consumer.cpp" << 'CPP'
#include <bowg/parameters/parameter_table.h>
#include <bowg_ros/KeyframeStatus.h>
#include <bowg_ros/ros_conversions.h>

#include <iostream>

int main() {
  // One symbol of each library: libbowg_engine and libbowg_ros.
  double covariance[36];
  bowg_ros::fillRelativePoseCovariance(true, 40, covariance);
  bowg_ros::KeyframeStatus status;
  status.status = bowg_ros::KeyframeStatus::NO_CANDIDATES;
  std::cout << bowg::parameterTable().size() << " parameters\n";
  return 0;
}
CPP
set +e
env -i HOME="$HOME" PATH=/usr/bin:/bin bash -c '
  source "$1/setup.bash" &&
  cmake -S "$2/src" -B "$2/build" -DCMAKE_BUILD_TYPE=Release &&
  make -C "$2/build" &&
  "$2/build/consumer"' _ "$inst" "$downstream" > "$work/downstream.log" 2>&1
status=$?
set -e
[ "$status" -eq 0 ] || { tail -n 40 "$work/downstream.log" >&2; fail "a package against the install space does not build or run"; }
echo "downstream package: built and ran against the install space ($(tail -n 1 "$work/downstream.log"))"

# The clean environment: HOME and the system PATH, then the install space.
env -i HOME="$HOME" PATH=/usr/bin:/bin bash "$repo/scripts/check_install_space.sh" \
  --in-clean-env "$inst" "$work" "$repo/test/install_space_probe.py" "$ws" \
  || fail "the install space does not run (above)"
echo "check_install_space: ok"
