#include "bowg_evaluation/image_file.h"

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <vector>

namespace bowg {
namespace eval {
namespace {

bool isJpeg(const std::vector<unsigned char>& bytes) {
  return bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff;
}

// A complete JPEG ends with the EOI marker FF D9 (some writers pad after it).
bool jpegComplete(const std::vector<unsigned char>& bytes) {
  std::size_t end = bytes.size();
  while (end > 2 && bytes[end - 1] == 0x00) --end;
  return end >= 2 && bytes[end - 2] == 0xff && bytes[end - 1] == 0xd9;
}

}  // namespace

cv::Mat readGreyImage(const std::string& path, const FeatureOptions& options, std::string* why) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *why = "cannot open the file";
    return cv::Mat();
  }
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
  if (bytes.empty()) {
    *why = "the file is empty";
    return cv::Mat();
  }
  if (isJpeg(bytes) && !jpegComplete(bytes)) {
    *why = "truncated JPEG (no end-of-image marker)";
    return cv::Mat();
  }
  // OpenCV (3.4.2+) refuses images above OPENCV_IO_MAX_IMAGE_PIXELS after
  // reading the header, before allocating: set it to the first limit asked
  // for unless the user did. It is read once per process, so where OpenCV
  // decoded an image before this point, or for a later, larger limit, the
  // check after decoding is what holds.
  static const bool limit_set = [&options] {
    return ::setenv("OPENCV_IO_MAX_IMAGE_PIXELS", std::to_string(options.max_image_pixels).c_str(),
                    0) == 0;
  }();
  (void)limit_set;
  cv::Mat grey;
  try {
    grey = cv::imdecode(bytes, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception& e) {
    *why = "OpenCV refused it (more than max_image_pixels " +
           std::to_string(options.max_image_pixels) + ", or corrupt): " + e.what();
    return cv::Mat();
  }
  if (grey.empty()) {
    *why = "not an image OpenCV can decode";
    return cv::Mat();
  }
  const std::string size = imageSizeProblem(grey.cols, grey.rows, options);
  if (!size.empty()) {
    *why = size;
    return cv::Mat();
  }
  return grey;
}

}  // namespace eval
}  // namespace bowg
