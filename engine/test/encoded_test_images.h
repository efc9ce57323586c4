// Encoded test images, good and bad, made in memory (no data files): a
// PNG whose header declares 30000 x 30000 pixels in a few hundred bytes, a
// JPEG cut short, and helpers to write them. Used by the engine, ROS-layer,
// tools and fuzz-seed code alike.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

namespace bowg {
namespace test {

inline std::vector<std::uint8_t> encodeImage(const cv::Mat& image, const std::string& ext) {
  std::vector<std::uint8_t> bytes;
  cv::imencode(ext, image, bytes);
  return bytes;
}

/// Random grey noise: JPEG cannot compress it away.
inline cv::Mat noiseImage(int width, int height) {
  cv::Mat noise(height, width, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  return noise;
}

inline void putBigEndian32(std::uint32_t v, std::uint8_t* p) {
  p[0] = std::uint8_t(v >> 24);
  p[1] = std::uint8_t(v >> 16);
  p[2] = std::uint8_t(v >> 8);
  p[3] = std::uint8_t(v);
}

/// A valid 16 x 16 PNG whose IHDR (and its CRC) is rewritten to declare
/// width x height: a decoder would allocate the declared size.
inline std::vector<std::uint8_t> pngDeclaring(std::uint32_t width, std::uint32_t height) {
  std::vector<std::uint8_t> png = encodeImage(cv::Mat(16, 16, CV_8UC1, cv::Scalar(50)), ".png");
  putBigEndian32(width, &png[16]);
  putBigEndian32(height, &png[20]);
  const uLong crc = crc32(crc32(0L, Z_NULL, 0), &png[12], 17);  // "IHDR" + 13 data bytes
  putBigEndian32(static_cast<std::uint32_t>(crc), &png[29]);
  return png;
}

/// A JPEG of noise cut in half: no end-of-image marker (libjpeg would
/// decode the top and fill the rest with grey).
inline std::vector<std::uint8_t> truncatedJpeg() {
  std::vector<std::uint8_t> jpeg = encodeImage(noiseImage(160, 120), ".jpg");
  jpeg.resize(jpeg.size() / 2);
  return jpeg;
}

inline void writeBytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

}  // namespace test
}  // namespace bowg
