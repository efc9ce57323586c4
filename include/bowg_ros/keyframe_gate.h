// Keyframe selection: not every camera frame is a
// keyframe. A frame becomes one when at least `min_interval` seconds passed
// since the last keyframe (within 10 %: camera jitter) and, when `min_distance` > 0 and odometry is
// arriving, the robot travelled at least `min_distance` metres (path length of
// the odometry positions) since then. Until the first odometry message
// arrives, only the time gate applies, so a missing odometry topic never
// silences the detector. The travelled path comes from odometry positions,
// or, on a robot without them, from an odometer's readings (metres driven,
// a cable counter); positions win once they arrive. Frames whose stamp does not increase are
// rejected (the detector's temporal score needs time order), and so are frames not after the last
// keyframe of a loaded database (the stamp floor). A replay that starts over (a bag restarted,
// simulated time reset) sends stamps far back: with `time_jump_reset` > 0 a jump back by more than
// that starts a new run (the gate forgets everything and counts an epoch; the nodelet then resets
// its database), otherwise such frames are rejected like any other out-of-order frame. ROS-free.
#pragma once

#include <string>

#include "bowg/core/types.h"
#include "bowg_ros/odometry_reading.h"

namespace bowg_ros {

/// A frame at least this share of min_interval after the last keyframe is on
/// time: a camera whose period equals the interval keeps every frame.
constexpr double kIntervalTolerance = 0.9;

struct KeyframeGateOptions {
  double min_interval = 0.0;  ///< s, >= 0
  double min_distance = 0.0;  ///< m, >= 0; 0 = no distance gate
  /// s, >= 0: a stamp more than this before the previous frame's starts a
  /// new run (kTimeJump); 0 = never (such frames are kOutOfOrder).
  double time_jump_reset = 0.0;
  void validate() const;  ///< throws std::invalid_argument naming the field
};

enum class GateDecision {
  kAccept,         ///< a keyframe
  kTooSoon,        ///< less than 0.9 x min_interval since the last keyframe
  kTooClose,       ///< travelled less than min_distance
  kOutOfOrder,     ///< stamp older than the previous frame's
  kRepeatedStamp,  ///< same stamp as the previous frame
  kBeforeFloor,    ///< not after the stamp floor (a loaded database's last keyframe)
  kTimeJump,       ///< jumped back by more than time_jump_reset: a new run, and its first keyframe
};
/// True for the decisions that make the frame a keyframe.
inline bool isKeyframe(GateDecision d) {
  return d == GateDecision::kAccept || d == GateDecision::kTimeJump;
}
/// True for the decisions that reject a frame for its stamp (counted, logged).
inline bool isStampRejection(GateDecision d) {
  return d == GateDecision::kOutOfOrder || d == GateDecision::kRepeatedStamp ||
         d == GateDecision::kBeforeFloor;
}
const char* toString(GateDecision d);

/// True when `stamp` (s) lies more than `reset` s before `previous`: a replay
/// that started over, with ~reset_on_time_jump (`reset` > 0; 0 = never). One
/// rule for frames (KeyframeGate::check) and stamped odometer readings.
inline bool isTimeJump(double stamp, double previous, double reset) {
  return reset > 0.0 && stamp < previous - reset;
}

class KeyframeGate {
 public:
  explicit KeyframeGate(const KeyframeGateOptions& options = KeyframeGateOptions());

  /// Decides for a frame stamped `stamp` (s). Out-of-order and repeated
  /// stamps are judged against the previous frame, accepted or not. On
  /// kAccept the interval and distance counters restart; on kTimeJump the
  /// gate first forgets everything (as reset()) and counts a new epoch.
  GateDecision check(double stamp);

  /// Frames must be stamped after `stamp` (s) until the next reset(): the
  /// last keyframe of a loaded database, whose detector refuses older ones.
  void setStampFloor(double stamp);
  /// Runs started by time jumps so far (0 until the first).
  unsigned epoch() const { return epoch_; }

  /// One odometry position (m, any fixed frame); adds the distance from the
  /// previous position to the travelled path. A position with a non-finite
  /// coordinate is ignored (false).
  bool addPosition(double x, double y, double z);

  /// One odometer reading (m driven, any origin; a decrease, the tether
  /// reeled in, is driving too): adds |change| to the travelled path. Ignored
  /// (false) once odometry positions arrived: they measure the same path.
  bool addOdometerReading(double metres);

  /// One reading of either source: addPosition (which also takes a
  /// position's heading) or addOdometerReading. False when an odometer
  /// reading is ignored (as addOdometerReading).
  bool addReading(const OdometryReading& r);

  double travelledSinceKeyframe() const { return travelled_; }
  /// Path length of every odometry position (or odometer reading) so far
  /// plus the base of setOdometer(): the keyframes' odometer for the
  /// detector's windows in metres (bowg::KeyframeInput::odometer). NaN before
  /// the first position or reading.
  double odometer() const;
  /// Continues the odometer from `base` metres (after loading a database
  /// whose keyframes were driven up to `base`). Finite and >= 0.
  void setOdometer(double base);
  bool hasOdometry() const { return has_position_ || has_reading_; }
  bool hasPositions() const { return has_position_; }
  /// The last odometry position (the keyframes' position for the odometry
  /// gate, bowg::KeyframeInput::position); unknown before the first one.
  bowg::OdometryPosition position() const;
  /// The heading of the last odometry position (bowg::KeyframeInput::
  /// heading); unknown before the first one or when it came without one.
  bowg::OdometryHeading heading() const { return heading_; }
  const KeyframeGateOptions& options() const { return options_; }
  void setOptions(const KeyframeGateOptions& options);

  /// Forgets every frame, position and the stamp floor (after a database
  /// reset); the epoch is kept.
  void reset();

 private:
  KeyframeGateOptions options_;
  bool has_frame_ = false, has_keyframe_ = false, has_position_ = false, has_floor_ = false;
  bool has_reading_ = false;
  double last_reading_ = 0;
  double floor_ = 0;
  unsigned epoch_ = 0;
  double last_frame_stamp_ = 0, last_keyframe_stamp_ = 0;
  double last_x_ = 0, last_y_ = 0, last_z_ = 0;
  bowg::OdometryHeading heading_;
  double travelled_ = 0;
  double odometer_ = 0;  ///< path length since reset() / setOdometer()
};

}  // namespace bowg_ros
