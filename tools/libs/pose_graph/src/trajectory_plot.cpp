#include "bowg_pose_graph/trajectory_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace bowg {
namespace pose_graph {

cv::Mat plotTopView(const std::vector<Eigen::Vector3d>& truth,
                    const std::vector<Eigen::Vector3d>& odometry,
                    const std::vector<Eigen::Vector3d>& optimised,
                    const std::vector<std::pair<std::size_t, std::size_t>>& loops, int size) {
  cv::Mat canvas(size, size, CV_8UC3, cv::Scalar(255, 255, 255));
  double lo_x = std::numeric_limits<double>::max(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
  for (const auto* track : {&truth, &odometry, &optimised}) {
    for (const Eigen::Vector3d& p : *track) {
      lo_x = std::min(lo_x, p.x());
      hi_x = std::max(hi_x, p.x());
      lo_y = std::min(lo_y, p.y());
      hi_y = std::max(hi_y, p.y());
    }
  }
  if (!(hi_x >= lo_x)) return canvas;  // nothing to draw
  const int margin = 60;
  const double extent = std::max({hi_x - lo_x, hi_y - lo_y, 1e-3});
  const double scale = (size - 2 * margin) / extent;  // px per metre, same on both axes
  // World y up on the picture.
  const auto px = [&](const Eigen::Vector3d& p) {
    return cv::Point(static_cast<int>(margin + (p.x() - lo_x) * scale),
                     static_cast<int>(size - margin - (p.y() - lo_y) * scale));
  };
  const auto polyline = [&](const std::vector<Eigen::Vector3d>& track, const cv::Scalar& colour,
                            int width) {
    for (std::size_t i = 1; i < track.size(); ++i) {
      cv::line(canvas, px(track[i - 1]), px(track[i]), colour, width, cv::LINE_AA);
    }
  };
  polyline(odometry, cv::Scalar(40, 40, 220), 1);
  polyline(truth, cv::Scalar(0, 0, 0), 2);
  polyline(optimised, cv::Scalar(220, 90, 20), 1);
  // The loops over the tracks: under them, a loop whose ends the correction
  // brought together is a line of a few px hidden by the blue one.
  const cv::Scalar loop_grey(150, 150, 150);
  for (const auto& l : loops) {
    if (l.first < optimised.size() && l.second < optimised.size()) {
      cv::line(canvas, px(optimised[l.first]), px(optimised[l.second]), loop_grey, 1, cv::LINE_AA);
      cv::circle(canvas, px(optimised[l.first]), 4, loop_grey, 1, cv::LINE_AA);
    }
  }
  const auto legend_at = [&](const cv::Point& at, const cv::Scalar& colour, const char* text) {
    cv::line(canvas, at + cv::Point(0, -5), at + cv::Point(30, -5), colour, 2, cv::LINE_AA);
    cv::putText(canvas, text, at + cv::Point(40, 0), cv::FONT_HERSHEY_SIMPLEX, 0.5,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  };
  const auto legend = [&](int row, const cv::Scalar& colour, const char* text) {
    legend_at(cv::Point(margin, 22 + 20 * row), colour, text);
  };
  legend(0, cv::Scalar(0, 0, 0), "truth");
  legend(1, cv::Scalar(40, 40, 220), "odometry");
  legend(2, cv::Scalar(220, 90, 20), "pose graph with the detected loops");
  // Bottom left, beside the scale bar: a fourth row on top would reach into
  // the tracks (the margin is 60 px).
  const cv::Point loop_legend(margin, size - margin / 2);
  legend_at(loop_legend, loop_grey, "loop: ring at the query, line to the match");
  cv::circle(canvas, loop_legend + cv::Point(0, -5), 4, loop_grey, 1, cv::LINE_AA);
  // Scale bar: the largest 1-2-5 x 10^k metres under a fifth of the picture.
  double bar = std::pow(10.0, std::floor(std::log10(extent / 5)));
  for (double f : {5.0, 2.0}) {
    if (bar * f <= extent / 5) {
      bar *= f;
      break;
    }
  }
  const cv::Point end(size - margin, size - margin / 2);
  cv::line(canvas, end - cv::Point(static_cast<int>(bar * scale), 0), end, cv::Scalar(0, 0, 0), 2);
  char label[32];
  std::snprintf(label, sizeof label, "%g m", bar);
  cv::putText(canvas, label, end - cv::Point(static_cast<int>(bar * scale), 8),
              cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  return canvas;
}

}  // namespace pose_graph
}  // namespace bowg
