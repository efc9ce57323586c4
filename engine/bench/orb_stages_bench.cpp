// Where OpenCV's multi-scale ORB spends its time at the pipe preset's FAST
// threshold (10) against DLoopDetector's (20): the whole detectAndCompute,
// and the three image-wide steps inside it timed alone with the same
// OpenCV calls: the pyramid's resizing, FAST on every level, and the 7x7
// Gaussian blur of every level for the descriptors. The rest (Harris
// responses, orientations, descriptors) works on a few hundred keypoints.
//
// Frames: the PNG images of BOWG_BENCH_IMAGES (a directory, e.g. a rendered
// sequence of scripts/peer_benchmark.sh; every 5th of its first 300) or,
// without it, one synthetic 640x480 texture.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "feature_test_images.h"

namespace {

// cv::ORB's parameters in config/pipe.yaml and in the peer's driver.
const int kLevels = 8;
const double kScaleFactor = 1.2;
const int kFeatures = 500;

const std::vector<cv::Mat>& frames() {
  static const std::vector<cv::Mat> images = [] {
    std::vector<cv::Mat> out;
    if (const char* dir = std::getenv("BOWG_BENCH_IMAGES")) {
      std::vector<cv::String> files;
      cv::glob(std::string(dir) + "/*.png", files, false);
      std::sort(files.begin(), files.end());
      for (std::size_t i = 0; i < files.size() && i < 300; i += 5) {
        const cv::Mat grey = cv::imread(files[i], cv::IMREAD_GRAYSCALE);
        if (!grey.empty()) out.push_back(grey);
      }
    } else {
      out.push_back(bowg::test::texturedImage(640, 480, 400, 42));
    }
    return out;
  }();
  return images;
}

// The levels as cv::ORB sizes and computes them: level i is level i-1
// resized to the image's size / 1.2^i (INTER_LINEAR_EXACT).
std::vector<cv::Mat> pyramid(const cv::Mat& image) {
  std::vector<cv::Mat> levels(kLevels);
  levels[0] = image;
  for (int i = 1; i < kLevels; ++i) {
    const double scale = static_cast<float>(std::pow(kScaleFactor, i));
    const cv::Size size(cvRound(image.cols / scale), cvRound(image.rows / scale));
    cv::resize(levels[i - 1], levels[i], size, 0, 0, cv::INTER_LINEAR_EXACT);
  }
  return levels;
}

// Every frame's levels, made once for the benchmarks of a step on them.
const std::vector<std::vector<cv::Mat>>& framePyramids() {
  static const std::vector<std::vector<cv::Mat>> all = [] {
    std::vector<std::vector<cv::Mat>> out;
    for (const cv::Mat& f : frames()) out.push_back(pyramid(f));
    return out;
  }();
  return all;
}

bool noFrames(benchmark::State& state) {
  if (!frames().empty()) return false;
  state.SkipWithError("no PNG images in BOWG_BENCH_IMAGES");
  return true;
}

void BM_OrbWhole(benchmark::State& state) {
  if (noFrames(state)) return;
  const cv::Ptr<cv::ORB> orb =
      cv::ORB::create(kFeatures, static_cast<float>(kScaleFactor), kLevels, 31, 0, 2,
                      cv::ORB::HARRIS_SCORE, 31, static_cast<int>(state.range(0)));
  std::size_t frame = 0, keypoints = 0, runs = 0;
  for (auto _ : state) {
    std::vector<cv::KeyPoint> kps;
    cv::Mat descriptors;
    orb->detectAndCompute(frames()[frame++ % frames().size()], cv::noArray(), kps, descriptors);
    keypoints += kps.size();
    ++runs;
  }
  state.counters["keypoints"] = static_cast<double>(keypoints) / static_cast<double>(runs);
}
BENCHMARK(BM_OrbWhole)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);

void BM_OrbPyramid(benchmark::State& state) {
  if (noFrames(state)) return;
  std::size_t frame = 0;
  for (auto _ : state) {
    const std::vector<cv::Mat> levels = pyramid(frames()[frame++ % frames().size()]);
    benchmark::DoNotOptimize(levels.back().data);
  }
}
BENCHMARK(BM_OrbPyramid)->Unit(benchmark::kMillisecond);

void BM_OrbFast(benchmark::State& state) {
  if (noFrames(state)) return;
  const std::vector<std::vector<cv::Mat>>& levels = framePyramids();
  const int threshold = static_cast<int>(state.range(0));
  std::size_t frame = 0, corners = 0, runs = 0;
  for (auto _ : state) {
    for (const cv::Mat& level : levels[frame++ % levels.size()]) {
      std::vector<cv::KeyPoint> kps;
      cv::FAST(level, kps, threshold, true);
      corners += kps.size();
    }
    ++runs;
  }
  state.counters["corners"] = static_cast<double>(corners) / static_cast<double>(runs);
}
BENCHMARK(BM_OrbFast)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);

void BM_OrbBlur(benchmark::State& state) {
  if (noFrames(state)) return;
  const std::vector<std::vector<cv::Mat>>& levels = framePyramids();
  // cv::ORB blurs each level in place as part of its bordered pyramid
  // image, which takes GaussianBlur's separable filter, as here.
  const cv::Mat kernel = cv::getGaussianKernel(7, 2, CV_32F);
  std::size_t frame = 0;
  for (auto _ : state) {
    for (const cv::Mat& level : levels[frame++ % levels.size()]) {
      cv::Mat blurred;
      cv::sepFilter2D(level, blurred, CV_8U, kernel, kernel, cv::Point(-1, -1), 0,
                      cv::BORDER_REFLECT_101);
      benchmark::DoNotOptimize(blurred.data);
    }
  }
}
BENCHMARK(BM_OrbBlur)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
