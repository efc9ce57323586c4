// Feature extraction (paper Sec. III-A): GFTT corners for the pipe setting or
// multi-scale ORB/FAST for the public datasets, described by 256-bit ORB
// rBRIEF or VINS-compatible plain BRIEF. The keypoint size is kept: it is the
// word-group radius s_t^(i).
#include "bowg/features/feature_extractor.h"

#include <algorithm>
#include <cmath>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <utility>

#include "bowg/core/bounded_file.h"
#include "bowg/core/errors.h"
#include "bowg/features/brief_descriptor.h"
#include "bowg/features/brief_pattern.h"
#include "bowg/features/descriptor_conversion.h"
#include "bowg/features/image_decoding.h"
#include "bowg/features/orb_descriptor.h"
#include "bowg/features/orientation.h"
#include "features/gftt_corners.h"

namespace bowg {
namespace {

// Usable pixels = non-zero in any channel, as 0/255 CV_8UC1. Read like any
// input image: BoundedFile (no FIFO, device or huge file), then the header
// check (format, truncation, max_image_pixels) before decoding.
cv::Mat loadMask(const std::string& path, const FeatureOptions& options) {
  const std::string bytes = readBoundedFile(path, FileKind::kImage, "feature mask image");
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  const ImageCheck check = checkEncodedImage(data, bytes.size(), options);
  if (!check.ok()) throw FormatError("feature mask " + path + ": " + check.message());
  const cv::Mat encoded(1, static_cast<int>(bytes.size()), CV_8UC1,
                        const_cast<std::uint8_t*>(data));
  cv::Mat raw;
  try {
    raw = cv::imdecode(encoded, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception&) {
    raw = cv::Mat();
  }
  if (raw.empty()) {
    throw FormatError("feature mask " + path + " is not an image OpenCV can decode");
  }
  if (raw.depth() != CV_8U) {
    throw FormatError("feature mask " + path + " must be an 8-bit image");
  }
  cv::Mat mask = raw;
  if (raw.channels() > 1) {
    std::vector<cv::Mat> planes;
    cv::split(raw, planes);
    mask = planes[0].clone();
    for (std::size_t i = 1; i < planes.size(); ++i) cv::max(mask, planes[i], mask);
  }
  cv::Mat binary;
  cv::compare(mask, 0, binary, cv::CMP_NE);
  return binary;
}

void checkImage(const cv::Mat& image, const FeatureOptions& options) {
  if (image.empty()) throw std::invalid_argument("FeatureExtractor::extract: image is empty");
  const std::string size = imageSizeProblem(image.cols, image.rows, options);
  if (!size.empty()) throw std::invalid_argument("FeatureExtractor::extract: image of " + size);
  if (image.channels() != 1) {
    throw std::invalid_argument(
        "FeatureExtractor::extract: image must be single-channel (grey), got " +
        std::to_string(image.channels()) + " channels");
  }
  if (image.depth() != CV_8U) {
    throw std::invalid_argument(
        "FeatureExtractor::extract: image must be 8-bit (CV_8U), got depth " +
        std::to_string(image.depth()));
  }
}

Keypoint toKeypoint(const cv::KeyPoint& kp, bool oriented) {
  Keypoint out;
  out.x = kp.pt.x;
  out.y = kp.pt.y;
  out.size = kp.size;
  out.angle = oriented ? kp.angle : -1.f;
  out.response = kp.response;
  out.octave = kp.octave;
  return out;
}

// How many of `total` features each of `levels` levels gets: cv::ORB's
// split (a geometric series of ratio 1 / scale_factor), the rest to the
// last level.
std::vector<int> featuresPerLevel(int total, double scale_factor, int levels) {
  std::vector<int> n(static_cast<std::size_t>(levels));
  const double factor = 1.0 / scale_factor;
  double desired = total * (1.0 - factor) / (1.0 - std::pow(factor, levels));
  int sum = 0;
  for (int l = 0; l + 1 < levels; ++l) {
    n[l] = cvRound(desired);
    sum += n[l];
    desired *= factor;
  }
  n[levels - 1] = std::max(total - sum, 0);
  return n;
}

// GFTT corners (Shi-Tomasi or Harris) on each of gftt_levels pyramid levels
// (level l the image shrunk by orb_scale_factor^l), with their corner
// quality as the response. A corner keeps ORB's conventions: its position in
// level-0 pixels, its size gftt_keypoint_size times the level's scale, its
// level as the octave; with `orientation_radius` > 0 its intensity-centroid
// angle measured on its level, on the unsmoothed image as ORB measures it.
// Corners whose `border` level pixels leave the level (insideOrbLevel's
// rule) are left out: their descriptor patch would leave it.
std::vector<cv::KeyPoint> detectGftt(const cv::Mat& image, const cv::Mat& mask,
                                     const FeatureOptions& o, int border, int orientation_radius) {
  GfttCornerOptions g;
  g.quality_level = o.gftt_quality_level;
  g.min_distance = o.gftt_min_distance;
  g.block_size = o.gftt_block_size;
  g.use_harris = o.gftt_use_harris;
  const std::vector<int> per_level =
      featuresPerLevel(o.gftt_max_corners, o.orb_scale_factor, o.gftt_levels);
  const OrbPyramid pyramid{o.orb_scale_factor, o.gftt_levels};
  std::vector<cv::KeyPoint> detected;
  // The shrunk levels, kept per thread like the corner buffers: each keeps
  // its size from frame to frame.
  thread_local std::vector<cv::Mat> shrunk, shrunk_mask;
  shrunk.resize(std::max<std::size_t>(shrunk.size(), o.gftt_levels));
  shrunk_mask.resize(shrunk.size());
  std::vector<cv::Point2f> corners;
  std::vector<float> quality;
  for (int l = 0; l < o.gftt_levels; ++l) {
    const double scale = std::pow(o.orb_scale_factor, l);
    cv::Mat level = image, level_mask = mask;
    if (l > 0) {
      const cv::Size size(cvRound(image.cols / scale), cvRound(image.rows / scale));
      if (size.width <= 2 * border || size.height <= 2 * border) break;
      cv::resize(image, shrunk[l], size, 0, 0, cv::INTER_LINEAR);
      level = shrunk[l];
      if (!mask.empty()) {
        cv::resize(mask, shrunk_mask[l], size, 0, 0, cv::INTER_NEAREST);
        level_mask = shrunk_mask[l];
      }
    }
    if (per_level[l] == 0) continue;
    g.max_corners = per_level[l];
    detectGfttCorners(level, level_mask, g, corners, quality, static_cast<std::size_t>(l));
    for (std::size_t i = 0; i < corners.size(); ++i) {
      const cv::Point2f c = corners[i];
      cv::KeyPoint kp(c * static_cast<float>(scale),
                      static_cast<float>(o.gftt_keypoint_size * scale), -1.f, quality[i], l);
      if (!insideOrbLevel(kp, image.size(), pyramid, border)) continue;
      if (orientation_radius > 0) kp.angle = intensityCentroidAngle(level, c, orientation_radius);
      detected.push_back(kp);
    }
  }
  return detected;
}

// OpenCV's multi-scale ORB with the configured pyramid and FAST threshold.
cv::Ptr<cv::ORB> makeOrb(const FeatureOptions& o) {
  return cv::ORB::create(o.orb_max_features, static_cast<float>(o.orb_scale_factor), o.orb_levels,
                         2 * kOrbHalfPatch + 1, 0, 2, cv::ORB::HARRIS_SCORE, 2 * kOrbHalfPatch + 1,
                         o.orb_fast_threshold);
}

// The keypoints whose patch of `radius` level pixels lies inside the image at
// their pyramid level.
std::vector<cv::KeyPoint> keepInside(const std::vector<cv::KeyPoint>& detected, cv::Size size,
                                     const OrbPyramid& pyramid, int radius) {
  std::vector<cv::KeyPoint> kept;
  kept.reserve(detected.size());
  for (const cv::KeyPoint& kp : detected) {
    if (insideOrbLevel(kp, size, pyramid, radius)) kept.push_back(kp);
  }
  return kept;
}

}  // namespace

FeatureExtractor::FeatureExtractor(const FeatureOptions& options) : options_(options) {
  options_.validate();
  if (options_.descriptor == FeatureOptions::DescriptorType::kBrief) {
    brief_pattern_ = loadBriefPattern(options_.brief_pattern_path);
  }
  if (!options_.mask_path.empty()) mask_ = loadMask(options_.mask_path, options_);
}

ImageFeatures FeatureExtractor::extract(const cv::Mat& image) const {
  checkImage(image, options_);
  if (!mask_.empty() && mask_.size() != image.size()) {
    throw std::invalid_argument("FeatureExtractor::extract: mask " + options_.mask_path + " is " +
                                std::to_string(mask_.cols) + "x" + std::to_string(mask_.rows) +
                                " but the image is " + std::to_string(image.cols) + "x" +
                                std::to_string(image.rows));
  }
  ImageFeatures features;
  features.image_width = image.cols;
  features.image_height = image.rows;

  const bool oriented = options_.compute_orientation;
  const bool brief = options_.descriptor == FeatureOptions::DescriptorType::kBrief;
  const bool gftt = options_.detector == FeatureOptions::Detector::kGftt;
  // ORB's keypoints are integer level coordinates times the level's scale.
  if (!gftt) features.pyramid_scale_factor = static_cast<float>(options_.orb_scale_factor);
  // The pyramid the keypoints' octaves refer to (gftt_levels for GFTT).
  OrbPyramid pyramid;
  pyramid.scale_factor = options_.orb_scale_factor;
  pyramid.levels = gftt ? options_.gftt_levels : options_.orb_levels;
  if (gftt && pyramid.levels > 1) {
    features.pyramid_scale_factor = static_cast<float>(options_.orb_scale_factor);
  }

  // Border each keypoint must keep so that its whole descriptor patch (and
  // orientation disc) lies in the image; BRIEF always samples level 0.
  const int radius = brief ? briefPatternRadius(brief_pattern_, oriented)
                           : (oriented ? kOrbSteeredRadius : kOrbUprightRadius);
  // Intensity-centroid disc for GFTT corners: ORB's for ORB descriptors,
  // the pattern's upright extent for BRIEF (within `radius` either way).
  const int orientation_radius = brief ? briefPatternRadius(brief_pattern_, false) : kOrbHalfPatch;
  if (image.cols <= 2 * radius || image.rows <= 2 * radius) return features;

  // 1. Detect.
  std::vector<cv::KeyPoint> detected;
  if (gftt) {
    detected = detectGftt(image, mask_, options_, radius, oriented ? orientation_radius : 0);
  } else {
    cv::Ptr<cv::ORB> orb = makeOrb(options_);
    if (oriented && !brief) {
      // ORB's own orientation and descriptors: one pass over one pyramid
      // (detect + compute would build it twice). ORB keeps its keypoints
      // edgeThreshold = 31 level pixels inside, beyond the 22 needed, so the
      // border check below drops nothing; it still runs to keep the promise.
      cv::Mat mat;
      orb->detectAndCompute(image, mask_, detected, mat);
      const std::vector<Descriptor> described = descriptorsFromMat(mat);
      for (std::size_t i = 0; i < detected.size(); ++i) {
        if (!insideOrbLevel(detected[i], image.size(), pyramid, radius)) continue;
        features.keypoints.push_back(toKeypoint(detected[i], true));
        features.descriptors.push_back(described[i]);
      }
      return features;
    }
    orb->detect(image, detected, mask_);
  }

  // 2. Drop keypoints whose descriptor patch leaves the image (BRIEF always
  // samples level 0). GFTT's corners were checked on their level as they were
  // found, which is the stricter check for BRIEF too.
  std::vector<cv::KeyPoint> kept =
      gftt ? std::move(detected)
           : keepInside(detected, image.size(), brief ? OrbPyramid{1.0, 1} : pyramid, radius);

  // 3. Orientation: both detectors already measured it (intensity centroid
  // at the keypoint's level). Upright descriptors use angle 0.
  if (!oriented) {
    for (cv::KeyPoint& kp : kept) kp.angle = 0.f;
  }

  // 4. Describe.
  if (brief) {
    features.descriptors =
        computeBriefDescriptors(smoothForBrief(image), brief_pattern_, kept, oriented);
  } else {
    features.descriptors = computeOrbDescriptors(image, kept, pyramid);
  }
  features.keypoints.reserve(kept.size());
  for (const cv::KeyPoint& kp : kept) features.keypoints.push_back(toKeypoint(kp, oriented));
  return features;
}

}  // namespace bowg
