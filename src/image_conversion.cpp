// Incoming image -> 8-bit grey (see image_conversion.h).
#include "bowg_ros/image_conversion.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

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

std::string imageLayoutProblem(std::uint32_t width, std::uint32_t height, std::uint32_t step,
                               std::size_t data_size, const std::string& encoding) {
  const EncodingInfo* e = find(encoding);
  if (!e) return "unsupported encoding '" + encoding + "'";
  if (width == 0 || height == 0) {
    return "empty image (" + std::to_string(width) + " x " + std::to_string(height) + ")";
  }
  const std::uint64_t row = std::uint64_t(width) * std::uint64_t(e->bytes);
  if (step < row) {
    return "step " + std::to_string(step) + " is shorter than a row of " + std::to_string(width) +
           " " + encoding + " pixels (" + std::to_string(row) + " bytes)";
  }
  const std::uint64_t needed = std::uint64_t(height) * std::uint64_t(step);
  if (data_size < needed) {
    return "data holds " + std::to_string(data_size) + " bytes, height x step needs " +
           std::to_string(needed);
  }
  return "";
}

cv::Mat toMono8(const cv::Mat& image, const std::string& encoding) {
  const EncodingInfo* e = find(encoding);
  if (!e) {
    throw BadImage("unsupported image encoding '" + encoding +
                   "' (supported: " + supportedEncodings() + ")");
  }
  if (image.empty()) throw BadImage("empty image with encoding '" + encoding + "'");
  if (image.type() != e->type) {
    throw BadImage("image data does not match its encoding '" + encoding + "'");
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

cv::Mat greyFromImage(const sensor_msgs::Image& msg) {
  const std::string problem =
      imageLayoutProblem(msg.width, msg.height, msg.step, msg.data.size(), msg.encoding);
  if (!problem.empty()) throw BadImage("image message: " + problem);
  const EncodingInfo* e = find(msg.encoding);
  // Wraps the message's buffer (checked above to hold height x step bytes).
  const cv::Mat view(static_cast<int>(msg.height), static_cast<int>(msg.width), e->type,
                     const_cast<std::uint8_t*>(msg.data.data()), msg.step);
  return toMono8(view, msg.encoding);
}

cv::Mat greyFromCompressed(const sensor_msgs::CompressedImage& msg) {
  cv::Mat grey;
  if (!msg.data.empty()) {
    const cv::Mat data(1, static_cast<int>(msg.data.size()), CV_8UC1,
                       const_cast<std::uint8_t*>(msg.data.data()));
    grey = cv::imdecode(data, cv::IMREAD_GRAYSCALE);
  }
  if (grey.empty()) {
    throw BadImage("cannot decode the compressed image (" + std::to_string(msg.data.size()) +
                   " bytes, format '" + msg.format + "')");
  }
  return grey;
}

}  // namespace bowg_ros
