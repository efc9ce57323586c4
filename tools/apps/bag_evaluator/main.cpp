// bowg_bag_evaluator: scores the LoopDetectorNodelet live, while `rosbag play`
// feeds it a bag (launch/evaluate_bag.launch). It reads the bag once, only to
// map image stamps to frame indices (the ground truth's indexing), listens to
// the nodelet's LoopClosure and KeyframeStatus outputs, and when the bag is
// over prints and writes the summary bowg_evaluate prints for the same bag
// (docs/evaluation.md, "Live evaluation"), the loops (detections_nodelet.csv)
// and their relative poses (loop_poses_nodelet.csv).
//
// Against reference maps (~map_bags: the bags the nodelet's ~reference_maps
// were recorded from, every image a keyframe, in order), the maps' images
// are frames 0..M-1 and the played bag's follow: the numbering of
// `bowg_evaluate --map` and of a ground truth over the maps' bags and the
// played one together.
//
// The bag is over when the first of these happens:
//  - the KeyframeStatus of the bag's last image arrived (plus ~grace, for
//    the LoopClosure of that frame, which travels on another connection);
//  - nothing arrived for ~idle_timeout wall seconds after the first output;
//  - ~bag_duration wall seconds passed since the first output (0 = off);
//  - a std_msgs/Empty on ~done;
//  - nothing at all arrived within ~startup_timeout (exit code 1).
// Wall time throughout: with use_sim_time the clock stops with the bag.
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/Empty.h>
#include <sys/stat.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "bowg/core/atomic_file.h"
#include "bowg/core/errors.h"
#include "bowg_bag_reading/bag_images.h"
#include "bowg_evaluation/ground_truth.h"
#include "bowg_evaluation/loop_pose_file.h"
#include "bowg_evaluation/metrics.h"
#include "bowg_evaluation/online_run.h"
#include "bowg_evaluation/reference_maps.h"
#include "bowg_evaluation/stamp_index.h"
#include "bowg_ros/KeyframeStatus.h"
#include "bowg_ros/LoopClosure.h"

namespace {

using bowg::eval::StampIndex;

// Header stamps (ns) of the image messages on `topic`, in bag order.
std::vector<std::int64_t> imageStamps(const std::string& path, const std::string& topic) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw bowg::IoError("cannot open the bag " + path + ": " + e.what());
  }
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  std::vector<std::int64_t> stamps;
  for (const rosbag::MessageInstance& m : view) {
    const ros::Time stamp = bowg::bag::bagImageStamp(m, path);
    stamps.push_back(static_cast<std::int64_t>(stamp.toNSec()));
  }
  if (stamps.empty()) throw bowg::FormatError("the bag " + path + " has no message on " + topic);
  return stamps;
}

class BagEvaluator {
 public:
  BagEvaluator(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
    // Subscribe first: outputs published while the bag is being read wait
    // in the subscriber queues (no callback runs before the spinner starts).
    loop_sub_ = nh.subscribe("loop_closure", 1000, &BagEvaluator::loopCallback, this);
    status_sub_ = nh.subscribe("keyframe_status", 1000, &BagEvaluator::statusCallback, this);
    done_sub_ = pnh.subscribe("done", 1, &BagEvaluator::doneCallback, this);

    std::string bag_path, gt_path, image_topic;
    if (!pnh.getParam("bag", bag_path) || bag_path.empty()) {
      throw std::invalid_argument("~bag (the played bag file) is required");
    }
    std::vector<std::string> map_bags;
    if (pnh.hasParam("map_bags") && !pnh.getParam("map_bags", map_bags)) {
      throw std::invalid_argument("~map_bags must be a list of bag files");
    }
    pnh.param<std::string>("image_topic", image_topic, "/camera/image_raw");
    pnh.param<std::string>("gt", gt_path, "");
    pnh.param<std::string>("output_dir", output_dir_, "bowg_bag_evaluation");
    pnh.param("idle_timeout", idle_timeout_, 10.0);
    pnh.param("startup_timeout", startup_timeout_, 120.0);
    pnh.param("bag_duration", bag_duration_, 0.0);
    pnh.param("grace", grace_, 1.0);
    double tolerance_s = 1e-3;
    pnh.param("stamp_tolerance", tolerance_s, tolerance_s);
    if (!(idle_timeout_ > 0) || !(startup_timeout_ > 0) || bag_duration_ < 0 || grace_ < 0 ||
        tolerance_s < 0) {
      throw std::invalid_argument(
          "~idle_timeout and ~startup_timeout must be > 0; ~bag_duration, ~grace and "
          "~stamp_tolerance >= 0");
    }

    // The maps' images first, then the played bag's.
    std::vector<std::int64_t> stamps;
    std::string maps_line;
    for (const std::string& path : map_bags) {
      const std::vector<std::int64_t> map_stamps = imageStamps(path, image_topic);
      stamps.insert(stamps.end(), map_stamps.begin(), map_stamps.end());
      maps_line += " " + path + " (" + std::to_string(map_stamps.size()) + ")";
    }
    const int first_frame = static_cast<int>(stamps.size());
    const std::vector<std::int64_t> played = imageStamps(bag_path, image_topic);
    stamps.insert(stamps.end(), played.begin(), played.end());
    index_.reset(new StampIndex(stamps));
    // Never so wide that a stamp could reach two frames.
    tolerance_ns_ = index_->safeTolerance(bowg::eval::secondsToNanoseconds(tolerance_s));
    run_.reset(new bowg::eval::OnlineRun(played.size(), first_frame));
    has_gt_ = !gt_path.empty();
    // Only the played frames are queries.
    if (has_gt_) {
      gt_ = bowg::eval::groundTruthAfterMaps(bowg::eval::readGroundTruth(gt_path), first_frame,
                                             static_cast<std::size_t>(first_frame));
    }
    title_ = "bag: " + bag_path + " (" + std::to_string(played.size()) + " images on " +
             image_topic + ")\n" +
             (map_bags.empty() ? ""
                               : "map bags (frames 0-" + std::to_string(first_frame - 1) +
                                     "):" + maps_line + "\n") +
             (has_gt_ ? "ground truth: " + gt_path + "\n" : "");
    ROS_INFO("bowg_bag_evaluator: %zu images in %s; waiting for the nodelet's outputs",
             played.size(), bag_path.c_str());
    start_ = ros::WallTime::now();
    timer_ = nh.createWallTimer(ros::WallDuration(0.1), &BagEvaluator::check, this);
  }

  int exitCode() const { return exit_code_; }

 private:
  void touch() {
    const ros::WallTime now = ros::WallTime::now();
    if (first_output_.isZero()) first_output_ = now;
    last_output_ = now;
  }

  void loopCallback(const bowg_ros::LoopClosure::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    touch();
    const int query =
        index_->find(static_cast<std::int64_t>(msg->query_stamp.toNSec()), tolerance_ns_);
    const int match =
        index_->find(static_cast<std::int64_t>(msg->match_stamp.toNSec()), tolerance_ns_);
    // Counted per mission where missions matter: a named one or another
    // mission than the query's.
    const bool named = !msg->match_mission_name.empty() || msg->match_mission != msg->query_mission;
    run_->addLoop(
        query, match, msg->score,
        named ? std::to_string(msg->match_mission) + " '" + msg->match_mission_name + "'" : "");
    if (query >= 0 && match >= 0 && msg->has_relative_pose) {
      loop_poses_.push_back(loopPoseOf(*msg, query, match));
    }
  }

  // The message's relative pose as bowg_evaluate writes it (loop_pose_file.h);
  // a loop without the scale says "no_scale" (the message does not carry
  // the detector's reason).
  static bowg::eval::LoopPose loopPoseOf(const bowg_ros::LoopClosure& m, int query, int match) {
    bowg::eval::LoopPose p;
    p.query = query;
    p.match = match;
    p.metric_status = m.translation_scale_known ? "estimated" : "no_scale";
    const geometry_msgs::Quaternion& q = m.relative_pose.pose.orientation;
    const Eigen::Matrix3d R =
        Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) {
        p.rotation[3 * r + c] = R(r, c);
        if (m.translation_scale_known)
          p.covariance[3 * r + c] = m.relative_pose.covariance[6 * r + c];
      }
    }
    const geometry_msgs::Point& t = m.relative_pose.pose.position;
    p.translation[0] = t.x;
    p.translation[1] = t.y;
    p.translation[2] = t.z;
    return p;
  }

  void statusCallback(const bowg_ros::KeyframeStatus::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    touch();
    const std::int64_t stamp = static_cast<std::int64_t>(msg->header.stamp.toNSec());
    const int frame = index_->find(stamp, tolerance_ns_);
    run_->addKeyframe(frame);
    if (frame >= 0 && static_cast<std::size_t>(frame) + 1 == index_->frames() &&
        last_frame_seen_.isZero()) {
      last_frame_seen_ = ros::WallTime::now();
    }
  }

  void doneCallback(const std_msgs::Empty::ConstPtr&) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (done_requested_.isZero()) done_requested_ = ros::WallTime::now();
  }

  void check(const ros::WallTimerEvent&) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) return;
    const ros::WallTime now = ros::WallTime::now();
    std::string why;
    if (!done_requested_.isZero() && (now - done_requested_).toSec() >= grace_) {
      why = "~done received";
    } else if (!last_frame_seen_.isZero() && (now - last_frame_seen_).toSec() >= grace_) {
      why = "the bag's last image was processed";
    } else if (!last_output_.isZero() && (now - last_output_).toSec() >= idle_timeout_) {
      why = "no output for ~idle_timeout";
    } else if (bag_duration_ > 0 && !first_output_.isZero() &&
               (now - first_output_).toSec() >= bag_duration_) {
      why = "~bag_duration elapsed";
    } else if (first_output_.isZero() && (now - start_).toSec() >= startup_timeout_) {
      why = "no output at all within ~startup_timeout (is the nodelet running, the bag playing?)";
      exit_code_ = 1;
    }
    if (why.empty()) return;
    finished_ = true;
    finish(why);
    ros::shutdown();
  }

  void finish(const std::string& why) {
    const std::string summary = bowg::eval::summarizeOnlineRun(*run_, has_gt_ ? &gt_ : nullptr,
                                                               title_ + "finished: " + why + "\n");
    std::printf("%s", summary.c_str());
    std::fflush(stdout);
    try {
      ::mkdir(output_dir_.c_str(), 0755);
      struct stat st;
      if (::stat(output_dir_.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
        throw bowg::IoError("cannot create the output folder " + output_dir_);
      }
      bowg::writeFileAtomically(output_dir_ + "/summary.txt", summary);
      bowg::writeFileAtomically(output_dir_ + "/detections_nodelet.csv",
                                bowg::eval::detectionsToCsv(run_->detections()));
      bowg::writeFileAtomically(output_dir_ + "/loop_poses_nodelet.csv",
                                bowg::eval::loopPosesToCsv(loop_poses_));
    } catch (const std::exception& e) {
      ROS_ERROR("bowg_bag_evaluator: %s", e.what());
      exit_code_ = 1;
    }
  }

  ros::Subscriber loop_sub_, status_sub_, done_sub_;
  ros::WallTimer timer_;
  std::mutex mutex_;
  std::unique_ptr<StampIndex> index_;
  std::unique_ptr<bowg::eval::OnlineRun> run_;
  std::vector<bowg::eval::LoopPose> loop_poses_;
  std::int64_t tolerance_ns_ = 0;
  bool has_gt_ = false;
  bowg::eval::GroundTruth gt_;
  std::string output_dir_, title_;
  double idle_timeout_ = 10, startup_timeout_ = 120, bag_duration_ = 0, grace_ = 1;
  ros::WallTime start_, first_output_, last_output_, last_frame_seen_, done_requested_;
  bool finished_ = false;
  int exit_code_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "bowg_bag_evaluator");
  ros::NodeHandle nh, pnh("~");
  try {
    BagEvaluator evaluator(nh, pnh);
    // Two threads: the timer's summary never waits behind a burst of outputs.
    ros::AsyncSpinner spinner(2);
    spinner.start();
    ros::waitForShutdown();
    return evaluator.exitCode();
  } catch (const std::exception& e) {
    ROS_FATAL("bowg_bag_evaluator: %s", e.what());
    return 1;
  }
}
