// The classification of bad images (see image_check.h).
#include "bowg/features/image_check.h"

namespace bowg {

const char* imageProblemName(ImageProblem problem) {
  switch (problem) {
    case ImageProblem::kNone: return "ok";
    case ImageProblem::kEmpty: return "empty";
    case ImageProblem::kFileRefused: return "file_refused";
    case ImageProblem::kUnsupportedFormat: return "unsupported_format";
    case ImageProblem::kBadHeader: return "bad_header";
    case ImageProblem::kTruncated: return "truncated";
    case ImageProblem::kTooLarge: return "too_large";
    case ImageProblem::kUndecodable: return "undecodable";
    case ImageProblem::kMalformed: return "malformed";
  }
  return "unknown";
}

std::string ImageCheck::message() const {
  return detail.empty() ? imageProblemName(problem)
                        : std::string(imageProblemName(problem)) + ": " + detail;
}

BadImage::BadImage(ImageProblem problem, const std::string& detail)
    : std::invalid_argument(imageRefusal(problem, detail).message()),
      check_(imageRefusal(problem, detail)) {}

void ImageProblemCounts::add(ImageProblem problem) {
  ++counts_[static_cast<std::size_t>(problem)];
}

std::size_t ImageProblemCounts::count(ImageProblem problem) const {
  return counts_[static_cast<std::size_t>(problem)];
}

std::size_t ImageProblemCounts::total() const {
  std::size_t n = 0;
  for (std::size_t i = 1; i < kImageProblemCount; ++i) n += counts_[i];
  return n;
}

std::string ImageProblemCounts::summary() const {
  std::string s;
  for (std::size_t i = 1; i < kImageProblemCount; ++i) {
    if (counts_[i] == 0) continue;
    if (!s.empty()) s += ", ";
    s += std::to_string(counts_[i]) + " " + imageProblemName(static_cast<ImageProblem>(i));
  }
  return s;
}

ImageCheck checkRawLayout(std::uint64_t width, std::uint64_t height, std::uint64_t step,
                          std::uint64_t data_size, int pixel_bytes, int channel_bytes) {
  if (width == 0 || height == 0) {
    return imageRefusal(ImageProblem::kBadHeader, "empty image (" + std::to_string(width) +
                                                      " x " + std::to_string(height) + ")");
  }
  // Message fields are 32-bit: these products cannot overflow 64 bits.
  const std::uint64_t row = width * std::uint64_t(pixel_bytes);
  if (step < row) {
    return imageRefusal(ImageProblem::kMalformed,
                        "step " + std::to_string(step) + " is shorter than a row of " +
                            std::to_string(width) + " pixels (" + std::to_string(row) + " bytes)");
  }
  // OpenCV needs every row to start on a whole value (its Mat asserts it).
  if (step % std::uint64_t(channel_bytes) != 0) {
    return imageRefusal(ImageProblem::kMalformed,
                        "step " + std::to_string(step) + " is not a multiple of the " +
                            std::to_string(channel_bytes) + "-byte channel value");
  }
  const std::uint64_t needed = height * step;
  if (data_size < needed) {
    return imageRefusal(ImageProblem::kMalformed,
                        "data holds " + std::to_string(data_size) +
                            " bytes, height x step needs " + std::to_string(needed));
  }
  return ImageCheck();
}

}  // namespace bowg
