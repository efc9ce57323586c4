// Frames of an image folder or a bag (frame_loading.h).
#include "frame_loading.h"

#include <dirent.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/Float64.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <limits>
#include <string>

#include "bag_odometry.h"
#include "bowg/core/errors.h"
#include "bowg/features/image_decoding.h"
#include "bowg_bag_reading/bag_images.h"
#include "bowg_evaluation/intrinsics_file.h"
#include "bowg_evaluation/odometry_file.h"
#include "bowg_ros/ros_conversions.h"
#include "console_output.h"

namespace bowg {
namespace evaluate_app {

using namespace bowg::eval;

namespace {

std::vector<std::string> listImages(const std::string& dir) {
  DIR* d = ::opendir(dir.c_str());
  if (!d) throw IoError("cannot open the image folder " + dir + ": " + std::strerror(errno));
  std::vector<std::string> files;
  while (dirent* e = ::readdir(d)) {
    std::string name = e->d_name, lower = name;
    std::transform(lower.begin(), lower.end(), lower.begin(), ::tolower);
    for (const char* ext : {".png", ".jpg", ".jpeg", ".pgm", ".bmp"}) {
      const std::string x(ext);
      if (lower.size() > x.size() && lower.compare(lower.size() - x.size(), x.size(), x) == 0) {
        files.push_back(dir + "/" + name);
        break;
      }
    }
  }
  ::closedir(d);
  std::sort(files.begin(), files.end());
  if (files.empty()) throw IoError("no png/jpg/jpeg/pgm/bmp image in " + dir);
  return files;
}

// A refused image is kept as a frame without features, so that frame i
// stays image i of the folder or bag (the ground truth's numbering).
void skipImage(const std::string& what, const ImageCheck& check, ImageProblemCounts* skipped) {
  std::fprintf(stderr, "\nwarning: %s skipped (%s): a frame without features\n", what.c_str(),
               check.message().c_str());
  skipped->add(check.problem);
}

void reportSkipped(const ImageProblemCounts& skipped, std::size_t images) {
  if (skipped.total() == 0) return;
  std::fprintf(stderr, "warning: %zu of %zu images skipped (%s)\n", skipped.total(), images,
               skipped.summary().c_str());
}

// Frames in the order they come, each with its features extracted once.
class FrameCollector {
 public:
  FrameCollector(const FeatureExtractor& extractor, std::vector<FrameInput>* frames)
      : extractor_(extractor), frames_(frames) {}
  // `grey` empty: a frame without features (unreadable, or left out).
  void add(const cv::Mat& grey, double stamp, const CameraIntrinsics& k) {
    FrameInput f;
    // rosbag stamps may repeat (several cameras, a replayed clock): keep
    // them strictly increasing as the detector requires.
    f.stamp = frames_->empty() ? stamp : std::max(stamp, frames_->back().stamp + 1e-6);
    f.intrinsics = k;
    // std::clock: the process's CPU time (every thread's: OpenCV's workers
    // included); nothing else runs while the frames load.
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t cpu0 = std::clock();
    f.features = grey.empty() ? ImageFeatures() : extractor_.extract(grey);
    f.feature_cpu_ms = 1000.0 * static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
    f.feature_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    frames_->push_back(std::move(f));
  }

 private:
  const FeatureExtractor& extractor_;
  std::vector<FrameInput>* frames_;
};

std::vector<FrameInput> loadFolder(const Args& a, const FeatureExtractor& extractor) {
  std::vector<FrameInput> frames;
  FrameCollector collect(extractor, &frames);
  ProgressBar bar("features", a.quiet);
  const CameraIntrinsics intrinsics =
      a.intrinsics.empty() ? CameraIntrinsics() : eval::readIntrinsics(a.intrinsics);
  std::vector<std::string> files = listImages(a.images);
  if (a.max_frames > 0 && files.size() > static_cast<std::size_t>(a.max_frames))
    files.resize(a.max_frames);
  ImageProblemCounts skipped;
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (static_cast<long>(i) < a.skip_frames) {  // left out: only its place is kept
      collect.add(cv::Mat(), i / a.rate, intrinsics);
      continue;
    }
    ImageCheck check;
    const cv::Mat grey = readGreyImageFile(files[i], extractor.options(), &check);
    if (!check.ok()) skipImage(files[i], check, &skipped);
    collect.add(grey, i / a.rate, intrinsics);
    bar(i + 1, files.size());
  }
  const std::size_t used = files.size() - std::min<std::size_t>(files.size(), a.skip_frames);
  reportSkipped(skipped, used);
  // (Nothing used: skipFrames says why.)
  if (used > 0 && skipped.total() == used) throw FormatError("no readable image in " + a.images);
  return frames;
}

std::vector<FrameInput> loadBag(const Args& a, const FeatureExtractor& extractor) {
  std::vector<FrameInput> frames;
  FrameCollector collect(extractor, &frames);
  ProgressBar bar("features", a.quiet);
  rosbag::Bag bag;
  try {
    bag.open(a.bag, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    throw IoError("cannot open the bag " + a.bag + ": " + e.what());
  }
  std::vector<std::string> topics{a.image_topic};
  if (a.info_topic != "none") topics.push_back(a.info_topic);
  if (!a.odometer_topic.empty()) topics.push_back(a.odometer_topic);
  if (!a.odom_topic.empty()) topics.push_back(a.odom_topic);
  BagOdometry odometer(a.bag, a.odometer_topic, a.odom_topic, &frames);
  rosbag::View view(bag, rosbag::TopicQuery(topics));
  odometer.expectStamped(view);
  rosbag::View images_only(bag, rosbag::TopicQuery(a.image_topic));
  std::size_t total = images_only.size();
  if (total == 0) throw FormatError("the bag " + a.bag + " has no messages on " + a.image_topic);
  if (a.max_frames > 0) total = std::min<std::size_t>(total, a.max_frames);
  CameraIntrinsics intrinsics;
  ImageProblemCounts skipped;
  for (const rosbag::MessageInstance& m : view) {
    // Past the last frame only the readings its stamp may still wait for.
    if (frames.size() >= total && !odometer.waiting()) break;
    if (m.getTopic() == a.info_topic) {
      // The first valid camera_info, checked as the nodelet checks it.
      const sensor_msgs::CameraInfo::ConstPtr info = m.instantiate<sensor_msgs::CameraInfo>();
      if (info && !intrinsics.valid) intrinsics = bowg_ros::toIntrinsics(*info);
      continue;
    }
    if (odometer.reads(m.getTopic())) {
      odometer.reading(m);
      continue;
    }
    if (frames.size() >= total) continue;
    if (static_cast<long>(frames.size()) < a.skip_frames) {  // left out: only its place is kept
      collect.add(cv::Mat(), 0.0, intrinsics);  // a stamp that never raises the next frame's
      odometer.frameAdded(m.getTime().toSec());
      continue;
    }
    const bowg::bag::BagImage image = bowg::bag::readBagImage(m, a.bag, extractor.options());
    if (!image.check.ok()) {
      skipImage("frame " + std::to_string(frames.size()), image.check, &skipped);
    }
    collect.add(image.grey, image.stamp.toSec(), intrinsics);
    odometer.frameAdded(image.stamp.toSec());
    bar(frames.size(), total);
  }
  odometer.finish();
  reportSkipped(skipped, frames.size());
  return frames;
}

}  // namespace

std::vector<FrameInput> loadFrames(const Args& a, const FeatureExtractor& extractor) {
  return a.images.empty() ? loadBag(a, extractor) : loadFolder(a, extractor);
}

namespace {

// Gives every frame its value of `values` (one per frame at least, read
// from `path`: `what` names them in the error).
template <typename T, typename Set>
void attachPerFrame(const std::string& path, const std::vector<T>& values, const char* what,
                    std::vector<FrameInput>* frames, Set set) {
  if (values.size() < frames->size()) {
    throw FormatError(path + ": " + what + " for " + std::to_string(values.size()) +
                      " frames, the input has " + std::to_string(frames->size()));
  }
  for (std::size_t i = 0; i < frames->size(); ++i) set(&(*frames)[i], values[i]);
}

}  // namespace

void attachOdometry(const std::string& path, std::vector<FrameInput>* frames) {
  attachPerFrame(path, readOdometry(path), "odometers", frames,
                 [](FrameInput* f, double odometer) { f->odometer = odometer; });
}

void attachOdometryPositions(const std::string& path, std::vector<FrameInput>* frames) {
  attachPerFrame(path, readOdometryPoses(path), "odometry positions", frames,
                 [](FrameInput* f, const OdometryPose& p) {
                   f->position = p.position;
                   f->heading = p.heading;
                 });
}

OdometryInput odometryInputOf(const std::vector<eval::FrameInput>& frames) {
  OdometryInput input = OdometryInput::kNone;
  for (const eval::FrameInput& f : frames) {
    const OdometryInput i = odometryInput(f.odometer, f.position);
    if (i == OdometryInput::kPositions) return i;
    if (i == OdometryInput::kOdometer) input = i;
  }
  return input;
}

std::size_t framesWithHeading(const std::vector<eval::FrameInput>& frames) {
  return static_cast<std::size_t>(std::count_if(
      frames.begin(), frames.end(), [](const eval::FrameInput& f) { return f.heading.known(); }));
}

}  // namespace evaluate_app
}  // namespace bowg
