#include "bowg_evaluation/online_run.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace bowg {
namespace eval {
namespace {

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(OnlineRun, CountsKeyframesDropsAndUnmappedStamps) {
  OnlineRun run(10);
  for (int f : {0, 1, 2, 3, 5, 6, 7, 8, 8}) run.addKeyframe(f);  // 4 and 9 missing, 8 twice
  run.addKeyframe(-1);
  run.addLoop(5, -1, 0.4);
  // 8 distinct frames of 10 -> 2 dropped; two unmapped stamps.
  EXPECT_EQ(run.keyframesSeen(), 8u);
  EXPECT_EQ(run.framesDropped(), 2u);
  EXPECT_EQ(run.unmappedStamps(), 2u);
  EXPECT_TRUE(run.sawKeyframe(8));
  EXPECT_FALSE(run.sawKeyframe(4));
  EXPECT_TRUE(run.detections().empty());
  EXPECT_EQ(run.missingFrames(), (std::vector<int>{4, 9}));
  EXPECT_TRUE(has(summarizeOnlineRun(run, nullptr, ""), "frames without a keyframe status: 4 9\n"));
  // More keyframes than images (stamps from elsewhere) never underflows.
  OnlineRun small(1);
  small.addKeyframe(0);
  small.addKeyframe(1);
  EXPECT_EQ(small.framesDropped(), 0u);
}

TEST(OnlineRun, SummaryHasTheOfflineToolsMetrics) {
  // gt: 5 -> {1}, 7 -> {2, 3}, 9 -> {} : P = 2 queries with a revisit.
  const GroundTruth gt = parseGroundTruth("5: 1\n7: 2,3\n9:\n", "gt");
  OnlineRun run(10);
  for (int f = 0; f < 10; ++f) run.addKeyframe(f);
  run.addLoop(5, 1, 0.9);  // correct
  run.addLoop(7, 0, 0.5);  // wrong place
  run.addLoop(9, 2, 0.3);  // no revisit: wrong
  // TP = 1, FP = 2: precision 1/3 = 0.333, recall 1/2 = 0.500,
  // F1 = 2 (1/3)(1/2) / (1/3 + 1/2) = (1/3) / (5/6) = 0.400.
  // Score sweep: at 0.9 TP 1 FP 0 -> R@100%P = 0.5 at threshold 0.900.
  const std::string s = summarizeOnlineRun(run, &gt, "title line");
  EXPECT_TRUE(has(s, "title line\n")) << s;
  EXPECT_TRUE(
      has(s, "nodelet            0.333   0.500   0.400    1    2    0.500 (    0.900)      3"))
      << s;
  EXPECT_TRUE(has(s, "frames dropped: 0\n")) << s;
  EXPECT_TRUE(has(s, "keyframes processed: 10\n")) << s;
  EXPECT_TRUE(has(s, "loop 5 -> 1  score 0.900  correct")) << s;
  EXPECT_TRUE(has(s, "loop 7 -> 0  score 0.500  wrong")) << s;

  // Without a ground truth: counts only, no table.
  const std::string counts = summarizeOnlineRun(run, nullptr, "");
  EXPECT_TRUE(has(counts, "no ground truth")) << counts;
  EXPECT_FALSE(has(counts, "precision")) << counts;
}

}  // namespace
}  // namespace eval
}  // namespace bowg
