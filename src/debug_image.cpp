// Side-by-side debug image of a loop (see debug_image.h).
#include "bowg_ros/debug_image.h"

#include <algorithm>
#include <string>
#include <vector>
#include <opencv2/imgproc.hpp>

namespace bowg_ros {

cv::Mat drawDebugImage(const cv::Mat& query, const cv::Mat& match,
                       const std::vector<bowg::Correspondence>& inliers,
                       const std::string& caption) {
  // One caption line per '\n'-separated part, 18 px each.
  std::vector<std::string> lines;
  for (std::size_t start = 0;;) {
    const std::size_t end = caption.find('\n', start);
    lines.push_back(caption.substr(start, end == std::string::npos ? end : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  const int kCaption = 6 + 18 * static_cast<int>(lines.size());
  const cv::Size qs = query.empty() ? cv::Size(320, 240) : query.size();
  const cv::Size ms = match.empty() ? qs : match.size();
  cv::Mat canvas(std::max(qs.height, ms.height) + kCaption, qs.width + ms.width, CV_8UC3,
                 cv::Scalar(64, 64, 64));
  const auto paste = [&](const cv::Mat& grey, int x0) {
    if (grey.empty()) return;
    cv::Mat bgr;
    cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
    bgr.copyTo(canvas(cv::Rect(x0, kCaption, bgr.cols, bgr.rows)));
  };
  paste(query, 0);
  paste(match, qs.width);
  if (match.empty()) {
    cv::putText(canvas, "match image not cached", cv::Point(qs.width + 10, kCaption + 30),
                cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(200, 200, 200), 1);
  }
  for (const bowg::Correspondence& c : inliers) {
    const cv::Point2f q(c.query_x, c.query_y + kCaption);
    const cv::Point2f m(c.match_x + qs.width, c.match_y + kCaption);
    cv::line(canvas, q, m, cv::Scalar(0, 255, 0), 1, cv::LINE_AA);
    cv::circle(canvas, q, 3, cv::Scalar(0, 0, 255), 1, cv::LINE_AA);
    cv::circle(canvas, m, 3, cv::Scalar(0, 0, 255), 1, cv::LINE_AA);
  }
  for (std::size_t i = 0; i < lines.size(); ++i) {
    cv::putText(canvas, lines[i], cv::Point(4, 17 + 18 * static_cast<int>(i)),
                cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255, 255, 255), 1);
  }
  return canvas;
}

}  // namespace bowg_ros
