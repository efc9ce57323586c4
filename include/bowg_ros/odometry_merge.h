// Stamp order between the robot's stamped odometry and the camera's frames.
// A frame's odometry is the latest reading stamped at or before the frame,
// whatever order the topics' callbacks ran in: readings and frames come on
// separate connections and callback threads, and under load a reading can be
// handled after the image it precedes. So a frame waits here until every
// source that has sent readings (odometry positions, a stamped odometer) has
// one stamped at or after it (then every reading up to its stamp, and
// nothing after, went to the keyframe gate before it), or until it has
// waited `wait` seconds: then it goes on late, with the readings that came,
// and is counted. ROS-free; the caller locks.
#pragma once

#include <array>
#include <cstddef>
#include <deque>
#include <iterator>
#include <utility>

#include "bowg_ros/odometry_reading.h"

namespace bowg_ros {

template <typename Frame>
class OdometryMerge {
 public:
  /// At most `max_waiting` frames wait (>= 1); beyond, the oldest goes on late.
  explicit OdometryMerge(std::size_t max_waiting = 256) : max_waiting_(max_waiting) {}

  /// One reading stamped `stamp` (s). False, and dropped, when stamped
  /// before the previous reading of its source: each source's path is
  /// summed in stamp order.
  bool addReading(double stamp, const OdometryReading& r) {
    Stream& s = streams_[r.source];
    if (s.has_reading && stamp < s.last_stamp) return false;
    s.has_reading = true;
    s.last_stamp = stamp;
    // Kept in stamp order across the sources (the other source's latest
    // may be later): after every reading stamped at or before it.
    auto at = readings_.end();
    while (at != readings_.begin() && std::prev(at)->first > stamp) --at;
    readings_.insert(at, {stamp, r});
    return true;
  }

  /// A frame stamped `stamp`, arrived at `arrival` (s, the caller's clock).
  void addFrame(double stamp, double arrival, Frame frame) {
    frames_.push_back({stamp, arrival, std::move(frame)});
  }

  /// Hands on, in stamp order, everything ready at `now`:
  /// `on_reading(const OdometryReading&)` for each reading,
  /// `on_frame(Frame&&, bool late)` for each frame every source reached
  /// (late = false) or that waited `wait` s or more, or overflowed
  /// max_waiting (late = true). A reading stamped at or before every waiting
  /// frame goes on at once; one stamped after a waiting frame only once that
  /// frame went on.
  template <typename OnReading, typename OnFrame>
  void release(double now, double wait, OnReading on_reading, OnFrame on_frame) {
    while (!frames_.empty()) {
      Waiting& f = frames_.front();
      const bool reached = reachedBy(f.stamp);
      const bool late = now - f.arrival >= wait || frames_.size() > max_waiting_;
      if (!reached && !late) break;
      handOnUpTo(f.stamp, on_reading);
      Frame frame = std::move(f.frame);
      frames_.pop_front();
      on_frame(std::move(frame), !reached);
    }
    if (frames_.empty()) {
      for (; !readings_.empty(); readings_.pop_front()) on_reading(readings_.front().second);
    } else {
      handOnUpTo(frames_.front().stamp, on_reading);
    }
  }

  bool hasReadings() const {
    return hasReadings(OdometryReading::kOdometer) || hasReadings(OdometryReading::kPosition);
  }
  bool hasReadings(OdometryReading::Source source) const { return streams_[source].has_reading; }
  std::size_t waiting() const { return frames_.size(); }

  /// The latest reading's stamp of `source` (0 before the first).
  double lastStamp(OdometryReading::Source source) const { return streams_[source].last_stamp; }

  /// A new run of `source`'s readings (a replay that started over): its
  /// readings not handed on are dropped and an earlier stamp is taken again;
  /// the waiting frames stay.
  void restartReadings(OdometryReading::Source source) {
    for (auto it = readings_.begin(); it != readings_.end();) {
      it = it->second.source == source ? readings_.erase(it) : std::next(it);
    }
    streams_[source] = Stream();
  }

 private:
  struct Waiting {
    double stamp, arrival;
    Frame frame;
  };
  struct Stream {
    bool has_reading = false;
    double last_stamp = 0.0;  ///< the latest reading's stamp
  };

  /// Every source that has sent readings has one stamped at or after `stamp`.
  bool reachedBy(double stamp) const {
    bool any = false;
    for (const Stream& s : streams_) {
      if (!s.has_reading) continue;
      if (s.last_stamp < stamp) return false;
      any = true;
    }
    return any;
  }

  template <typename OnReading>
  void handOnUpTo(double stamp, OnReading& on_reading) {
    while (!readings_.empty() && readings_.front().first <= stamp) {
      on_reading(readings_.front().second);
      readings_.pop_front();
    }
  }

  std::size_t max_waiting_;
  std::deque<std::pair<double, OdometryReading>> readings_;  ///< by stamp, not yet handed on
  std::deque<Waiting> frames_;
  std::array<Stream, OdometryReading::kSources> streams_;
};

}  // namespace bowg_ros
