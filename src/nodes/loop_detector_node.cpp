// Standalone executable for bowg_ros/LoopDetectorNodelet: loads the same
// nodelet in-process through nodelet::Loader (one code path, as
// image_pipeline does), with this node's remappings and private parameters.
// Exits 1 when the nodelet does not start (a missing vocabulary, an invalid
// parameter), with the reason, so that roslaunch's respawn or required=
// sees the failure.
#include <nodelet/loader.h>
#include <ros/ros.h>

#include <string>

#include "bowg_ros/startup_status.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "bowg_loop_detector");
  nodelet::Loader loader;
  nodelet::M_string remappings(ros::names::getRemappings());
  nodelet::V_string my_argv(argv + 1, argv + argc);
  if (!loader.load(ros::this_node::getName(), "bowg_ros/LoopDetectorNodelet", remappings,
                   my_argv)) {
    ROS_FATAL("could not load bowg_ros/LoopDetectorNodelet");
    return 1;
  }
  std::string why;
  if (bowg_ros::startupFailed(ros::this_node::getName(), &why)) {
    ROS_FATAL("bowg_loop_detector: not started: %s", why.c_str());
    return 1;
  }
  ros::spin();
  return 0;
}
