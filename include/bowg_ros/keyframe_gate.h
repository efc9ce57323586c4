// Keyframe selection: not every camera frame is a
// keyframe. A frame becomes one when at least `min_interval` seconds passed
// since the last keyframe and, when `min_distance` > 0 and odometry is
// arriving, the robot travelled at least `min_distance` metres (path length of
// the odometry positions) since then. Until the first odometry message
// arrives, only the time gate applies, so a missing odometry topic never
// silences the detector. Frames whose stamp does not increase are rejected
// (the detector's temporal score needs time order). ROS-free.
#pragma once

#include <string>

namespace bowg_ros {

struct KeyframeGateOptions {
  double min_interval = 0.0;  ///< s, >= 0
  double min_distance = 0.0;  ///< m, >= 0; 0 = no distance gate
  void validate() const;      ///< throws std::invalid_argument naming the field
};

enum class GateDecision {
  kAccept,         ///< a keyframe
  kTooSoon,        ///< less than min_interval since the last keyframe
  kTooClose,       ///< travelled less than min_distance
  kOutOfOrder,     ///< stamp older than the previous frame's
  kRepeatedStamp,  ///< same stamp as the previous frame
};
const char* toString(GateDecision d);

class KeyframeGate {
 public:
  explicit KeyframeGate(const KeyframeGateOptions& options = KeyframeGateOptions());

  /// Decides for a frame stamped `stamp` (s). Out-of-order and repeated
  /// stamps are judged against the previous frame, accepted or not. On
  /// kAccept the interval and distance counters restart.
  GateDecision check(double stamp);

  /// One odometry position (m, any fixed frame); adds the distance from the
  /// previous position to the travelled path.
  void addPosition(double x, double y, double z);

  double travelledSinceKeyframe() const { return travelled_; }
  /// Path length of every odometry position so far plus the base of
  /// setOdometer(): the keyframes' odometer for the detector's windows in
  /// metres (bowg::KeyframeInput::odometer). NaN before the first position.
  double odometer() const;
  /// Continues the odometer from `base` metres (after loading a database
  /// whose keyframes were driven up to `base`). Finite and >= 0.
  void setOdometer(double base);
  bool hasOdometry() const { return has_position_; }
  const KeyframeGateOptions& options() const { return options_; }
  void setOptions(const KeyframeGateOptions& options);

  /// Forgets every frame and position (after a database reset).
  void reset();

 private:
  KeyframeGateOptions options_;
  bool has_frame_ = false, has_keyframe_ = false, has_position_ = false;
  double last_frame_stamp_ = 0, last_keyframe_stamp_ = 0;
  double last_x_ = 0, last_y_ = 0, last_z_ = 0;
  double travelled_ = 0;
  double odometer_ = 0;  ///< path length since reset() / setOdometer()
};

}  // namespace bowg_ros
