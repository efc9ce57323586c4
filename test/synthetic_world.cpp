#include "synthetic_world.h"

#include <opencv2/imgproc.hpp>

namespace bowg_ros {
namespace test {

cv::Mat makeWorld(int width, int height, std::uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat img(height, width, CV_8UC1, cv::Scalar(110));
  const int shapes = width * height / 250;
  for (int i = 0; i < shapes; ++i) {
    const cv::Point c(rng.uniform(0, width), rng.uniform(0, height));
    const cv::Scalar value(rng.uniform(0, 256));
    switch (rng.uniform(0, 3)) {
      case 0:
        cv::ellipse(img, c, cv::Size(rng.uniform(3, 22), rng.uniform(3, 22)),
                    rng.uniform(0.0, 180.0), 0, 360, value, cv::FILLED);
        break;
      case 1:
        cv::rectangle(img, c, c + cv::Point(rng.uniform(4, 28), rng.uniform(4, 28)), value,
                      cv::FILLED);
        break;
      default:
        cv::line(img, c, c + cv::Point(rng.uniform(-30, 30), rng.uniform(-30, 30)), value,
                 rng.uniform(1, 4));
        break;
    }
  }
  cv::GaussianBlur(img, img, cv::Size(3, 3), 0.8);
  return img;
}

cv::Mat viewAt(const cv::Mat& world, int x, int view_width, int brightness) {
  cv::Mat view = world(cv::Rect(x, 0, view_width, world.rows)).clone();
  if (brightness != 0) view.convertTo(view, CV_8U, 1.0, brightness);
  return view;
}

std::vector<int> trajectory(int forward, int revisit, int step, int offset) {
  std::vector<int> xs;
  for (int i = 0; i < forward; ++i) xs.push_back(i * step);
  for (int j = 0; j < revisit; ++j) xs.push_back(j * step + offset);
  return xs;
}

}  // namespace test
}  // namespace bowg_ros
