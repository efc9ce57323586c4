// The byte layout the features_message target reads a fuzz input as, and
// the seed writer writes: width and height (uint16 each), a byte whose bits
// drop the last element of x, y, size, angle, response, octave or the last
// descriptor byte (inconsistent messages), then records of five float32
// (x, y, size, angle, response), an int32 octave and 32 descriptor bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "bowg/core/types.h"
#include "bowg/features/descriptor_conversion.h"
#include "bowg/features/feature_arrays.h"

namespace bowg {
namespace fuzz {

constexpr std::size_t kFeatureRecordBytes = 5 * 4 + 4 + kDescriptorBytes;

inline FeatureArrays featureArraysFromBytes(const std::uint8_t* data, std::size_t size) {
  FeatureArrays a;
  if (size < 5) return a;
  a.image_width = data[0] | (std::uint32_t(data[1]) << 8);
  a.image_height = data[2] | (std::uint32_t(data[3]) << 8);
  const std::uint8_t drop = data[4];
  for (std::size_t at = 5; at + kFeatureRecordBytes <= size; at += kFeatureRecordBytes) {
    float v[5];
    std::memcpy(v, data + at, sizeof v);
    std::int32_t octave;
    std::memcpy(&octave, data + at + 20, 4);
    a.x.push_back(v[0]);
    a.y.push_back(v[1]);
    a.size.push_back(v[2]);
    a.angle.push_back(v[3]);
    a.response.push_back(v[4]);
    a.octave.push_back(octave);
    a.descriptors.insert(a.descriptors.end(), data + at + 24, data + at + kFeatureRecordBytes);
  }
  if (!a.x.empty()) {
    if (drop & 1) a.x.pop_back();
    if (drop & 2) a.y.pop_back();
    if (drop & 4) a.size.pop_back();
    if (drop & 8) a.angle.pop_back();
    if (drop & 16) a.response.pop_back();
    if (drop & 32) a.octave.pop_back();
    if (drop & 64) a.descriptors.pop_back();
  }
  return a;
}

inline std::string featureBytes(const ImageFeatures& f) {
  std::string out(5, '\0');
  out[0] = static_cast<char>(f.image_width & 0xff);
  out[1] = static_cast<char>((f.image_width >> 8) & 0xff);
  out[2] = static_cast<char>(f.image_height & 0xff);
  out[3] = static_cast<char>((f.image_height >> 8) & 0xff);
  for (std::size_t i = 0; i < f.size(); ++i) {
    const Keypoint& k = f.keypoints[i];
    const float v[5] = {k.x, k.y, k.size, k.angle, k.response};
    char record[kFeatureRecordBytes];
    std::memcpy(record, v, sizeof v);
    std::memcpy(record + 20, &k.octave, 4);
    descriptorToBytes(f.descriptors[i], reinterpret_cast<std::uint8_t*>(record + 24));
    out.append(record, sizeof record);
  }
  return out;
}

}  // namespace fuzz
}  // namespace bowg
