#include "bowg_evaluation/pr_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <string>
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

std::vector<cv::Rect> placeLabels(const std::vector<cv::Point>& points,
                                  const std::vector<cv::Size>& sizes, const cv::Rect& bounds,
                                  std::vector<cv::Rect>* taken) {
  if (points.size() != sizes.size()) {
    throw std::invalid_argument("placeLabels: " + std::to_string(points.size()) + " points, " +
                                std::to_string(sizes.size()) + " label sizes");
  }
  const int gap = 6;  // px between a point and its label: clear of the marker
  const int pad = 2;  // px kept between two labels
  std::vector<cv::Rect> placed;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const cv::Point& p = points[i];
    const cv::Size& s = sizes[i];
    const cv::Point corners[] = {{p.x + gap, p.y - gap - s.height},
                                 {p.x + gap, p.y + gap},
                                 {p.x - gap - s.width, p.y - gap - s.height},
                                 {p.x - gap - s.width, p.y + gap}};
    cv::Rect chosen;
    for (const cv::Point& corner : corners) {
      const cv::Rect box(corner, s);
      if ((box & bounds) != box) continue;
      const cv::Rect padded(box.x - pad, box.y - pad, box.width + 2 * pad, box.height + 2 * pad);
      const bool free = std::none_of(taken->begin(), taken->end(),
                                     [&](const cv::Rect& t) { return (t & padded).area() > 0; });
      if (free) {
        chosen = box;
        break;
      }
    }
    if (chosen.area() > 0) taken->push_back(chosen);
    placed.push_back(chosen);
  }
  return placed;
}

namespace {

const int kFont = cv::FONT_HERSHEY_SIMPLEX;

// The plot area of the image and the pixel of a (recall, precision) point.
struct PrPlot {
  cv::Rect area;
  cv::Point toPixel(double recall, double precision) const {
    return cv::Point(area.x + static_cast<int>(std::lround(recall * area.width)),
                     area.y + area.height - static_cast<int>(std::lround(precision * area.height)));
  }
};

// Distinct colours (BGR) for up to 8 methods, then repeated.
const cv::Scalar& curveColour(std::size_t k) {
  static const cv::Scalar colours[] = {{200, 80, 0},   {0, 140, 255},  {40, 160, 40}, {30, 30, 220},
                                       {160, 60, 160}, {60, 120, 140}, {180, 180, 0}, {90, 90, 90}};
  return colours[k % 8];
}

// Grid and ticks every 0.1, labelled every 0.2.
void drawGrid(const PrPlot& plot, cv::Mat* img) {
  for (int i = 0; i <= 10; ++i) {
    const double v = i / 10.0;
    const cv::Scalar grid(225, 225, 225);
    cv::line(*img, plot.toPixel(v, 0), plot.toPixel(v, 1), grid, 1);
    cv::line(*img, plot.toPixel(0, v), plot.toPixel(1, v), grid, 1);
    cv::line(*img, plot.toPixel(v, 0), plot.toPixel(v, 0) + cv::Point(0, 5), cv::Scalar(0, 0, 0),
             1);
    cv::line(*img, plot.toPixel(0, v), plot.toPixel(0, v) - cv::Point(5, 0), cv::Scalar(0, 0, 0),
             1);
    if (i % 2 == 0) {
      char label[8];
      std::snprintf(label, sizeof(label), "%.1f", v);
      cv::putText(*img, label, plot.toPixel(v, 0) + cv::Point(-12, 22), kFont, 0.45,
                  cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
      cv::putText(*img, label, plot.toPixel(0, v) + cv::Point(-40, 5), kFont, 0.45,
                  cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    }
  }
}

// The frame, the axis names, the title and the hint on the point labels.
void drawFrameAndTitles(const PrPlot& plot, const std::string& title, cv::Mat* img) {
  const cv::Rect& area = plot.area;
  cv::rectangle(*img, area, cv::Scalar(0, 0, 0), 1);
  cv::putText(*img, "recall", cv::Point(area.x + area.width / 2 - 25, img->rows - 12), kFont, 0.6,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  // Vertical y label: draw horizontally on a strip and rotate it.
  cv::Mat strip(24, 110, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::putText(strip, "precision", cv::Point(5, 17), kFont, 0.6, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  cv::Mat rotated;
  cv::rotate(strip, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  const int y0 = std::max(0, area.y + area.height / 2 - rotated.rows / 2);
  if (y0 + rotated.rows <= img->rows) {
    rotated.copyTo((*img)(cv::Rect(2, y0, rotated.cols, rotated.rows)));
  }
  cv::putText(*img, title, cv::Point(area.x, 26), kFont, 0.65, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  cv::putText(*img, "point labels: threshold", cv::Point(area.x + area.width - 170, 26), kFont,
              0.45, cv::Scalar(90, 90, 90), 1, cv::LINE_AA);
}

// Every curve with its markers and its legend entry, in the lower-left
// corner of the plot (PR curves rarely go there). The legend's boxes and
// the markers go to `taken` so that no threshold label covers them; the
// curves' pixels are returned.
std::vector<std::vector<cv::Point>> drawCurvesAndLegend(const std::vector<NamedCurve>& curves,
                                                        const PrPlot& plot, cv::Mat* img,
                                                        std::vector<cv::Rect>* taken) {
  const cv::Rect& area = plot.area;
  const auto legend_y = [&](std::size_t k) {
    return area.y + area.height - 15 - 22 * static_cast<int>(curves.size() - 1 - k);
  };
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const cv::Size text = cv::getTextSize(curves[k].name, kFont, 0.5, 1, nullptr);
    taken->emplace_back(area.x + 15, legend_y(k) - 11, 37 + text.width, 22);
  }
  std::vector<std::vector<cv::Point>> points(curves.size());
  for (std::size_t k = 0; k < curves.size(); ++k) {
    const cv::Scalar& colour = curveColour(k);
    // Points in threshold order (descending) trace recall increasing.
    std::vector<cv::Point>& pts = points[k];
    for (const PrPoint& p : curves[k].curve) pts.push_back(plot.toPixel(p.recall, p.precision));
    if (pts.size() > 1) cv::polylines(*img, pts, false, colour, 2, cv::LINE_AA);
    for (const cv::Point& p : pts) {
      cv::circle(*img, p, 4, colour, -1, cv::LINE_AA);
      taken->emplace_back(p.x - 3, p.y - 3, 7, 7);  // the marker's core
    }
    const int ly = legend_y(k);
    cv::line(*img, cv::Point(area.x + 15, ly), cv::Point(area.x + 45, ly), colour, 3, cv::LINE_AA);
    cv::putText(*img, curves[k].name, cv::Point(area.x + 52, ly + 5), kFont, 0.5,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  return points;
}

// A label per threshold of the sweep, so the reader can pick an operating
// point. Dense sweeps put points a few px apart: placeLabels moves a label
// to another side of its point or leaves it out (the marker stays) rather
// than print it over another label or marker.
void drawThresholdLabels(const std::vector<NamedCurve>& curves,
                         const std::vector<std::vector<cv::Point>>& points, const PrPlot& plot,
                         cv::Mat* img, std::vector<cv::Rect>* taken) {
  const double label_scale = 0.38;
  for (std::size_t k = 0; k < curves.size(); ++k) {
    std::vector<std::string> labels;
    std::vector<cv::Size> sizes;
    for (const PrPoint& p : curves[k].curve) {
      char label[24];
      std::snprintf(label, sizeof label, "%g", p.threshold);
      labels.push_back(label);
      sizes.push_back(cv::getTextSize(label, kFont, label_scale, 1, nullptr));
    }
    const std::vector<cv::Rect> boxes = placeLabels(points[k], sizes, plot.area, taken);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      if (boxes[i].area() == 0) continue;
      cv::putText(*img, labels[i], cv::Point(boxes[i].x, boxes[i].y + boxes[i].height), kFont,
                  label_scale, curveColour(k), 1, cv::LINE_AA);
    }
  }
}

}  // namespace

cv::Mat drawPrCurves(const std::vector<NamedCurve>& curves, const std::string& title, int width,
                     int height) {
  if (width < 200 || height < 150) {
    throw std::invalid_argument("drawPrCurves: image must be at least 200 x 150 px");
  }
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const int left = 70, right = 20, top = 40, bottom = 55;
  const PrPlot plot{cv::Rect(left, top, width - left - right, height - top - bottom)};
  drawGrid(plot, &img);
  drawFrameAndTitles(plot, title, &img);
  // Every curve and marker first, then the labels: a label then keeps clear
  // of every marker (their boxes are taken too) and no later curve's line
  // is drawn over it.
  std::vector<cv::Rect> taken;
  const std::vector<std::vector<cv::Point>> points =
      drawCurvesAndLegend(curves, plot, &img, &taken);
  drawThresholdLabels(curves, points, plot, &img, &taken);
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
