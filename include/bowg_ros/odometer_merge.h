// Stamp order between a stamped odometer's readings and the camera's frames.
// A frame's metres driven are the latest reading stamped at or before the
// frame, whatever order the two topics' callbacks ran in: the readings and
// the frames come on two connections and callback threads, and under load a
// reading can be handled after the image it precedes. So a frame waits here
// until a reading stamped at or after it has arrived (then every reading up
// to its stamp, and nothing after, went to the keyframe gate before it), or
// until it has waited `wait` seconds: then it goes on late, with the
// readings that came, and is counted. ROS-free; the caller locks.
#pragma once

#include <cstddef>
#include <deque>
#include <utility>

namespace bowg_ros {

template <typename Frame>
class OdometerMerge {
 public:
  /// At most `max_waiting` frames wait (>= 1); beyond, the oldest goes on late.
  explicit OdometerMerge(std::size_t max_waiting = 256) : max_waiting_(max_waiting) {}

  /// One reading (metres driven) stamped `stamp` (s). False, and dropped,
  /// when stamped before the previous reading: the path is summed in stamp
  /// order.
  bool addReading(double stamp, double metres) {
    if (has_reading_ && stamp < last_stamp_) return false;
    has_reading_ = true;
    last_stamp_ = stamp;
    readings_.push_back({stamp, metres});
    return true;
  }

  /// A frame stamped `stamp`, arrived at `arrival` (s, the caller's clock).
  void addFrame(double stamp, double arrival, Frame frame) {
    frames_.push_back({stamp, arrival, std::move(frame)});
  }

  /// Hands on, in stamp order, everything ready at `now`:
  /// `on_reading(metres)` for each reading, `on_frame(Frame&&, bool late)`
  /// for each frame whose reading came (late = false) or that waited `wait`
  /// s or more, or overflowed max_waiting (late = true). A reading stamped
  /// before every waiting frame goes on at once; one stamped after a
  /// waiting frame only once that frame went on.
  template <typename OnReading, typename OnFrame>
  void release(double now, double wait, OnReading on_reading, OnFrame on_frame) {
    while (!frames_.empty()) {
      Waiting& f = frames_.front();
      const bool reached = has_reading_ && last_stamp_ >= f.stamp;
      const bool late = now - f.arrival >= wait || frames_.size() > max_waiting_;
      if (!reached && !late) break;
      while (!readings_.empty() && readings_.front().first <= f.stamp) {
        on_reading(readings_.front().second);
        readings_.pop_front();
      }
      Frame frame = std::move(f.frame);
      frames_.pop_front();
      on_frame(std::move(frame), !reached);
    }
    // What is left precedes the first waiting frame (else it went on above).
    for (; !readings_.empty(); readings_.pop_front()) on_reading(readings_.front().second);
  }

  bool hasReadings() const { return has_reading_; }
  std::size_t waiting() const { return frames_.size(); }

  /// The latest reading's stamp (0 before the first).
  double lastStamp() const { return last_stamp_; }

  /// A new run of readings (a replay that started over): the readings not
  /// handed on are dropped and an earlier stamp is taken again; the waiting
  /// frames stay.
  void restartReadings() {
    readings_.clear();
    has_reading_ = false;
    last_stamp_ = 0.0;
  }

 private:
  struct Waiting {
    double stamp, arrival;
    Frame frame;
  };
  std::size_t max_waiting_;
  std::deque<std::pair<double, double>> readings_;  ///< (stamp, metres), not yet handed on
  std::deque<Waiting> frames_;
  bool has_reading_ = false;
  double last_stamp_ = 0.0;  ///< the latest reading's stamp
};

}  // namespace bowg_ros
