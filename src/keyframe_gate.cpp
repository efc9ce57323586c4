// Keyframe selection by time and travelled distance (see keyframe_gate.h).
#include "bowg_ros/keyframe_gate.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace bowg_ros {

void KeyframeGateOptions::validate() const {
  if (!(min_interval >= 0.0) || !std::isfinite(min_interval)) {
    throw std::invalid_argument("min_keyframe_interval must be a finite value >= 0 s");
  }
  if (!(min_distance >= 0.0) || !std::isfinite(min_distance)) {
    throw std::invalid_argument("min_keyframe_distance must be a finite value >= 0 m");
  }
  if (!(time_jump_reset >= 0.0) || !std::isfinite(time_jump_reset)) {
    throw std::invalid_argument("reset_on_time_jump must be a finite value >= 0 s");
  }
}

const char* toString(GateDecision d) {
  switch (d) {
    case GateDecision::kAccept:
      return "accept";
    case GateDecision::kTooSoon:
      return "too soon after the last keyframe";
    case GateDecision::kTooClose:
      return "too close to the last keyframe";
    case GateDecision::kOutOfOrder:
      return "stamp older than the previous frame";
    case GateDecision::kRepeatedStamp:
      return "same stamp as the previous frame";
    case GateDecision::kBeforeFloor:
      return "stamp not after the loaded database's last keyframe";
    case GateDecision::kTimeJump:
      return "time jumped back: a new run";
  }
  return "?";
}

KeyframeGate::KeyframeGate(const KeyframeGateOptions& options) { setOptions(options); }

void KeyframeGate::setOptions(const KeyframeGateOptions& options) {
  options.validate();
  options_ = options;
}

GateDecision KeyframeGate::check(double stamp) {
  if (has_frame_ && isTimeJump(stamp, last_frame_stamp_, options_.time_jump_reset)) {
    reset();
    ++epoch_;
    has_frame_ = has_keyframe_ = true;
    last_frame_stamp_ = last_keyframe_stamp_ = stamp;
    return GateDecision::kTimeJump;
  }
  if (has_frame_) {
    if (stamp < last_frame_stamp_) return GateDecision::kOutOfOrder;
    if (stamp == last_frame_stamp_) return GateDecision::kRepeatedStamp;
  }
  if (has_floor_ && !(stamp > floor_)) return GateDecision::kBeforeFloor;
  has_frame_ = true;
  last_frame_stamp_ = stamp;
  if (has_keyframe_) {
    // A camera's frames are not exactly periodic: a 10 Hz camera under a
    // 0.1 s gate would lose every frame that came a few ms early (and a
    // played bag's stamps differ from 0.1 in the last bits). A frame within
    // 10 % of the interval counts as on time.
    if (stamp - last_keyframe_stamp_ < kIntervalTolerance * options_.min_interval) {
      return GateDecision::kTooSoon;
    }
    if (options_.min_distance > 0.0 && hasOdometry() && travelled_ < options_.min_distance) {
      return GateDecision::kTooClose;
    }
  }
  has_keyframe_ = true;
  last_keyframe_stamp_ = stamp;
  travelled_ = 0.0;
  return GateDecision::kAccept;
}

bool KeyframeGate::addPosition(double x, double y, double z) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return false;
  if (has_position_) {
    const double step = std::sqrt((x - last_x_) * (x - last_x_) + (y - last_y_) * (y - last_y_) +
                                  (z - last_z_) * (z - last_z_));
    travelled_ += step;
    odometer_ += step;
  }
  has_position_ = true;
  last_x_ = x;
  last_y_ = y;
  last_z_ = z;
  return true;
}

bool KeyframeGate::addOdometerReading(double metres) {
  if (has_position_ || !std::isfinite(metres)) return false;
  if (has_reading_) {
    const double step = std::fabs(metres - last_reading_);
    travelled_ += step;
    odometer_ += step;
  }
  has_reading_ = true;
  last_reading_ = metres;
  return true;
}

bool KeyframeGate::addReading(const OdometryReading& r) {
  if (r.source == OdometryReading::kOdometer) return addOdometerReading(r.metres);
  // The heading belongs to the position: one addPosition ignored leaves the
  // last one's.
  if (addPosition(r.x, r.y, r.z)) heading_ = r.heading;
  return true;
}

void KeyframeGate::setStampFloor(double stamp) {
  has_floor_ = true;
  floor_ = stamp;
}

void KeyframeGate::reset() {
  has_frame_ = has_keyframe_ = has_position_ = has_floor_ = has_reading_ = false;
  heading_ = bowg::OdometryHeading();
  last_reading_ = 0.0;
  floor_ = 0.0;
  last_frame_stamp_ = last_keyframe_stamp_ = 0.0;
  travelled_ = 0.0;
  odometer_ = 0.0;
}

double KeyframeGate::odometer() const {
  return hasOdometry() ? odometer_ : std::numeric_limits<double>::quiet_NaN();
}

bowg::OdometryPosition KeyframeGate::position() const {
  bowg::OdometryPosition p;
  if (has_position_) {
    p.x = last_x_;
    p.y = last_y_;
    p.z = last_z_;
  }
  return p;
}

void KeyframeGate::setOdometer(double base) {
  if (!std::isfinite(base) || base < 0.0) {
    throw std::invalid_argument("KeyframeGate::setOdometer: base must be finite and >= 0");
  }
  odometer_ = base;
}

}  // namespace bowg_ros
