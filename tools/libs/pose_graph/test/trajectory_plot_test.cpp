// plotTopView: the loops are drawn where their ends are, over the tracks.
#include "bowg_pose_graph/trajectory_plot.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace bowg {
namespace pose_graph {
namespace {

// A U open to the left, 10 m x 2 m: 900 px with the 60 px margin give 78 px
// per metre, so (x, y) m is at pixel (60 + 78 x, 840 - 78 y).
const std::vector<Eigen::Vector3d> kTrack = {{0, 0, 0}, {5, 0, 0},  {10, 0, 0},
                                             {10, 2, 0}, {5, 2, 0}, {0, 2, 0}};

// Any pixel of the box grey (the loops' colour, anti-aliased onto white),
// not white and not one of the tracks' colours?
bool hasGrey(const cv::Mat& img, int x0, int x1, int y0, int y1) {
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
      if (std::abs(p[0] - p[1]) < 6 && std::abs(p[1] - p[2]) < 6 && p[0] > 100 && p[0] < 235) {
        return true;
      }
    }
  }
  return false;
}

TEST(TrajectoryPlot, EachLoopIsAGreyLineFromQueryToMatchAndARingAtTheQuery) {
  // Loop 5 -> 0 spans the open side, (0, 2) to (0, 0): pixels (60, 684) to
  // (60, 840), where no track runs. Loop 1 -> 1 is a loop whose ends the
  // correction brought together at (5, 0), pixel (450, 840): only its ring
  // (radius 4 px) shows, above and below the track's line.
  const std::vector<std::pair<std::size_t, std::size_t>> loops = {{5, 0}, {1, 1}};
  const cv::Mat with = plotTopView(kTrack, kTrack, kTrack, loops);
  const cv::Mat without = plotTopView(kTrack, kTrack, kTrack, {});
  ASSERT_EQ(with.size(), cv::Size(900, 900));
  EXPECT_TRUE(hasGrey(with, 59, 61, 750, 770));   // the line, halfway
  EXPECT_FALSE(hasGrey(without, 59, 61, 750, 770));
  EXPECT_TRUE(hasGrey(with, 446, 454, 834, 836));  // the ring's top
  EXPECT_FALSE(hasGrey(without, 446, 454, 834, 836));
  // A loop naming a frame the tracks lack is left out, not drawn to 0.
  const cv::Mat bad = plotTopView(kTrack, kTrack, kTrack, {{5, 99}});
  EXPECT_FALSE(hasGrey(bad, 59, 61, 750, 770));
}

}  // namespace
}  // namespace pose_graph
}  // namespace bowg
