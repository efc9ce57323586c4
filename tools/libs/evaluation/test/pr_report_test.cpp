#include "bowg_evaluation/pr_report.h"

#include <cmath>
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
  // The label "0.7": right of and above the point (6 px right and up), not
  // below it.
  EXPECT_TRUE(has(715, 740, 124, 135));
  EXPECT_FALSE(has(715, 740, 150, 170));
}

// Do two boxes overlap (touching edges do not)?
bool overlap(const cv::Rect& a, const cv::Rect& b) { return (a & b).area() > 0; }

TEST(PrReportTest, LabelsMoveAroundTheirPointOrAreLeftOutRatherThanOverlap) {
  const cv::Rect bounds(0, 0, 400, 300);
  const cv::Size size(24, 9);
  std::vector<cv::Rect> taken;
  // Two points 4 px apart: the first label right above its point, the
  // second, which would cover it there, right below its own.
  const std::vector<cv::Rect> two =
      placeLabels({{100, 100}, {104, 100}}, {size, size}, bounds, &taken);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0], cv::Rect(106, 85, 24, 9));
  EXPECT_EQ(two[1], cv::Rect(110, 106, 24, 9));
  ASSERT_EQ(taken.size(), 2u);
  // Eight points on one pixel (a sweep whose thresholds give the same
  // precision and recall): four places, four labels, the rest left out.
  taken.clear();
  const std::vector<cv::Point> same(8, cv::Point(200, 150));
  const std::vector<cv::Rect> crowded =
      placeLabels(same, std::vector<cv::Size>(8, size), bounds, &taken);
  std::size_t drawn = 0;
  for (std::size_t i = 0; i < crowded.size(); ++i) {
    if (crowded[i].area() == 0) continue;
    ++drawn;
    for (std::size_t j = 0; j < i; ++j) EXPECT_FALSE(overlap(crowded[i], crowded[j])) << i << j;
  }
  EXPECT_EQ(drawn, 4u);
  EXPECT_EQ(crowded[4], cv::Rect());
}

TEST(PrReportTest, LabelsStayInsideThePlotAndOffWhatIsTaken) {
  const cv::Rect bounds(0, 0, 400, 300);
  const cv::Size size(24, 9);
  // Top-right corner: neither above nor right fits, left below does.
  std::vector<cv::Rect> taken;
  const std::vector<cv::Rect> corner = placeLabels({{398, 2}}, {size}, bounds, &taken);
  EXPECT_EQ(corner[0], cv::Rect(368, 8, 24, 9));
  // A box already taken (the legend, another curve's label) beside the
  // point: the label goes to a side clear of it, 2 px apart at least.
  taken = {cv::Rect(100, 80, 60, 40)};
  const std::vector<cv::Rect> beside = placeLabels({{98, 100}}, {size}, bounds, &taken);
  ASSERT_GT(beside[0].area(), 0);
  EXPECT_FALSE(overlap(beside[0], cv::Rect(98, 78, 64, 44)));
  EXPECT_LT(beside[0].x + beside[0].width, 100);
  EXPECT_THROW(placeLabels({{1, 1}}, {}, bounds, &taken), std::invalid_argument);
}

TEST(PrReportTest, ADenseSweepOfTwoCurvesDrawsNoLabelOverAnother) {
  // Two curves of 40 thresholds each along nearly the same path, their
  // points where drawPrCurves puts them (800 x 600) and their labels about
  // the size of "1.85" at its label scale: many labels placed, none over
  // another.
  std::vector<NamedCurve> curves = {{"a", {}}, {"b", {}}};
  for (int i = 0; i < 40; ++i) {
    PrPoint p = point(1.0 - 0.005 * i, 0.02 * i);
    p.threshold = 2.0 - 0.05 * i;
    curves[0].curve.push_back(p);
    p.precision -= 0.01;
    curves[1].curve.push_back(p);
  }
  EXPECT_NO_THROW(drawPrCurves(curves, "dense"));
  const cv::Rect plot(70, 40, 710, 505);
  std::vector<cv::Rect> taken, all;
  for (const NamedCurve& c : curves) {
    std::vector<cv::Point> pts;
    for (const PrPoint& p : c.curve) {
      pts.emplace_back(70 + static_cast<int>(std::lround(p.recall * 710)),
                       545 - static_cast<int>(std::lround(p.precision * 505)));
    }
    const std::vector<cv::Rect> boxes =
        placeLabels(pts, std::vector<cv::Size>(pts.size(), cv::Size(24, 9)), plot, &taken);
    for (const cv::Rect& b : boxes) {
      if (b.area() > 0) all.push_back(b);
    }
  }
  EXPECT_GT(all.size(), 10u);  // thinned, not emptied
  EXPECT_LT(all.size(), 80u);  // 80 labels cannot all fit
  for (std::size_t i = 0; i < all.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) EXPECT_FALSE(overlap(all[i], all[j])) << i << " " << j;
  }
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
