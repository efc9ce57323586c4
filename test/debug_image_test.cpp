// drawDebugImage: layout (panels, caption lines), placeholder, inlier lines.
#include "bowg_ros/debug_image.h"

#include <gtest/gtest.h>

namespace bowg_ros {
namespace {

TEST(DebugImage, QueryLeftMatchRightOneCaptionLinePerPart) {
  const cv::Mat query(240, 320, CV_8UC1, cv::Scalar(10));
  const cv::Mat match(240, 320, CV_8UC1, cv::Scalar(200));
  const cv::Mat out = drawDebugImage(query, match, {}, "line one\nline two");
  ASSERT_EQ(out.type(), CV_8UC3);
  const int caption = 6 + 2 * 18;
  ASSERT_EQ(out.size(), cv::Size(640, 240 + caption));
  EXPECT_EQ(out.at<cv::Vec3b>(caption + 100, 100), cv::Vec3b(10, 10, 10));
  EXPECT_EQ(out.at<cv::Vec3b>(caption + 100, 420), cv::Vec3b(200, 200, 200));
  // One line: a shorter caption band.
  EXPECT_EQ(drawDebugImage(query, match, {}, "one").rows, 240 + 6 + 18);
}

TEST(DebugImage, MissingMatchIsAGreyPanelAndInliersAreGreenLines) {
  const cv::Mat query(240, 320, CV_8UC1, cv::Scalar(0));
  const cv::Mat none = drawDebugImage(query, cv::Mat(), {}, "c");
  const int caption = 24;
  EXPECT_EQ(none.at<cv::Vec3b>(caption + 200, 600), cv::Vec3b(64, 64, 64));
  bowg::Correspondence c;
  c.query_x = 100;
  c.query_y = 100;
  c.match_x = 100;  // right panel x = 420
  c.match_y = 100;
  const cv::Mat lines = drawDebugImage(query, query, {c}, "c");
  // Half way along the horizontal line from (100, 124) to (420, 124).
  const cv::Vec3b mid = lines.at<cv::Vec3b>(caption + 100, 260);
  EXPECT_EQ(mid[0], 0);
  EXPECT_GT(mid[1], 200);
  EXPECT_EQ(mid[2], 0);
}

}  // namespace
}  // namespace bowg_ros
