// Basic value types shared by every stage of the BoWG engine.
//
// The engine is ROS-free on purpose: the nodelet, the offline tools and the
// tests all drive this same code (see README "Architecture").
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace bowg {

/// A 256-bit binary descriptor (ORB rBRIEF or plain BRIEF), stored as four
/// 64-bit blocks so that the Hamming distance is four popcounts.
/// Bit b of the descriptor is bit (b % 64) of block (b / 64); for OpenCV's
/// 32-byte descriptors, byte j holds bits 8j..8j+7 (little-endian packing).
struct Descriptor {
  std::array<std::uint64_t, 4> bits{{0, 0, 0, 0}};

  bool operator==(const Descriptor& o) const { return bits == o.bits; }
  bool operator!=(const Descriptor& o) const { return bits != o.bits; }
};

/// Hamming distance between two 256-bit descriptors (0..256).
inline int hammingDistance(const Descriptor& a, const Descriptor& b) {
  return __builtin_popcountll(a.bits[0] ^ b.bits[0]) +
         __builtin_popcountll(a.bits[1] ^ b.bits[1]) +
         __builtin_popcountll(a.bits[2] ^ b.bits[2]) +
         __builtin_popcountll(a.bits[3] ^ b.bits[3]);
}

/// A detected feature point in image coordinates (pixels, origin top-left,
/// x right, y down).
struct Keypoint {
  float x = 0.f;
  float y = 0.f;
  /// Diameter of the meaningful neighbourhood in pixels (OpenCV's
  /// KeyPoint::size). The paper uses it as the word-group radius s_t^(i).
  float size = 0.f;
  /// Orientation in degrees [0, 360), or -1 when not computed.
  float angle = -1.f;
  float response = 0.f;
  /// Pyramid octave the point was detected in (0 for single-scale GFTT).
  int octave = 0;
};

/// A keypoint's position alone (pixels, as Keypoint::x, y): what a database
/// entry keeps of its keypoints, since the later stages (distribution
/// vectors, RANSAC, metric translation) read nothing else and a full
/// Keypoint costs three times the bytes.
struct ImagePoint {
  float x = 0.f;
  float y = 0.f;
};

/// The positions of `keypoints`, index-aligned.
inline std::vector<ImagePoint> imagePoints(const std::vector<Keypoint>& keypoints) {
  std::vector<ImagePoint> out(keypoints.size());
  for (std::size_t i = 0; i < keypoints.size(); ++i)
    out[i] = ImagePoint{keypoints[i].x, keypoints[i].y};
  return out;
}

/// The features of one image: keypoints and their descriptors, index-aligned.
struct ImageFeatures {
  std::vector<Keypoint> keypoints;
  std::vector<Descriptor> descriptors;
  int image_width = 0;
  int image_height = 0;
  /// The detector's pyramid scale factor when every keypoint lies at integer
  /// coordinates of its octave's level times that level's scale (OpenCV's
  /// ORB); 0 when unknown. Lets the database keep positions in 4 bytes
  /// (PackedPoints), losslessly either way.
  float pyramid_scale_factor = 0.f;

  std::size_t size() const { return keypoints.size(); }
  bool empty() const { return keypoints.empty(); }
};

/// Identifiers.
using WordId = std::uint32_t;   ///< leaf index of the vocabulary tree, 0..W-1
using NodeId = std::uint32_t;   ///< node index of the vocabulary tree, root = 0
using EntryId = std::uint32_t;  ///< keyframe index in the database, 0..N-1

/// Camera intrinsics (pinhole, pixels). `valid` is false when unknown.
struct CameraIntrinsics {
  bool valid = false;
  double fx = 0, fy = 0, cx = 0, cy = 0;
};

/// The robot's position in its odometry's fixed frame (metres; REP-105's
/// `odom`): dead reckoning, drifting with the metres driven. All three NaN
/// when unknown.
struct OdometryPosition {
  double x = std::numeric_limits<double>::quiet_NaN();
  double y = std::numeric_limits<double>::quiet_NaN();
  double z = std::numeric_limits<double>::quiet_NaN();
  bool known() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }
  bool unknown() const { return std::isnan(x) && std::isnan(y) && std::isnan(z); }
  /// Known or unknown as a whole: what a keyframe and a detector file may hold.
  bool valid() const { return known() || unknown(); }
};

/// The direction the robot faces in its odometry's fixed frame: the x axis
/// of its body frame (REP-103: x forward) as a unit vector, from the
/// odometry's orientation (odometry_heading.h). Roll about that axis leaves
/// it unchanged, so a crawler rolling in the pipe keeps its heading. All
/// three NaN when unknown. Floats: a direction to a fraction of a degree is
/// all the heading gate needs, in half the memory of a database's entries.
struct OdometryHeading {
  float x = std::numeric_limits<float>::quiet_NaN();
  float y = std::numeric_limits<float>::quiet_NaN();
  float z = std::numeric_limits<float>::quiet_NaN();
  bool known() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }
  bool unknown() const { return std::isnan(x) && std::isnan(y) && std::isnan(z); }
  /// Unknown, or known with unit length (within 1e-3): what a keyframe and a
  /// detector file may hold.
  bool valid() const {
    return unknown() || (known() && std::abs(x * x + y * y + z * z - 1.f) <= 1e-3f);
  }
};

}  // namespace bowg
