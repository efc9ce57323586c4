// bowg_pose_graph_node: the live pose-graph example. It listens to the robot's
// odometry, the loop detector's keyframes and loops, keeps one graph node per
// keyframe (the odometry at the keyframe's stamp), and after every loop
// re-optimises and publishes the corrected path. The ROS shell of
// tools/libs/pose_graph.
//
//   odom (nav_msgs/Odometry)            -> OdometryBuffer
//   keyframe_status (bowg_ros/KeyframeStatus) -> a node + an odometry edge
//   loop_closure (bowg_ros/LoopClosure) -> a loop edge, optimise
//   -> ~path (nav_msgs/Path, corrected), ~odometry_path (as measured),
//      ~loops (visualization_msgs/Marker: a line per loop on the corrected path),
//      TF map -> odom (REP-105: the correction of the odometry's drift)
//   ground_truth (nav_msgs/Odometry, with ~use_ground_truth; off by default)
//      -> per solve, the position RMSE of the corrected path and of the
//      odometry against it at the keyframes' stamps (a line on the log)
//
// The camera's mounting: with ~base_frame (the odometry's body frame) each
// loop looks up base_frame <- the loop's optical frame in TF, so that "the
// cameras stood at the same place" becomes the right constraint between the
// bodies; without it the camera is taken to sit at the body's origin looking
// along its x axis.
#pragma once

#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/Marker.h>

#include <Eigen/Geometry>
#include <Eigen/StdVector>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bowg_pose_graph/odometry_buffer.h"
#include "bowg_pose_graph/pose_graph.h"
#include "bowg_ros/KeyframeStatus.h"
#include "bowg_ros/LoopClosure.h"

namespace bowg {
namespace pose_graph_node {

class LivePoseGraph {
 public:
  LivePoseGraph(ros::NodeHandle& nh, ros::NodeHandle& pnh);

 private:
  void onOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  void onKeyframe(const bowg_ros::KeyframeStatus::ConstPtr& msg);
  void onLoop(const bowg_ros::LoopClosure::ConstPtr& msg);
  void onGroundTruth(const nav_msgs::Odometry::ConstPtr& msg);
  /// Gives the waiting nodes their ground truth where the buffer covers
  /// their stamp.
  void fillGroundTruth();
  /// Logs the corrected path's and the odometry's position RMSE against the
  /// ground truth at the keyframes that have one.
  void reportTrajectoryError();
  /// Turns the keyframes whose stamp the odometry covers into nodes.
  void addCoveredKeyframes();
  /// Adds the loops whose keyframes are nodes and drops those with a
  /// keyframe that never will be; true when one was added.
  bool addReadyLoops();
  /// Adds `loop` between nodes `query` and `match`: a metric edge where its
  /// translation is usable and wanted, else a same-place edge.
  void addLoop(const bowg_ros::LoopClosure& loop, std::size_t query, std::size_t match,
               const Eigen::Isometry3d& camera);
  /// Whether keyframe `id` was handled (or passed over, lost) without
  /// becoming a node: skipped without odometry, or its status lost.
  bool neverANode(std::uint32_t id) const;
  /// body_T_optical of the loop's camera; false (logged; the loop waits)
  /// when TF lacks it.
  bool cameraMounting(const bowg_ros::LoopClosure& loop, Eigen::Isometry3d* body_T_optical);
  void publish();
  void restart(const std::string& why);

  pose_graph::PoseGraphOptions options_;
  bool use_loop_rotation_ = false;
  bool use_metric_translation_ = true;
  std::string map_frame_, base_frame_;
  std::string odom_frame_;  ///< the odometry's frame_id, for map -> odom
  bool publish_tf_ = true;
  double last_tf_stamp_ = -1;
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_broadcaster_;
  tf2_ros::Buffer tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  pose_graph::OdometryBuffer odometry_;
  std::unique_ptr<pose_graph::PoseGraph> graph_;
  std::deque<std::pair<std::uint32_t, double>> pending_keyframes_;  // id, stamp
  std::vector<bowg_ros::LoopClosure> pending_loops_;
  std::map<std::uint32_t, std::size_t> node_of_keyframe_;
  std::vector<std::pair<std::size_t, std::size_t>> loop_nodes_;  // query, match
  std::vector<double> node_stamps_;
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> node_odometry_;
  std::size_t loops_ = 0, metric_loops_ = 0, skipped_keyframes_ = 0, lost_keyframes_ = 0;
  // Loops dropped because a keyframe of theirs never became a node (skipped
  // or lost), and the largest keyframe id handled (-1: none yet).
  std::size_t dropped_loops_ = 0;
  std::int64_t handled_id_ = -1;

  // Ground truth per node: it travels on its own connection and may trail
  // the odometry, so a node waits for the truth to cover its stamp.
  bool use_ground_truth_ = false;
  pose_graph::OdometryBuffer ground_truth_;
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> node_truth_;
  std::vector<bool> node_has_truth_;
  std::deque<std::size_t> truth_waiting_;  ///< nodes, in stamp order

  ros::Subscriber odom_sub_, keyframe_sub_, loop_sub_, ground_truth_sub_;
  ros::Publisher path_pub_, odometry_path_pub_, loops_pub_;
};

}  // namespace pose_graph_node
}  // namespace bowg
