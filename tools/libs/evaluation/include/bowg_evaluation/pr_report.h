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

/// Draws precision (y) against recall (x), both 0..1, as a BGR image.
/// Throws std::invalid_argument for a size below 200 x 150.
cv::Mat drawPrCurves(const std::vector<NamedCurve>& curves, const std::string& title,
                     int width = 800, int height = 600);

/// drawPrCurves + atomic PNG write; throws bowg::IoError.
void writePrPlot(const std::string& path, const std::vector<NamedCurve>& curves,
                 const std::string& title);

}  // namespace eval
}  // namespace bowg
