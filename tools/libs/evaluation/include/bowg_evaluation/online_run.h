// What the nodelet did with a played bag, gathered from its outputs
// (KeyframeStatus per keyframe, LoopClosure per loop) after mapping their
// stamps to frame indices (stamp_index.h), and the summary bowg_bag_evaluator
// prints: the same metrics as bowg_evaluate (metrics.h) plus what only a live
// run has, the frames that never became keyframes.
//
// Unlike the offline tool, not every image need be a keyframe here: the
// nodelet's bounded queue drops the oldest frame when the detector falls
// behind, and the keyframe gate skips frames by time/distance. Frames dropped
// = images in the bag - distinct frames with a KeyframeStatus.
//
// Against reference maps (the nodelet's ~reference_maps recorded from other
// bags, every image a keyframe), the maps' images are frames 0..first-1 and
// the played bag's follow from `first_frame` on.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "bowg_evaluation/ground_truth.h"
#include "bowg_evaluation/metrics.h"

namespace bowg {
namespace eval {

class OnlineRun {
 public:
  explicit OnlineRun(std::size_t images_in_bag, int first_frame = 0)
      : images_(images_in_bag), first_(first_frame) {}

  /// A KeyframeStatus for `frame`; -1 (stamp not in the bag) is counted as
  /// unmapped. A repeated frame counts once.
  void addKeyframe(int frame);
  /// A LoopClosure; a query or match of -1 is counted as unmapped and the
  /// loop is not scored (it cannot be judged against the ground truth).
  /// `match_mission` names the match's mission (LoopClosure match_mission
  /// and match_mission_name), counted per mission.
  void addLoop(int query, int match, double score, const std::string& match_mission = "");

  std::size_t imagesInBag() const { return images_; }
  int firstFrame() const { return first_; }
  /// Loops per match mission (the names addLoop was given), mapped or not.
  const std::map<std::string, int>& loopsByMission() const { return by_mission_; }
  std::size_t keyframesSeen() const { return keyframes_.size(); }
  /// Images in the bag without a KeyframeStatus (0 when more were seen).
  std::size_t framesDropped() const;
  std::size_t unmappedStamps() const { return unmapped_; }
  bool sawKeyframe(int frame) const { return keyframes_.count(frame) > 0; }
  /// The bag's frames (first_frame..) without a KeyframeStatus, ascending.
  std::vector<int> missingFrames() const;
  /// The mapped loops, in arrival order.
  const std::vector<Detection>& detections() const { return detections_; }

 private:
  std::size_t images_ = 0;
  int first_ = 0;
  std::set<int> keyframes_;
  std::map<std::string, int> by_mission_;
  std::vector<Detection> detections_;
  std::size_t unmapped_ = 0;
};

/// The evaluator's report: header lines (`title`), then with a ground truth
/// the bowg_evaluate table row (precision, recall, F1, TP, FP at the
/// nodelet's min_score; recall at 100 % precision over the published loops'
/// scores, docs/evaluation.md "--sweep score"), the counts of keyframes,
/// dropped frames (and the first 20 of them) and unmapped stamps, the loops
/// per match mission (when named) and the list of loops.
std::string summarizeOnlineRun(const OnlineRun& run, const GroundTruth* gt,
                               const std::string& title);

}  // namespace eval
}  // namespace bowg
