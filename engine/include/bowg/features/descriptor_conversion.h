// Conversion between OpenCV's binary descriptor matrices (N x 32, CV_8U, one
// row per keypoint, as returned by cv::ORB) and bowg::Descriptor.
//
// Packing (types.h): byte j of a row holds descriptor bits 8j..8j+7, bit k of
// the byte being descriptor bit 8j+k (little endian). This is the order in
// which OpenCV's ORB writes its binary tests (test 8j+k -> bit k of byte j),
// so descriptor bit b is ORB test b.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "bowg/core/types.h"

namespace bowg {

/// Bytes per 256-bit descriptor.
constexpr int kDescriptorBytes = 32;

/// Packs one 32-byte row (`bytes` points at 32 bytes).
Descriptor descriptorFromBytes(const std::uint8_t* bytes);

/// Unpacks one descriptor into 32 bytes at `bytes`.
void descriptorToBytes(const Descriptor& d, std::uint8_t* bytes);

/// `mat` must be empty or N x 32 CV_8UC1 (throws std::invalid_argument
/// naming the size/type otherwise). An empty matrix gives no descriptors.
std::vector<Descriptor> descriptorsFromMat(const cv::Mat& mat);

/// N x 32 CV_8UC1 matrix (empty matrix for an empty vector).
cv::Mat descriptorsToMat(const std::vector<Descriptor>& descriptors);

}  // namespace bowg
