#!/usr/bin/env bash
# Installs everything bowg_ros needs on Debian 12 (bookworm) from Debian's own
# ROS 1 packages. Idempotent: installs only what is missing, so a second run
# does nothing. Run as root, or as a user with sudo.
set -euo pipefail

PACKAGES=(
  build-essential cmake pkg-config zlib1g-dev
  catkin catkin-lint ros-message-generation ros-message-runtime
  libroscpp-dev rosout python3-rosmaster python3-roslaunch rosbash
  python3-rostopic python3-rosnode python3-rosparam python3-rosservice
  libnodeletlib-dev libnodelet-dev libnodeletlib-tools pluginlib-dev
  libcv-bridge-dev libimage-transport-dev image-transport-tools
  libopencv-dev libeigen3-dev
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libdiagnostic-updater-dev python3-diagnostic-updater
  libdiagnostic-msgs-dev ros-diagnostic-msgs python3-diagnostic-msgs
  libstd-msgs-dev ros-std-msgs python3-std-msgs
  libstd-srvs-dev ros-std-srvs python3-std-srvs
  libgeometry-msgs-dev ros-geometry-msgs python3-geometry-msgs
  libsensor-msgs-dev ros-sensor-msgs python3-sensor-msgs
  libnav-msgs-dev ros-nav-msgs python3-nav-msgs
  librosbag-dev python3-rosbag
  libgtest-dev googletest librostest-dev python3-rostest libros-rosgraph-msgs-dev
  libbenchmark-dev python3-numpy python3-yaml python3-matplotlib
  clang libclang-rt-14-dev
  g++-aarch64-linux-gnu qemu-user
  libceres-dev libtf2-ros-dev libtf2-eigen-dev libvisualization-msgs-dev
  rviz ros-image-view libimage-view-dev
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install_deps: installing ${#missing[@]} missing packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive

# apt-get, waiting while another apt or dpkg (unattended upgrades on a fresh
# machine) holds its lock: up to BOWG_APT_LOCK_WAIT seconds (default 600),
# then the failure as apt reported it.
apt_get() {
  local waited=0 limit="${BOWG_APT_LOCK_WAIT:-600}" out status
  while true; do
    set +e
    out="$($SUDO apt-get -o DPkg::Lock::Timeout=60 "$@" 2>&1)"
    status=$?
    set -e
    if [ "$status" -eq 0 ]; then
      [ -z "$out" ] || printf '%s\n' "$out"
      return 0
    fi
    if ! printf '%s' "$out" | grep -qiE 'could not get lock|unable to acquire|is another process using it'; then
      printf '%s\n' "$out" >&2
      return "$status"
    fi
    if [ "$waited" -ge "$limit" ]; then
      printf '%s\n' "$out" >&2
      echo "install_deps: apt's lock still held after ${waited} s (BOWG_APT_LOCK_WAIT)" >&2
      return "$status"
    fi
    echo "install_deps: apt's lock is held by another process; waiting (${waited} s of ${limit} s)"
    sleep 5
    waited=$((waited + 5))
  done
}

apt_get update -qq
apt_get install -y -qq --no-install-recommends "${missing[@]}"
echo "install_deps: done"
