#include "bowg_evaluation/online_run.h"

#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <sstream>

namespace bowg {
namespace eval {

void OnlineRun::addKeyframe(int frame) {
  if (frame < 0) {
    ++unmapped_;
    return;
  }
  keyframes_.insert(frame);
}

void OnlineRun::addLoop(int query, int match, double score, const std::string& match_mission) {
  if (!match_mission.empty()) ++by_mission_[match_mission];
  if (query < 0 || match < 0) {
    ++unmapped_;
    return;
  }
  detections_.push_back({query, match, score});
}

std::size_t OnlineRun::framesDropped() const {
  const std::size_t seen = std::distance(keyframes_.lower_bound(first_), keyframes_.end());
  return seen >= images_ ? 0 : images_ - seen;
}

std::vector<int> OnlineRun::missingFrames() const {
  std::vector<int> missing;
  for (std::size_t i = 0; i < images_; ++i) {
    const int f = first_ + static_cast<int>(i);
    if (!keyframes_.count(f)) missing.push_back(f);
  }
  return missing;
}

std::string summarizeOnlineRun(const OnlineRun& run, const GroundTruth* gt,
                               const std::string& title) {
  std::ostringstream s;
  s << title;
  if (!title.empty() && title.back() != '\n') s << "\n";
  if (gt != nullptr) {
    // Every published loop passed the nodelet's min_score: "at min_score" is
    // all of them; the curve sweeps their final scores.
    const PrPoint at = evaluateAt(run.detections(), *gt, -std::numeric_limits<double>::infinity());
    const PrPoint full = recallAtFullPrecision(precisionRecallCurve(run.detections(), *gt));
    char threshold[32] = "none";
    if (!std::isinf(full.threshold))
      std::snprintf(threshold, sizeof(threshold), "%.3f", full.threshold);
    char line[256];
    s << "ground truth: " << gt->positives() << " queries with a revisit\n"
      << "R@100%P = recall at 100 % precision over the published loops' scores (its threshold)\n"
      << "row            precision  recall      F1   TP   FP  R@100%P (threshold)  loops\n";
    std::snprintf(line, sizeof(line), "%-14s %9.3f %7.3f %7.3f %4d %4d  %7.3f (%9s)  %5zu\n",
                  "nodelet", at.precision, at.recall, at.f1, at.true_positives, at.false_positives,
                  full.recall, threshold, run.detections().size());
    s << line;
  } else {
    s << "no ground truth: counts only\n";
  }
  s << "images in bag: " << run.imagesInBag() << "\n"
    << "keyframes processed: " << run.keyframesSeen() << "\n"
    << "frames dropped: " << run.framesDropped() << "\n";
  const std::vector<int> missing = run.missingFrames();
  if (!missing.empty()) {
    s << "frames without a keyframe status:";
    for (std::size_t i = 0; i < missing.size() && i < 20; ++i) s << " " << missing[i];
    s << (missing.size() > 20 ? " ...\n" : "\n");
  }
  s << "unmapped stamps: " << run.unmappedStamps() << "\n";
  if (!run.loopsByMission().empty()) {
    s << "loops by match mission:";
    for (const auto& m : run.loopsByMission()) s << " " << m.first << " " << m.second << ";";
    s << "\n";
  }
  s << "loops (query -> match, score" << (gt ? ", correct" : "") << "):\n";
  for (const Detection& d : run.detections()) {
    char line[128];
    std::snprintf(line, sizeof(line), "  loop %d -> %d  score %.3f", d.query, d.match, d.score);
    s << line;
    if (gt) s << (gt->contains(d.query, d.match) ? "  correct" : "  wrong");
    s << "\n";
  }
  return s.str();
}

}  // namespace eval
}  // namespace bowg
