// Checked decoding of encoded images (see image_decoding.h).
#include "bowg/features/image_decoding.h"

#include <opencv2/imgcodecs.hpp>

#include "bowg/core/bounded_file.h"
#include "bowg/core/errors.h"

namespace bowg {

ImageCheck checkEncodedImage(const std::uint8_t* data, std::size_t size,
                             const FeatureOptions& options, ImageHeader* header) {
  ImageHeader h;
  ImageCheck check = readImageHeader(data, size, &h);
  if (!check.ok()) return check;
  const std::string too_large = imageSizeProblem(static_cast<long long>(h.width),
                                                 static_cast<long long>(h.height), options);
  if (!too_large.empty()) return imageRefusal(ImageProblem::kTooLarge, h.format + " " + too_large);
  if (header) *header = h;
  return check;
}

cv::Mat decodeGreyImage(const std::uint8_t* data, std::size_t size, const FeatureOptions& options,
                        ImageCheck* check) {
  ImageHeader header;
  *check = checkEncodedImage(data, size, options, &header);
  if (!check->ok()) return cv::Mat();
  // The header check is the size guard: OpenCV's own limit
  // (OPENCV_IO_MAX_IMAGE_PIXELS, 2^30 by default) is far above any
  // max_image_pixels and is read once per process.
  const cv::Mat encoded(1, static_cast<int>(size), CV_8UC1, const_cast<std::uint8_t*>(data));
  cv::Mat grey;
  try {
    grey = cv::imdecode(encoded, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception& e) {
    *check = imageRefusal(ImageProblem::kUndecodable, header.format + ": " + e.what());
    return cv::Mat();
  }
  const std::uint64_t w = header.width, h = header.height;
  const bool same = grey.cols == static_cast<int>(w) && grey.rows == static_cast<int>(h);
  const bool swapped = grey.cols == static_cast<int>(h) && grey.rows == static_cast<int>(w);
  if (grey.empty() || !(same || swapped)) {
    *check = imageRefusal(ImageProblem::kUndecodable,
                          header.format + " of " + std::to_string(w) + " x " + std::to_string(h) +
                              " that OpenCV cannot decode");
    return cv::Mat();
  }
  return grey;
}

cv::Mat readGreyImageFile(const std::string& path, const FeatureOptions& options,
                          ImageCheck* check) {
  std::string bytes;
  try {
    BoundedFile file(path, FileKind::kImage);
    bytes = file.readRest();
  } catch (const IoError& e) {
    *check = imageRefusal(ImageProblem::kFileRefused, e.what());
    return cv::Mat();
  }
  if (bytes.empty()) {
    *check = imageRefusal(ImageProblem::kEmpty, "the file is empty");
    return cv::Mat();
  }
  if (bytes.size() > 0x7fffffffu) {
    *check = imageRefusal(ImageProblem::kFileRefused, "more than 2 GiB");
    return cv::Mat();
  }
  return decodeGreyImage(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(),
                         options, check);
}

}  // namespace bowg
