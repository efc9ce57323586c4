#include "bowg_evaluation/pr_report.h"

#include <cstdlib>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

namespace bowg {
namespace eval {
namespace {

PrPoint point(double precision, double recall) {
  PrPoint p;
  p.precision = precision;
  p.recall = recall;
  return p;
}

TEST(PrReportTest, PlotDrawsEachCurveInItsColourWhereItBelongs) {
  // Plot area for 800 x 600: x from 70 to 780 (710 px), y from 40 to 545
  // (505 px). Recall 0.5 -> x = 70 + 355 = 425; precision 0.5 -> y = 40 +
  // 505 - 252.5 -> 292 or 293.
  const std::vector<NamedCurve> curves = {{"first", {point(0.5, 0.5)}},
                                          {"second", {point(1.0, 0.2), point(0.8, 0.9)}}};
  const cv::Mat img = drawPrCurves(curves, "test");
  ASSERT_EQ(img.size(), cv::Size(800, 600));
  ASSERT_EQ(img.type(), CV_8UC3);
  const cv::Vec3b first_colour(200, 80, 0);
  bool found = false;
  for (int y = 290; y <= 295; ++y) {
    for (int x = 423; x <= 427; ++x) found = found || img.at<cv::Vec3b>(y, x) == first_colour;
  }
  EXPECT_TRUE(found);
  // The second curve's colour appears somewhere, and no curve colour at a
  // far corner of the plot (recall 1, precision 0).
  const cv::Vec3b second_colour(0, 140, 255);
  bool second = false;
  for (int y = 0; y < img.rows && !second; ++y) {
    for (int x = 0; x < img.cols; ++x) second = second || img.at<cv::Vec3b>(y, x) == second_colour;
  }
  EXPECT_TRUE(second);
  EXPECT_NE(img.at<cv::Vec3b>(540, 770), first_colour);
  EXPECT_THROW(drawPrCurves(curves, "t", 100, 100), std::invalid_argument);
}

TEST(PrReportTest, EachThresholdHasAMarkerAndALabel) {
  // One curve (the second colour, k = 1) from (recall 0.2, precision 1) to
  // (0.9, 0.8): pixels (212, 40) and (709, 141); thresholds 1.2 and 0.7.
  PrPoint a = point(1.0, 0.2), b = point(0.8, 0.9);
  a.threshold = 1.2;
  b.threshold = 0.7;
  const std::vector<NamedCurve> curves = {{"first", {}}, {"second", {a, b}}};
  const cv::Mat img = drawPrCurves(curves, "test");
  const cv::Vec3b colour(0, 140, 255);
  // Close to the colour (the labels are anti-aliased).
  const auto has = [&](int x0, int x1, int y0, int y1) {
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
        if (std::abs(p[0] - colour[0]) < 50 && std::abs(p[1] - colour[1]) < 50 &&
            std::abs(p[2] - colour[2]) < 50)
          return true;
      }
    return false;
  };
  // The marker: 3 px off the 2 px line, across its direction (slope ~0.2).
  EXPECT_TRUE(has(709, 711, 137, 138));
  // The label "0.7": right of and above the point (6 px right, 18 px up for
  // the second curve), not below it.
  EXPECT_TRUE(has(715, 740, 110, 124));
  EXPECT_FALSE(has(715, 740, 150, 170));
}

TEST(PrReportTest, WritesCsvAndPng) {
  const std::string dir = BOWG_TEST_OUTPUT_DIR;
  PrPoint p = point(0.75, 0.6);
  p.threshold = 0.3;
  p.true_positives = 3;
  p.false_positives = 1;
  p.positives = 5;
  const std::vector<NamedCurve> curves = {{"bow", {p}}, {"bowg", {p, p}}};
  writePrCurvesCsv(dir + "/pr_test.csv", curves);
  std::ifstream in(dir + "/pr_test.csv");
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "method,threshold,precision,recall,f1,tp,fp,positives");
  EXPECT_EQ(lines[1].substr(0, 9), "bow,0.3,0");
  writePrPlot(dir + "/pr_test.png", curves, "title");
  EXPECT_EQ(cv::imread(dir + "/pr_test.png").size(), cv::Size(800, 600));
}

}  // namespace
}  // namespace eval
}  // namespace bowg
