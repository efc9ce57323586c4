#include "bowg_evaluation/pr_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bowg/core/atomic_file.h"
#include "bowg/core/errors.h"

namespace bowg {
namespace eval {

void writePrCurvesCsv(const std::string& path, const std::vector<NamedCurve>& curves) {
  std::ostringstream out;
  out << "method,threshold,precision,recall,f1,tp,fp,positives\n" << std::setprecision(9);
  for (const NamedCurve& c : curves) {
    for (const PrPoint& p : c.curve) {
      out << c.name << "," << p.threshold << "," << p.precision << "," << p.recall << "," << p.f1
          << "," << p.true_positives << "," << p.false_positives << "," << p.positives << "\n";
    }
  }
  writeFileAtomically(path, out.str());
}

cv::Mat drawPrCurves(const std::vector<NamedCurve>& curves, const std::string& title, int width,
                     int height) {
  if (width < 200 || height < 150) {
    throw std::invalid_argument("drawPrCurves: image must be at least 200 x 150 px");
  }
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const int left = 70, right = 20, top = 40, bottom = 55;
  const cv::Rect plot(left, top, width - left - right, height - top - bottom);
  auto toPixel = [&](double recall, double precision) {
    return cv::Point(plot.x + static_cast<int>(std::lround(recall * plot.width)),
                     plot.y + plot.height - static_cast<int>(std::lround(precision * plot.height)));
  };
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  // Grid and ticks every 0.1, labelled every 0.2.
  for (int i = 0; i <= 10; ++i) {
    const double v = i / 10.0;
    const cv::Scalar grid(225, 225, 225);
    cv::line(img, toPixel(v, 0), toPixel(v, 1), grid, 1);
    cv::line(img, toPixel(0, v), toPixel(1, v), grid, 1);
    cv::line(img, toPixel(v, 0), toPixel(v, 0) + cv::Point(0, 5), cv::Scalar(0, 0, 0), 1);
    cv::line(img, toPixel(0, v), toPixel(0, v) - cv::Point(5, 0), cv::Scalar(0, 0, 0), 1);
    if (i % 2 == 0) {
      char label[8];
      std::snprintf(label, sizeof(label), "%.1f", v);
      cv::putText(img, label, toPixel(v, 0) + cv::Point(-12, 22), font, 0.45, cv::Scalar(0, 0, 0), 1,
                  cv::LINE_AA);
      cv::putText(img, label, toPixel(0, v) + cv::Point(-40, 5), font, 0.45, cv::Scalar(0, 0, 0), 1,
                  cv::LINE_AA);
    }
  }
  cv::rectangle(img, plot, cv::Scalar(0, 0, 0), 1);
  cv::putText(img, "recall", cv::Point(plot.x + plot.width / 2 - 25, height - 12), font, 0.6,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  // Vertical y label: draw horizontally on a strip and rotate it.
  {
    cv::Mat strip(24, 110, CV_8UC3, cv::Scalar(255, 255, 255));
    cv::putText(strip, "precision", cv::Point(5, 17), font, 0.6, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    cv::Mat rotated;
    cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
    const int y0 = std::max(0, plot.y + plot.height / 2 - rotated.rows / 2);
    if (y0 + rotated.rows <= height) rotated.copyTo(img(cv::Rect(2, y0, rotated.cols, rotated.rows)));
  }
  cv::putText(img, title, cv::Point(left, 26), font, 0.65, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  cv::putText(img, "point labels: threshold", cv::Point(plot.x + plot.width - 170, 26), font, 0.45,
              cv::Scalar(90, 90, 90), 1, cv::LINE_AA);

  // Distinct colours (BGR) for up to 8 methods, then repeat.
  const cv::Scalar colours[] = {{200, 80, 0},  {0, 140, 255}, {40, 160, 40}, {30, 30, 220},
                                {160, 60, 160}, {60, 120, 140}, {180, 180, 0}, {90, 90, 90}};
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const cv::Scalar colour = colours[k % 8];
    // Points in threshold order (descending) trace recall increasing.
    std::vector<cv::Point> pts;
    for (const PrPoint& p : curves[k].curve) pts.push_back(toPixel(p.recall, p.precision));
    if (pts.size() > 1) cv::polylines(img, pts, false, colour, 2, cv::LINE_AA);
    // A marker per threshold of the sweep, labelled with its value, so the
    // reader can pick an operating point (labels that would overlap the
    // previous one are left out; every point keeps its marker).
    cv::Point last_label(-1000, -1000);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      cv::circle(img, pts[i], 4, colour, -1, cv::LINE_AA);
      char label[24];
      std::snprintf(label, sizeof label, "%g", curves[k].curve[i].threshold);
      // Above and right of the point, staggered per curve; below or left of
      // it where that would leave the plot.
      cv::Point at = pts[i] + cv::Point(6, -6 - 12 * static_cast<int>(k % 3));
      if (at.y < plot.y + 10) at.y = pts[i].y + 16 + 12 * static_cast<int>(k % 3);
      if (at.x > plot.x + plot.width - 28) at.x = pts[i].x - 34;  // left of points at recall ~1
      if (std::abs(at.x - last_label.x) < 28 && std::abs(at.y - last_label.y) < 12) continue;
      cv::putText(img, label, at, font, 0.38, colour, 1, cv::LINE_AA);
      last_label = at;
    }
    // Legend in the lower-left corner of the plot (PR curves rarely go there).
    const int ly = plot.y + plot.height - 15 - 22 * static_cast<int>(curves.size() - 1 - k);
    cv::line(img, cv::Point(plot.x + 15, ly), cv::Point(plot.x + 45, ly), colour, 3, cv::LINE_AA);
    cv::putText(img, curves[k].name, cv::Point(plot.x + 52, ly + 5), font, 0.5, cv::Scalar(0, 0, 0),
                1, cv::LINE_AA);
  }
  return img;
}

void writePrPlot(const std::string& path, const std::vector<NamedCurve>& curves,
                 const std::string& title) {
  std::vector<uchar> png;
  if (!cv::imencode(".png", drawPrCurves(curves, title), png)) {
    throw IoError("cannot encode the PR plot for " + path);
  }
  writeFileAtomically(path, std::string(png.begin(), png.end()));
}

}  // namespace eval
}  // namespace bowg
