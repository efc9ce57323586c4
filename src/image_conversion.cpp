// Incoming image -> 8-bit grey (see image_conversion.h).
#include "bowg_ros/image_conversion.h"

#include <opencv2/imgproc.hpp>

namespace bowg_ros {
namespace {

struct EncodingInfo {
  const char* name;
  int type;  // the OpenCV type an image of this encoding has
  int code;  // cvtColor code to grey, -1 = none
};

const EncodingInfo kEncodings[] = {
    {"mono8", CV_8UC1, -1},
    {"mono16", CV_16UC1, -1},
    {"bgr8", CV_8UC3, cv::COLOR_BGR2GRAY},
    {"rgb8", CV_8UC3, cv::COLOR_RGB2GRAY},
    {"bgra8", CV_8UC4, cv::COLOR_BGRA2GRAY},
    {"rgba8", CV_8UC4, cv::COLOR_RGBA2GRAY},
};

const EncodingInfo* find(const std::string& encoding) {
  for (const EncodingInfo& e : kEncodings) {
    if (encoding == e.name) return &e;
  }
  return nullptr;
}

}  // namespace

bool isSupportedEncoding(const std::string& encoding) { return find(encoding) != nullptr; }

cv::Mat toMono8(const cv::Mat& image, const std::string& encoding) {
  const EncodingInfo* e = find(encoding);
  if (!e) {
    throw UnsupportedEncoding("unsupported image encoding '" + encoding +
                              "' (supported: mono8, mono16, bgr8, rgb8, bgra8, rgba8)");
  }
  if (image.empty()) throw UnsupportedEncoding("empty image with encoding '" + encoding + "'");
  if (image.type() != e->type) {
    throw UnsupportedEncoding("image data does not match its encoding '" + encoding + "'");
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

}  // namespace bowg_ros
