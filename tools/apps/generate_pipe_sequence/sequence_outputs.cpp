// bowg_generate_pipe_sequence's per-frame outputs (sequence_outputs.h): the
// image folder, the PNG of each frame, the rows of poses.csv and the poses
// for the ground truth; the bag messages are bag_output's.
#include "sequence_outputs.h"

#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "bowg/core/atomic_file.h"
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

SequenceOutputs::SequenceOutputs(const Args& args) : images_(args.images) {
  if (!args.images.empty()) makeImageFolder(args.images);
  if (!args.bag.empty()) {
    bag_.reset(new BagOutput(args.bag, args.compression, args.bag_images, args.camera));
  }
  // distance: position along the route; odometer: metres driven (they differ
  // once the robot backs up).
  poses_csv_ << "frame,stamp,x,y,z,qx,qy,qz,qw,roll_deg,exposure,distance,odometer\n";
}

void SequenceOutputs::add(const pipe_sim::FrameState& f, const cv::Mat& image) {
  const cv::Vec4d q = pipe_sim::rotationToQuaternion(f.pose.R_world_body);
  if (bag_) bag_->write(f, image, q);
  if (!images_.empty()) writeFramePng(images_, f.index, image);
  poses_csv_ << f.index << "," << std::fixed << f.stamp << "," << f.pose.position[0] << ","
             << f.pose.position[1] << "," << f.pose.position[2] << "," << q[0] << "," << q[1] << ","
             << q[2] << "," << q[3] << "," << f.roll_rad * 180 / M_PI << "," << f.exposure << ","
             << f.distance << "," << f.odometer << "\n";
  travel_.push_back(travelPoseOf(f));
}

void SequenceOutputs::finish() {
  if (bag_) bag_->finish();
  if (!images_.empty()) {
    bowg::writeFileAtomically(images_ + "/poses.csv", poses_csv_.str());
  }
}

}  // namespace generate_pipe_sequence_app
}  // namespace bowg
