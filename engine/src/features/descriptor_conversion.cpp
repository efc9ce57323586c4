#include "bowg/features/descriptor_conversion.h"

#include <stdexcept>
#include <string>

namespace bowg {

Descriptor descriptorFromBytes(const std::uint8_t* bytes) {
  Descriptor d;
  for (int j = 0; j < kDescriptorBytes; ++j) {
    // Byte j covers bits 8j..8j+7: block 8j / 64 = j / 8, shift 8 * (j % 8).
    d.bits[j / 8] |= static_cast<std::uint64_t>(bytes[j]) << (8 * (j % 8));
  }
  return d;
}

void descriptorToBytes(const Descriptor& d, std::uint8_t* bytes) {
  for (int j = 0; j < kDescriptorBytes; ++j) {
    bytes[j] = static_cast<std::uint8_t>((d.bits[j / 8] >> (8 * (j % 8))) & 0xFFu);
  }
}

std::vector<Descriptor> descriptorsFromMat(const cv::Mat& mat) {
  std::vector<Descriptor> out;
  if (mat.empty()) return out;
  if (mat.type() != CV_8UC1 || mat.cols != kDescriptorBytes) {
    throw std::invalid_argument(
        "descriptor matrix must be N x 32 of type CV_8UC1 (256-bit binary descriptors), got " +
        std::to_string(mat.rows) + " x " + std::to_string(mat.cols) + " of type " +
        std::to_string(mat.type()));
  }
  out.reserve(static_cast<std::size_t>(mat.rows));
  for (int r = 0; r < mat.rows; ++r) out.push_back(descriptorFromBytes(mat.ptr<std::uint8_t>(r)));
  return out;
}

cv::Mat descriptorsToMat(const std::vector<Descriptor>& descriptors) {
  if (descriptors.empty()) return cv::Mat();
  cv::Mat mat(static_cast<int>(descriptors.size()), kDescriptorBytes, CV_8UC1);
  for (int r = 0; r < mat.rows; ++r) descriptorToBytes(descriptors[r], mat.ptr<std::uint8_t>(r));
  return mat;
}

}  // namespace bowg
