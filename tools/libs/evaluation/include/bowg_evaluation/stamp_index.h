// Maps image stamps back to 0-based frame indices (the n-th image message of
// a bag is frame n, the ground truth's indexing; docs/evaluation.md).
//
// The nodelet reports keyframes and loops by stamp: KeyframeStatus and the
// query of a LoopClosure carry the image header's stamp exactly, but the
// match stamp goes through the detector's `double` seconds (LoopResult::
// match_stamp), which for an epoch stamp (~1.7e9 s) keeps only ~0.2 us. So
// lookups take the nearest bag stamp within a tolerance, not an exact match.
#pragma once

#include <cstdint>
#include <vector>

namespace bowg {
namespace eval {

class StampIndex {
 public:
  /// `stamps_ns[n]`: stamp of frame n in nanoseconds, in bag order (need not
  /// be sorted or unique). A stamp that repeats maps to its FIRST frame: the
  /// nodelet skips a frame whose stamp does not increase, so the first is
  /// the one it can have processed.
  explicit StampIndex(const std::vector<std::int64_t>& stamps_ns);

  /// Frame whose stamp is nearest to `stamp_ns`, if within `tolerance_ns`
  /// (inclusive); -1 otherwise. Equidistant neighbours: the earlier stamp.
  /// Throws std::invalid_argument for a negative tolerance.
  int find(std::int64_t stamp_ns, std::int64_t tolerance_ns) const;

  std::size_t frames() const { return frames_; }

  /// Half the smallest gap between distinct stamps (capped at `cap_ns`): the
  /// largest tolerance that can never map a stamp to the wrong frame.
  std::int64_t safeTolerance(std::int64_t cap_ns) const;

 private:
  std::vector<std::pair<std::int64_t, int>> sorted_;  ///< (stamp, first frame), unique stamps
  std::size_t frames_ = 0;
};

/// Seconds to nanoseconds, rounded to the nearest (stamps from `double`).
std::int64_t secondsToNanoseconds(double seconds);

}  // namespace eval
}  // namespace bowg
