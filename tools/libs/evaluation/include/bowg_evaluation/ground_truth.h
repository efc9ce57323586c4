// Loop ground truth in the project's common text format, and its
// computation from poses.
//
// Format (one query per line, 0-based frame indices: the n-th image message
// of the bag / the n-th image of the sorted folder is frame n):
//   # comment lines and blank lines are ignored
//   <query>: <match>,<match>,...
//   <query>:                      (an explicitly empty set is allowed)
// Every match is an earlier frame (0 <= match < query), a query appears at
// most once; queries not listed have an empty set (no revisit).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace bowg {
namespace eval {

struct GroundTruth {
  /// query -> sorted, unique earlier frames that see the same place.
  std::map<int, std::vector<int>> loops;

  /// True when `match` is a correct loop for `query`.
  bool contains(int query, int match) const;
  /// True when `query` has a non-empty set (it should be detected).
  bool hasLoop(int query) const;
  /// Number of queries with a non-empty set: the recall denominator.
  int positives() const;
};

/// Parses the format above. Throws bowg::FormatError("<path>:<line>: <why>")
/// on a malformed line, a negative or non-earlier match, a duplicate query;
/// bowg::IoError when the file cannot be read.
GroundTruth readGroundTruth(const std::string& path);
/// Same, from text (`source` names it in error messages).
GroundTruth parseGroundTruth(const std::string& text, const std::string& source);
/// Writes only queries with a non-empty set, after `header` (each line is
/// prefixed with "# "). Atomic; throws bowg::IoError.
void writeGroundTruth(const std::string& path, const GroundTruth& gt, const std::string& header);

/// A frame's position and direction of travel (roll is deliberately absent:
/// a revisit with another roll is the same place).
struct TravelPose {
  double x = 0, y = 0, z = 0;     ///< metres
  double hx = 1, hy = 0, hz = 0;  ///< unit direction of travel
  double distance = 0;            ///< distance driven since frame 0 (m)
};

struct GroundTruthOptions {
  double max_distance_m = 0.15;  ///< positions closer than this
  double max_heading_deg = 30;   ///< directions of travel closer than this
  /// Frames driven less than this before the query are the immediate past,
  /// not a revisit.
  double exclude_recent_m = 3.0;
  void validate() const;  ///< throws std::invalid_argument naming the field
};

/// gt[q] = { m < q : |p_q - p_m| < max_distance, angle(h_q, h_m) <
/// max_heading, distance_q - distance_m >= exclude_recent }.
GroundTruth groundTruthFromPoses(const std::vector<TravelPose>& poses,
                                 const GroundTruthOptions& options);

}  // namespace eval
}  // namespace bowg
