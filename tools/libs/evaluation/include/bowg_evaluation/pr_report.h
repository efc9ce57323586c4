// Writers for the evaluation outputs: the PR curves as CSV and as a PNG plot
// drawn with OpenCV (axes, ticks, labels, one coloured curve per method and a
// legend).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bowg_evaluation/metrics.h"

namespace bowg {
namespace eval {

struct NamedCurve {
  std::string name;  ///< method / ablation row, shown in the legend
  std::vector<PrPoint> curve;
};

/// CSV "method,threshold,precision,recall,f1,tp,fp,positives", one row per
/// point. Atomic; throws bowg::IoError.
void writePrCurvesCsv(const std::string& path, const std::vector<NamedCurve>& curves);

/// Where the threshold labels of `points` go (putText's box of each, in
/// order): for each point the first of the places around it (right above,
/// right below, left above, left below) whose box of `sizes[i]` stays inside
/// `bounds` and keeps 2 px from every box in `taken`; an empty rect (the
/// label left out, the marker stays) where none does. Each placed box joins
/// `taken`, so the labels of later curves keep clear of it too. Throws
/// std::invalid_argument when the sizes do not match the points.
std::vector<cv::Rect> placeLabels(const std::vector<cv::Point>& points,
                                  const std::vector<cv::Size>& sizes, const cv::Rect& bounds,
                                  std::vector<cv::Rect>* taken);

/// Draws precision (y) against recall (x), both 0..1, as a BGR image.
/// Throws std::invalid_argument for a size below 200 x 150.
cv::Mat drawPrCurves(const std::vector<NamedCurve>& curves, const std::string& title,
                     int width = 800, int height = 600);

/// drawPrCurves + atomic PNG write; throws bowg::IoError.
void writePrPlot(const std::string& path, const std::vector<NamedCurve>& curves,
                 const std::string& title);

}  // namespace eval
}  // namespace bowg
