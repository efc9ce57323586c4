#include "live_pose_graph.h"

#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "bowg_pose_graph/camera_frames.h"
#include "bowg_pose_graph/trajectory_error.h"

namespace bowg {
namespace pose_graph_node {
namespace {

Eigen::Isometry3d toIsometry(const geometry_msgs::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() =
      Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z)
          .normalized()
          .toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return t;
}

geometry_msgs::PoseStamped toPoseStamped(const Eigen::Isometry3d& t, double stamp,
                                         const std::string& frame) {
  geometry_msgs::PoseStamped p;
  p.header.stamp = ros::Time(stamp);
  p.header.frame_id = frame;
  p.pose.position.x = t.translation().x();
  p.pose.position.y = t.translation().y();
  p.pose.position.z = t.translation().z();
  const Eigen::Quaterniond q(t.rotation());
  p.pose.orientation.x = q.x();
  p.pose.orientation.y = q.y();
  p.pose.orientation.z = q.z();
  p.pose.orientation.w = q.w();
  return p;
}

}  // namespace

LivePoseGraph::LivePoseGraph(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
  pnh.param("loop_sigma", options_.loop_position_sigma, options_.loop_position_sigma);
  pnh.param("loop_rotation_sigma_deg", options_.loop_rotation_sigma_deg,
            options_.loop_rotation_sigma_deg);
  pnh.param("odometry_sigma", options_.odometry_position_fraction,
            options_.odometry_position_fraction);
  pnh.param("odometry_rotation_deg_per_sqrt_m", options_.odometry_rotation_deg_per_sqrt_m,
            options_.odometry_rotation_deg_per_sqrt_m);
  pnh.param("robust_sigmas", options_.loop_robust_sigmas, options_.loop_robust_sigmas);
  pnh.param("use_loop_rotation", use_loop_rotation_, false);
  pnh.param("use_metric_translation", use_metric_translation_, true);
  pnh.param<std::string>("map_frame", map_frame_, "map");
  pnh.param<std::string>("base_frame", base_frame_, "");
  pnh.param("publish_tf", publish_tf_, true);
  if (publish_tf_) tf_broadcaster_.reset(new tf2_ros::TransformBroadcaster);
  if (!base_frame_.empty()) tf_listener_.reset(new tf2_ros::TransformListener(tf_buffer_));
  double horizon = 120.0;
  pnh.param("odometry_horizon", horizon, horizon);
  options_.validate();  // throws: main() reports and exits
  odometry_ = pose_graph::OdometryBuffer(horizon);
  ground_truth_ = pose_graph::OdometryBuffer(horizon);
  pnh.param("use_ground_truth", use_ground_truth_, false);
  graph_.reset(new pose_graph::PoseGraph(options_));

  path_pub_ = pnh.advertise<nav_msgs::Path>("path", 1, true);
  odometry_path_pub_ = pnh.advertise<nav_msgs::Path>("odometry_path", 1, true);
  loops_pub_ = pnh.advertise<visualization_msgs::Marker>("loops", 1, true);
  // Deep queues: an optimisation after a loop takes a while on a long run,
  // and a keyframe lost here is a hole in the graph (counted below if it
  // happens anyway).
  odom_sub_ = nh.subscribe("odom", 5000, &LivePoseGraph::onOdometry, this);
  keyframe_sub_ = nh.subscribe("keyframe_status", 5000, &LivePoseGraph::onKeyframe, this);
  loop_sub_ = nh.subscribe("loop_closure", 1000, &LivePoseGraph::onLoop, this);
  ROS_INFO("bowg_pose_graph_node: odometry %s, keyframes %s, loops %s -> %s, %s",
           odom_sub_.getTopic().c_str(), keyframe_sub_.getTopic().c_str(),
           loop_sub_.getTopic().c_str(), path_pub_.getTopic().c_str(),
           odometry_path_pub_.getTopic().c_str());
  if (use_ground_truth_) {
    // A remappable topic like odom; the parameter keeps it off unless asked
    // for, since a robot in the field has no ground truth.
    ground_truth_sub_ = nh.subscribe("ground_truth", 5000, &LivePoseGraph::onGroundTruth, this);
    ROS_INFO("bowg_pose_graph_node: ground truth %s: each solve logs the position RMSE",
             ground_truth_sub_.getTopic().c_str());
  }
}

void LivePoseGraph::restart(const std::string& why) {
  ROS_WARN("bowg_pose_graph_node: %s: starting a new graph (%zu keyframes, %zu loops dropped)",
           why.c_str(), node_stamps_.size(), loops_);
  graph_.reset(new pose_graph::PoseGraph(options_));
  pending_keyframes_.clear();
  pending_loops_.clear();
  handled_id_ = -1;
  node_of_keyframe_.clear();
  node_stamps_.clear();
  node_odometry_.clear();
  loop_nodes_.clear();
  node_truth_.clear();
  node_has_truth_.clear();
  truth_waiting_.clear();
  loops_ = 0;
  metric_loops_ = 0;
  last_tf_stamp_ = -1;
}

void LivePoseGraph::onOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
  odom_frame_ = msg->header.frame_id;
  odometry_.add(msg->header.stamp.toSec(), toIsometry(msg->pose.pose));
  addCoveredKeyframes();
}

void LivePoseGraph::onGroundTruth(const nav_msgs::Odometry::ConstPtr& msg) {
  ground_truth_.add(msg->header.stamp.toSec(), toIsometry(msg->pose.pose));
  fillGroundTruth();
}

void LivePoseGraph::fillGroundTruth() {
  // Nodes wait in stamp order: the first one the truth does not reach yet
  // ends the pass. Looked up as soon as the truth covers them, not at the
  // next solve, which may come long after the buffer's horizon.
  while (!truth_waiting_.empty() && !ground_truth_.empty()) {
    const std::size_t node = truth_waiting_.front();
    if (node_stamps_[node] > ground_truth_.newest()) break;
    node_has_truth_[node] = ground_truth_.at(node_stamps_[node], &node_truth_[node]);
    truth_waiting_.pop_front();  // found, or older than the truth: never
  }
}

void LivePoseGraph::onKeyframe(const bowg_ros::KeyframeStatus::ConstPtr& msg) {
  // The detector's ids restart after its ~reset (or a new run).
  const std::uint32_t last =
      pending_keyframes_.empty()
          ? (node_of_keyframe_.empty() ? 0 : node_of_keyframe_.rbegin()->first)
          : pending_keyframes_.back().first;
  if ((!node_of_keyframe_.empty() || !pending_keyframes_.empty()) && msg->id <= last) {
    restart("keyframe id " + std::to_string(msg->id) + " after " + std::to_string(last));
  }
  if ((!node_of_keyframe_.empty() || !pending_keyframes_.empty()) && msg->id > last + 1) {
    lost_keyframes_ += msg->id - last - 1;
    ROS_WARN_THROTTLE(5.0,
                      "bowg_pose_graph_node: keyframe statuses %u..%u never arrived (%zu "
                      "lost): their odometry is bridged by one edge",
                      last + 1, msg->id - 1, lost_keyframes_);
  }
  pending_keyframes_.emplace_back(msg->id, msg->header.stamp.toSec());
  addCoveredKeyframes();
}

void LivePoseGraph::onLoop(const bowg_ros::LoopClosure::ConstPtr& msg) {
  pending_loops_.push_back(*msg);
  if (addReadyLoops()) publish();
}

void LivePoseGraph::addCoveredKeyframes() {
  bool added = false;
  while (!pending_keyframes_.empty() && !odometry_.empty() &&
         pending_keyframes_.front().second <= odometry_.newest()) {
    const std::uint32_t id = pending_keyframes_.front().first;
    const double stamp = pending_keyframes_.front().second;
    pending_keyframes_.pop_front();
    handled_id_ = std::max<std::int64_t>(handled_id_, id);
    Eigen::Isometry3d odom;
    if (!odometry_.at(stamp, &odom)) {
      ++skipped_keyframes_;
      ROS_WARN_THROTTLE(5.0,
                        "bowg_pose_graph_node: keyframe %u at %.6f: no odometry that old "
                        "(%zu keyframes skipped)",
                        id, stamp, skipped_keyframes_);
      continue;
    }
    if (node_stamps_.empty()) {
      graph_->addPose(odom);
    } else {
      // The new node continues the corrected trajectory by the measured step.
      const Eigen::Isometry3d step = node_odometry_.back().inverse() * odom;
      const std::size_t n = graph_->addPose(graph_->pose(graph_->size() - 1) * step);
      graph_->addOdometry(n - 1, n, step);
    }
    node_of_keyframe_[id] = node_stamps_.size();
    node_stamps_.push_back(stamp);
    node_odometry_.push_back(odom);
    node_truth_.emplace_back(Eigen::Isometry3d::Identity());
    node_has_truth_.push_back(false);
    if (use_ground_truth_) truth_waiting_.push_back(node_stamps_.size() - 1);
    added = true;
  }
  fillGroundTruth();
  if (addReadyLoops() || added) publish();
}

void LivePoseGraph::addLoop(const bowg_ros::LoopClosure& loop, std::size_t query,
                            std::size_t match, const Eigen::Isometry3d& camera) {
  const geometry_msgs::Quaternion& o = loop.relative_pose.pose.orientation;
  const Eigen::Quaterniond rotation(o.w, o.x, o.y, o.z);
  pose_graph::LoopEdge edge =
      pose_graph::loopEdgeForCamera(rotation, camera, use_loop_rotation_ && loop.has_relative_pose);
  edge.query = query;
  edge.match = match;
  bool added_metric = false;
  if (use_metric_translation_ && loop.has_relative_pose && loop.translation_scale_known) {
    // The query where the metric translation puts it, with its covariance.
    Eigen::Isometry3d q_T_m = Eigen::Isometry3d::Identity();
    q_T_m.linear() = rotation.normalized().toRotationMatrix();
    const geometry_msgs::Point& t = loop.relative_pose.pose.position;
    q_T_m.translation() = Eigen::Vector3d(t.x, t.y, t.z);
    Eigen::Matrix3d c;
    for (int r = 0; r < 3; ++r) {
      for (int k = 0; k < 3; ++k) c(r, k) = loop.relative_pose.covariance[r * 6 + k];
    }
    pose_graph::LoopEdge metric = pose_graph::metricLoopEdge(q_T_m, c, camera);
    metric.query = edge.query;
    metric.match = edge.match;
    try {
      graph_->addLoop(metric);
      added_metric = true;
      ++metric_loops_;
    } catch (const std::invalid_argument& e) {
      ROS_WARN(
          "bowg_pose_graph_node: loop %u -> %u: its metric translation is unusable (%s); "
          "added as a same-place loop",
          loop.query_id, loop.match_id, e.what());
    }
  }
  if (!added_metric) graph_->addLoop(edge);
  loop_nodes_.emplace_back(edge.query, edge.match);
  ++loops_;
}

bool LivePoseGraph::neverANode(std::uint32_t id) const {
  return static_cast<std::int64_t>(id) <= handled_id_ && node_of_keyframe_.count(id) == 0;
}

bool LivePoseGraph::addReadyLoops() {
  bool added = false;
  for (auto it = pending_loops_.begin(); it != pending_loops_.end();) {
    auto q = node_of_keyframe_.find(it->query_id), m = node_of_keyframe_.find(it->match_id);
    if (q == node_of_keyframe_.end() || m == node_of_keyframe_.end()) {
      if (neverANode(it->query_id) || neverANode(it->match_id)) {
        ++dropped_loops_;
        ROS_WARN_THROTTLE(5.0,
                          "bowg_pose_graph_node: loop %u -> %u dropped: a keyframe of it was "
                          "skipped or lost (%zu loops dropped)",
                          it->query_id, it->match_id, dropped_loops_);
        it = pending_loops_.erase(it);
      } else {
        ++it;  // its keyframes are still to come
      }
      continue;
    }
    Eigen::Isometry3d camera = pose_graph::cameraAtBodyOrigin();
    if (!base_frame_.empty() && !cameraMounting(*it, &camera)) {
      ++it;  // kept until TF has the mounting
      continue;
    }
    addLoop(*it, q->second, m->second, camera);
    added = true;
    it = pending_loops_.erase(it);
  }
  if (added) {
    const pose_graph::SolveSummary s = graph_->optimize();
    ROS_INFO("bowg_pose_graph_node: %zu keyframes, %zu loops (%zu metric): %s", graph_->size(),
             loops_, metric_loops_, s.report.c_str());
    if (use_ground_truth_) reportTrajectoryError();
  }
  return added;
}

void LivePoseGraph::reportTrajectoryError() {
  pose_graph::PoseVector truth;
  std::vector<Eigen::Vector3d> corrected, odometry;
  std::size_t first = node_stamps_.size();  // the first node with ground truth
  for (std::size_t i = 0; i < node_stamps_.size(); ++i) {
    if (!node_has_truth_[i]) continue;
    if (first == node_stamps_.size()) first = i;
    truth.push_back(node_truth_[i]);
    corrected.push_back(graph_->pose(i).translation());
    odometry.push_back(node_odometry_[i].translation());
  }
  if (truth.empty()) {
    ROS_WARN("bowg_pose_graph_node: no ground truth on %s at any of the %zu keyframes' stamps",
             ground_truth_sub_.getTopic().c_str(), node_stamps_.size());
    return;
  }
  // The truth's world frame is its own: carried onto the odometry at the
  // first keyframe it covers (node 0, where the graph is held, when the
  // truth was there from the start).
  const std::vector<Eigen::Vector3d> truth_here =
      pose_graph::anchoredTruth(truth, 0, node_odometry_[first]);
  const pose_graph::TrajectoryError after = pose_graph::positionError(corrected, truth_here);
  const pose_graph::TrajectoryError before = pose_graph::positionError(odometry, truth_here);
  // The keyframes left out of the graph are counted beside it: a status
  // that trails the odometry by more than the horizon has no pose.
  ROS_INFO(
      "bowg_pose_graph_node: position RMSE against the ground truth at %zu of %zu "
      "keyframes: corrected path %.3f m, odometry %.3f m (%zu keyframes skipped without "
      "odometry, %zu statuses lost)",
      truth.size(), node_stamps_.size(), after.rmse, before.rmse, skipped_keyframes_,
      lost_keyframes_);
}

bool LivePoseGraph::cameraMounting(const bowg_ros::LoopClosure& loop,
                                   Eigen::Isometry3d* body_T_optical) {
  try {
    // The mounting is static: the latest transform.
    *body_T_optical = tf2::transformToEigen(
        tf_buffer_.lookupTransform(base_frame_, loop.header.frame_id, ros::Time(0)));
    return true;
  } catch (const tf2::TransformException& e) {
    ROS_WARN_THROTTLE(5.0,
                      "bowg_pose_graph_node: loop %u -> %u waits for the transform %s <- '%s' "
                      "(%s); %zu loops wait",
                      loop.query_id, loop.match_id, base_frame_.c_str(),
                      loop.header.frame_id.c_str(), e.what(), pending_loops_.size());
    return false;
  }
}

void LivePoseGraph::publish() {
  nav_msgs::Path path, odometry_path;
  path.header.frame_id = odometry_path.header.frame_id = map_frame_;
  if (!node_stamps_.empty()) {
    path.header.stamp = odometry_path.header.stamp = ros::Time(node_stamps_.back());
  }
  for (std::size_t i = 0; i < node_stamps_.size(); ++i) {
    path.poses.push_back(toPoseStamped(graph_->pose(i), node_stamps_[i], map_frame_));
    odometry_path.poses.push_back(toPoseStamped(node_odometry_[i], node_stamps_[i], map_frame_));
  }
  path_pub_.publish(path);
  odometry_path_pub_.publish(odometry_path);
  visualization_msgs::Marker loops;
  loops.header = path.header;
  loops.ns = "loops";
  loops.type = visualization_msgs::Marker::LINE_LIST;
  loops.action = visualization_msgs::Marker::ADD;
  loops.pose.orientation.w = 1;
  loops.scale.x = 0.02;  // line width, m
  loops.color.r = 0.1f;
  loops.color.g = 0.7f;
  loops.color.b = 0.2f;
  loops.color.a = 1.0f;
  for (const auto& l : loop_nodes_) {
    for (std::size_t node : {l.first, l.second}) {
      geometry_msgs::Point p;
      p.x = path.poses[node].pose.position.x;
      p.y = path.poses[node].pose.position.y;
      p.z = path.poses[node].pose.position.z;
      loops.points.push_back(p);
    }
  }
  loops_pub_.publish(loops);
  // map -> odom: what turns the latest keyframe's odometry pose into its
  // corrected one (REP-105; identity until a loop moves the graph). Once per
  // keyframe: TF refuses a second transform at the same stamp.
  if (tf_broadcaster_ && !node_stamps_.empty() && !odom_frame_.empty() &&
      node_stamps_.back() > last_tf_stamp_) {
    last_tf_stamp_ = node_stamps_.back();
    const Eigen::Isometry3d map_T_odom =
        graph_->pose(node_stamps_.size() - 1) * node_odometry_.back().inverse();
    geometry_msgs::TransformStamped t = tf2::eigenToTransform(map_T_odom);
    t.header.stamp = ros::Time(node_stamps_.back());
    t.header.frame_id = map_frame_;
    t.child_frame_id = odom_frame_;
    tf_broadcaster_->sendTransform(t);
  }
}

}  // namespace pose_graph_node
}  // namespace bowg
