// Incoming image -> 8-bit grey (see image_conversion.h).
#include "bowg_ros/image_conversion.h"

#include <opencv2/imgproc.hpp>

#include "bowg/features/image_decoding.h"

namespace bowg_ros {
namespace {

struct EncodingInfo {
  const char* name;
  int type;   // the OpenCV type an image of this encoding has
  int code;   // cvtColor code to grey, -1 = none
  int bytes;  // bytes per pixel
};

const EncodingInfo kEncodings[] = {
    {"mono8", CV_8UC1, -1, 1},
    {"mono16", CV_16UC1, -1, 2},
    {"bgr8", CV_8UC3, cv::COLOR_BGR2GRAY, 3},
    {"rgb8", CV_8UC3, cv::COLOR_RGB2GRAY, 3},
    {"bgra8", CV_8UC4, cv::COLOR_BGRA2GRAY, 4},
    {"rgba8", CV_8UC4, cv::COLOR_RGBA2GRAY, 4},
    {"8UC1", CV_8UC1, -1, 1},
    {"16UC1", CV_16UC1, -1, 2},
};

const EncodingInfo* find(const std::string& encoding) {
  for (const EncodingInfo& e : kEncodings) {
    if (encoding == e.name) return &e;
  }
  return nullptr;
}

}  // namespace

bool isSupportedEncoding(const std::string& encoding) { return find(encoding) != nullptr; }

const std::string& supportedEncodings() {
  static const std::string list = [] {
    std::string l;
    for (const EncodingInfo& e : kEncodings) l += (l.empty() ? "" : ", ") + std::string(e.name);
    return l;
  }();
  return list;
}

bowg::ImageCheck checkImageLayout(std::uint32_t width, std::uint32_t height, std::uint32_t step,
                                  std::size_t data_size, const std::string& encoding) {
  const EncodingInfo* e = find(encoding);
  if (!e) {
    return bowg::imageRefusal(bowg::ImageProblem::kUnsupportedFormat,
                              "encoding '" + encoding + "' (supported: " + supportedEncodings() +
                                  ")");
  }
  const int channel_bytes = e->type == CV_16UC1 ? 2 : 1;
  return bowg::checkRawLayout(width, height, step, data_size, e->bytes, channel_bytes);
}

bowg::ImageCheck checkImage(const sensor_msgs::Image& msg, const bowg::FeatureOptions& options) {
  bowg::ImageCheck check =
      checkImageLayout(msg.width, msg.height, msg.step, msg.data.size(), msg.encoding);
  if (!check.ok()) return check;
  const std::string size = bowg::imageSizeProblem(msg.width, msg.height, options);
  if (!size.empty()) check = bowg::imageRefusal(bowg::ImageProblem::kTooLarge, size);
  return check;
}

namespace {

// "<detail> (format 'jpeg', 1234 bytes)": the message's own description.
bowg::ImageCheck namingFormat(bowg::ImageCheck check, const sensor_msgs::CompressedImage& msg) {
  if (!check.ok()) {
    check.detail += " (format '" + msg.format + "', " + std::to_string(msg.data.size()) + " bytes)";
  }
  return check;
}

}  // namespace

bowg::ImageCheck checkCompressed(const sensor_msgs::CompressedImage& msg,
                                 const bowg::FeatureOptions& options) {
  return namingFormat(bowg::checkEncodedImage(msg.data.data(), msg.data.size(), options), msg);
}

cv::Mat toMono8(const cv::Mat& image, const std::string& encoding) {
  const EncodingInfo* e = find(encoding);
  if (!e) {
    throw BadImage(bowg::ImageProblem::kUnsupportedFormat,
                   "encoding '" + encoding + "' (supported: " + supportedEncodings() + ")");
  }
  if (image.empty()) {
    throw BadImage(bowg::ImageProblem::kEmpty, "empty image with encoding '" + encoding + "'");
  }
  if (image.type() != e->type) {
    throw BadImage(bowg::ImageProblem::kMalformed,
                   "image data does not match its encoding '" + encoding + "'");
  }
  if (e->type == CV_8UC1) return image;  // zero copy
  cv::Mat grey;
  if (e->type == CV_16UC1) {
    image.convertTo(grey, CV_8U, 1.0 / 256.0);
  } else {
    cv::cvtColor(image, grey, e->code);
  }
  return grey;
}

cv::Mat greyFromImage(const sensor_msgs::Image& msg, const bowg::FeatureOptions& options) {
  const bowg::ImageCheck check = checkImage(msg, options);
  if (!check.ok()) throw BadImage(check);
  const EncodingInfo* e = find(msg.encoding);
  // Wraps the message's buffer (checked above to hold height x step bytes).
  const cv::Mat view(static_cast<int>(msg.height), static_cast<int>(msg.width), e->type,
                     const_cast<std::uint8_t*>(msg.data.data()), msg.step);
  return toMono8(view, msg.encoding);
}

cv::Mat greyFromCompressed(const sensor_msgs::CompressedImage& msg,
                           const bowg::FeatureOptions& options) {
  bowg::ImageCheck check;
  const cv::Mat grey = bowg::decodeGreyImage(msg.data.data(), msg.data.size(), options, &check);
  if (!check.ok()) throw BadImage(namingFormat(check, msg));
  return grey;
}

}  // namespace bowg_ros
