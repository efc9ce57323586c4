// The bag writer of bowg_generate_pipe_sequence (bag_output.h): the four
// messages of a frame and the image in each --bag-images format.
#include "bag_output.h"

#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/image_encodings.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Header.h>

#include <cstdint>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "bowg_ros/OdometerStamped.h"

namespace bowg {
namespace generate_pipe_sequence_app {
namespace {

// One frame into the bag in the chosen format (--bag-images); every format
// holds the same grey image (bgr8: three equal channels, which OpenCV's luma
// weights turn back into the same grey; jpeg: lossy, decoded alike live and
// offline).
void writeBagImage(rosbag::Bag* bag, const std_msgs::Header& header, const cv::Mat& grey,
                   const std::string& format) {
  if (format == "jpeg") {
    sensor_msgs::CompressedImage msg;
    msg.header = header;
    msg.format = "mono8; jpeg compressed mono8";
    if (!cv::imencode(".jpg", grey, msg.data, {cv::IMWRITE_JPEG_QUALITY, 95})) {
      throw std::runtime_error("cannot encode frame " + std::to_string(header.seq) + " as JPEG");
    }
    bag->write("/camera/image_raw/compressed", header.stamp, msg);
    return;
  }
  cv::Mat pixels = grey;
  if (format == "bgr8") cv::cvtColor(grey, pixels, cv::COLOR_GRAY2BGR);
  sensor_msgs::Image msg;
  msg.header = header;
  msg.height = pixels.rows;
  msg.width = pixels.cols;
  msg.encoding =
      format == "bgr8" ? sensor_msgs::image_encodings::BGR8 : sensor_msgs::image_encodings::MONO8;
  msg.is_bigendian = 0;
  msg.step = static_cast<std::uint32_t>(pixels.cols * pixels.elemSize());
  const cv::Mat packed = pixels.isContinuous() ? pixels : pixels.clone();
  msg.data.assign(packed.data, packed.data + packed.total() * packed.elemSize());
  bag->write("/camera/image_raw", header.stamp, msg);
}

ros::Time stampOf(double seconds) {
  ros::Time t;
  t.fromSec(seconds);
  return t;
}

sensor_msgs::CameraInfo cameraInfoOf(const pipe_sim::CameraModel& camera) {
  sensor_msgs::CameraInfo info;
  info.header.frame_id = "camera_optical_frame";
  info.width = camera.width;
  info.height = camera.height;
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {camera.fx, 0, camera.cx, 0, 0, camera.fy, camera.cy, 0, 0, 0, 1, 0};
  return info;
}

geometry_msgs::PoseStamped poseOf(const pipe_sim::FrameState& f, const cv::Vec4d& q,
                                  const ros::Time& stamp) {
  geometry_msgs::PoseStamped pose;
  pose.header.seq = f.index;
  pose.header.stamp = stamp;
  pose.header.frame_id = "map";
  pose.pose.position.x = f.pose.position[0];
  pose.pose.position.y = f.pose.position[1];
  pose.pose.position.z = f.pose.position[2];
  pose.pose.orientation.x = q[0];
  pose.pose.orientation.y = q[1];
  pose.pose.orientation.z = q[2];
  pose.pose.orientation.w = q[3];
  return pose;
}

}  // namespace

BagOutput::BagOutput(const std::string& path, const std::string& compression,
                     const std::string& image_format, const pipe_sim::CameraModel& camera)
    : path_(path), tmp_path_(path + ".tmp"), image_format_(image_format) {
  bag_.open(tmp_path_, rosbag::bagmode::Write);
  bag_.setCompression(compression == "lz4"   ? rosbag::compression::LZ4
                      : compression == "bz2" ? rosbag::compression::BZ2
                                             : rosbag::compression::Uncompressed);
  info_ = cameraInfoOf(camera);
}

void BagOutput::write(const pipe_sim::FrameState& f, const cv::Mat& image, const cv::Vec4d& q) {
  const ros::Time stamp = stampOf(f.stamp);
  std_msgs::Header header;
  header.seq = f.index;
  header.stamp = stamp;
  header.frame_id = info_.header.frame_id;
  writeBagImage(&bag_, header, image, image_format_);
  info_.header.seq = f.index;
  info_.header.stamp = stamp;
  bag_.write("/camera/camera_info", stamp, info_);
  const geometry_msgs::PoseStamped truth = poseOf(f, q, stamp);
  bag_.write("/ground_truth/pose", stamp, truth);
  // The same pose as nav_msgs/Odometry, the type of a simulator's or motion
  // capture's ground-truth odometry, which bowg_pose_graph_node compares its
  // paths with (its ground_truth input).
  nav_msgs::Odometry truth_odometry;
  truth_odometry.header = truth.header;
  truth_odometry.child_frame_id = "camera_link";
  truth_odometry.pose.pose = truth.pose;
  bag_.write("/ground_truth/odom", stamp, truth_odometry);
}

void BagOutput::writeOdometry(const pipe_sim::FrameState& f, const pipe_sim::CameraPose& pose,
                              const cv::Vec4d& q, const cv::Matx<double, 6, 6>& covariance) {
  nav_msgs::Odometry odometry;
  odometry.header.seq = f.index;
  odometry.header.stamp = stampOf(f.stamp);
  // "odom" coincides with "map" at frame 0 (the odometry starts at the true
  // pose) and drifts away from it.
  odometry.header.frame_id = "odom";
  odometry.child_frame_id = "camera_link";
  odometry.pose.pose.position.x = pose.position[0];
  odometry.pose.pose.position.y = pose.position[1];
  odometry.pose.pose.position.z = pose.position[2];
  odometry.pose.pose.orientation.x = q[0];
  odometry.pose.pose.orientation.y = q[1];
  odometry.pose.pose.orientation.z = q[2];
  odometry.pose.pose.orientation.w = q[3];
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) odometry.pose.covariance[6 * r + c] = covariance(r, c);
  }
  // The twist stays zero: the pose is what the pose-graph examples read.
  bag_.write("/odom", stampOf(f.stamp - kOdometerLead), odometry);
  const cv::Vec3d position(pose.position[0], pose.position[1], pose.position[2]);
  if (has_position_) odometer_ += cv::norm(position - last_position_);
  has_position_ = true;
  last_position_ = position;
  std_msgs::Float64 reading;
  reading.data = odometer_;
  bag_.write("/odometer", stampOf(f.stamp - kOdometerLead), reading);
  // The same reading stamped when measured, with the frame: a replay's
  // nodelet gives each frame the reading at its stamp, whatever order the
  // two topics arrive in.
  bowg_ros::OdometerStamped stamped;
  stamped.header.seq = f.index;
  stamped.header.stamp = stampOf(f.stamp);
  stamped.header.frame_id = "odom";
  stamped.metres = odometer_;
  bag_.write("/odometer_stamped", stampOf(f.stamp - kOdometerLead), stamped);
}

void BagOutput::finish() {
  bag_.close();
  if (std::rename(tmp_path_.c_str(), path_.c_str()) != 0) {
    throw std::runtime_error("cannot rename " + tmp_path_ + " to " + path_);
  }
}

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
