// bowg_generate_pipe_sequence's per-frame outputs (sequence_outputs.h): the
// image folder, the PNG of each frame, the rows of poses.csv, odometry.csv
// and missions.csv and the poses for the ground truth; the bag messages are
// bag_output's.
#include "sequence_outputs.h"

#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <ostream>
#include <stdexcept>
#include <string>

#include "bowg/core/atomic_file.h"
#include "bowg_evaluation/intrinsics_file.h"
#include "bowg_pipe_sim/pipe_renderer.h"

namespace bowg {
namespace generate_pipe_sequence_app {
namespace {

void makeImageFolder(const std::string& path) {
  ::mkdir(path.c_str(), 0755);
  struct stat st;
  if (::stat(path.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    throw std::runtime_error("cannot create the image folder " + path);
  }
}

void writeFramePng(const std::string& folder, int index, const cv::Mat& image) {
  char name[32];
  std::snprintf(name, sizeof(name), "/frame_%06d.png", index);
  if (!cv::imwrite(folder + name, image)) {
    throw std::runtime_error("cannot write " + folder + name);
  }
}

/// frame,stamp,x,y,z,qx,qy,qz,qw: the columns poses.csv and odometry.csv
/// share, so that their rows compare column by column.
void writePoseColumns(std::ostream& out, const pipe_sim::FrameState& f,
                      const pipe_sim::CameraPose& pose, const cv::Vec4d& q) {
  out << f.index << "," << std::fixed << f.stamp << "," << pose.position[0] << ","
      << pose.position[1] << "," << pose.position[2] << "," << q[0] << "," << q[1] << "," << q[2]
      << "," << q[3];
}

eval::TravelPose travelPoseOf(const pipe_sim::FrameState& f) {
  eval::TravelPose tp;
  tp.x = f.pose.position[0];
  tp.y = f.pose.position[1];
  tp.z = f.pose.position[2];
  tp.hx = f.tangent[0];
  tp.hy = f.tangent[1];
  tp.hz = f.tangent[2];
  // The ground truth's "immediate past" is metres driven: backing up 1 m
  // and coming forward again is 2 m, not 0.
  tp.distance = f.odometer;
  return tp;
}

}  // namespace

SequenceOutputs::SequenceOutputs(const Args& args)
    : images_(args.images), bag_path_(args.bag), camera_(args.camera), odometry_(args.odometry) {
  if (!args.images.empty()) makeImageFolder(args.images);
  if (!args.bag.empty()) {
    bag_.reset(new BagOutput(args.bag, args.compression, args.bag_images, args.camera));
  }
  // distance: position along the route; odometer: metres driven (they differ
  // once the robot backs up).
  poses_csv_ << "frame,stamp,x,y,z,qx,qy,qz,qw,roll_deg,exposure,distance,odometer\n";
  odometry_csv_ << "frame,stamp,x,y,z,qx,qy,qz,qw\n";
  // A comment line, so that the header is not mistaken for a mission.
  missions_csv_ << "# first_frame,mission_id,name\n";
}

void SequenceOutputs::startMission(int first_frame, int id, const std::string& name,
                                   const pipe_sim::OdometryNoise& noise) {
  missions_csv_ << first_frame << "," << id << "," << name << "\n";
  // A robot inspecting again months later starts its odometry afresh: the
  // drift of the first mission does not carry over.
  odometry_ = pipe_sim::OdometrySimulator(noise);
  if (bag_) bag_->startOdometryRun();
}

void SequenceOutputs::add(const pipe_sim::FrameState& f, const cv::Mat& image) {
  const cv::Vec4d q = pipe_sim::rotationToQuaternion(f.pose.R_world_body);
  if (bag_) bag_->write(f, image, q);
  if (!images_.empty()) writeFramePng(images_, f.index, image);
  writePoseColumns(poses_csv_, f, f.pose, q);
  poses_csv_ << "," << f.roll_rad * 180 / M_PI << "," << f.exposure << "," << f.distance << ","
             << f.odometer << "\n";
  travel_.push_back(travelPoseOf(f));

  const pipe_sim::CameraPose odometry = odometry_.step(f.pose);
  const cv::Vec4d q_odometry = pipe_sim::rotationToQuaternion(odometry.R_world_body);
  if (bag_) bag_->writeOdometry(f, odometry, q_odometry, odometry_.covariance());
  writePoseColumns(odometry_csv_, f, odometry, q_odometry);
  odometry_csv_ << "\n";
  odometry_drift_m_ = cv::norm(odometry.position - f.pose.position);
}

void SequenceOutputs::finish() {
  if (bag_) bag_->finish();
  if (!images_.empty()) {
    bowg::writeFileAtomically(images_ + "/poses.csv", poses_csv_.str());
    bowg::writeFileAtomically(images_ + "/odometry.csv", odometry_csv_.str());
    CameraIntrinsics k;
    k.valid = true;
    k.fx = camera_.fx;
    k.fy = camera_.fy;
    k.cx = camera_.cx;
    k.cy = camera_.cy;
    bowg::writeFileAtomically(images_ + "/intrinsics.csv", eval::intrinsicsToCsv(k));
    bowg::writeFileAtomically(images_ + "/missions.csv", missions_csv_.str());
  }
  if (bag_) {
    bowg::writeFileAtomically(bagStem(bag_path_) + "_missions.csv", missions_csv_.str());
  }
}

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
