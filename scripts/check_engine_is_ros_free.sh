#!/usr/bin/env bash
# The engine must build without ROS: no ROS, message or cv_bridge headers.
set -euo pipefail
engine="$(cd "$(dirname "${BASH_SOURCE[0]}")/../engine" && pwd)"
if grep -rnE '#include\s*[<"](ros/|nodelet/|cv_bridge/|image_transport/|sensor_msgs/|std_msgs/|geometry_msgs/|bowg_ros/|rosbag/|dynamic_reconfigure/)' "$engine"; then
  echo "FAIL: the engine includes ROS headers (listed above)" >&2
  exit 1
fi
echo "engine is ROS-free"
