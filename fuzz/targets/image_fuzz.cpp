// The image input path: header check and checked decoding
// (bowg::decodeGreyImage) of whatever bytes a compressed topic, a bag or an
// image folder holds. Documented outcomes: a grey image of the size the
// header declares, or a refusal with its reason; never an exception, never
// a decode of more than max_image_pixels.
#include <cstddef>
#include <cstdint>

#include "bowg/features/image_decoding.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  bowg::FeatureOptions options;
  // Small enough that a mutated header does not spend the run in one decode.
  options.max_image_pixels = 1024 * 1024;
  bowg::ImageHeader header;
  const bowg::ImageCheck header_check = bowg::readImageHeader(data, size, &header);
  bowg::ImageCheck check;
  const cv::Mat grey = bowg::decodeGreyImage(data, size, options, &check);
  if (check.ok()) {
    if (!header_check.ok() || grey.empty() || grey.type() != CV_8UC1) __builtin_trap();
    if (static_cast<std::uint64_t>(grey.total()) != header.width * header.height) __builtin_trap();
    if (grey.total() > static_cast<std::size_t>(options.max_image_pixels)) __builtin_trap();
  } else {
    if (!grey.empty() || check.detail.empty()) __builtin_trap();
  }
  return 0;
}
