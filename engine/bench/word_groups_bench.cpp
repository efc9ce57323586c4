// Cost of the word groups of one image (buildWordGroups, paper Sec. III-A):
// every keypoint's neighbours within its own radius (radius_scale * size).
//   BM_BuildWordGroupsSewer: the pipe preset's features (multi-scale ORB,
//     FAST threshold 10, 500) of a real sewer frame (../shared/data; skipped
//     with a message where it is absent). Its corners crowd the few textured
//     parts of the pipe wall, so a disc holds a hundred others or more.
//   BM_BuildWordGroups/N: N keypoints laid out as multi-scale ORB gives them
//     on a 640x480 frame: 8 levels of scale 1.2 (ORB's per-level share,
//     sizes 31 * 1.2^level), half of them in six textured patches, half
//     spread over the image.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>
#include <vector>

#include "bowg/features/feature_extractor.h"
#include "bowg/scoring/word_groups.h"
#include "shared_data_dir.h"

namespace bowg {
namespace {

struct Image {
  std::vector<Keypoint> keypoints;
  std::vector<WordId> words;
};

Image orbLikeImage(int features, std::uint64_t seed) {
  const int levels = 8;
  const double scale = 1.2;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(0, 640), uy(0, 480);
  std::normal_distribution<double> blob(0, 40);
  std::uniform_int_distribution<WordId> word(0, 9999);
  double centres[6][2];
  for (auto& c : centres) {
    c[0] = ux(rng);
    c[1] = uy(rng);
  }
  Image image;
  // ORB's share of level l: proportional to scale^-l.
  const double first = features * (1 - 1 / scale) / (1 - std::pow(1 / scale, levels));
  for (int l = 0; l < levels; ++l) {
    const int count = l + 1 < levels ? static_cast<int>(std::lround(first * std::pow(scale, -l)))
                                     : features - static_cast<int>(image.keypoints.size());
    for (int i = 0; i < count; ++i) {
      Keypoint k;
      if (i % 2 == 0) {
        const double* c = centres[static_cast<std::size_t>(i / 2) % 6];
        k.x = static_cast<float>(std::min(639.0, std::max(0.0, c[0] + blob(rng))));
        k.y = static_cast<float>(std::min(479.0, std::max(0.0, c[1] + blob(rng))));
      } else {
        k.x = static_cast<float>(ux(rng));
        k.y = static_cast<float>(uy(rng));
      }
      k.size = static_cast<float>(31 * std::pow(scale, l));
      k.octave = l;
      image.keypoints.push_back(k);
      image.words.push_back(word(rng));
    }
  }
  return image;
}

void run(benchmark::State& state, const Image& image) {
  const WordGroupOptions options;
  std::size_t groups = 0;
  for (auto _ : state) {
    const GroupVector g = buildWordGroups(image.keypoints, image.words, options);
    groups = g.size();
    benchmark::DoNotOptimize(g.data());
  }
  state.counters["groups"] = static_cast<double>(groups);
}

void BM_BuildWordGroups(benchmark::State& state) {
  run(state, orbLikeImage(static_cast<int>(state.range(0)), 7));
}
BENCHMARK(BM_BuildWordGroups)->Arg(500)->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_BuildWordGroupsSewer(benchmark::State& state) {
  const std::string path = bench::sharedDataDir() + "/sewer_cctv/left/1_16_left_108100.png";
  const cv::Mat grey = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (grey.empty()) {
    state.SkipWithError(("no sewer frame at " + path + " (set BOWG_SHARED_DATA_DIR)").c_str());
    return;
  }
  FeatureOptions options;  // config/pipe.yaml's features
  options.detector = FeatureOptions::Detector::kOrb;
  options.orb_fast_threshold = 10;
  options.compute_orientation = true;
  const ImageFeatures f = FeatureExtractor(options).extract(grey);
  Image image;
  image.keypoints = f.keypoints;
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<WordId> word(0, 9999);
  for (std::size_t i = 0; i < f.keypoints.size(); ++i) image.words.push_back(word(rng));
  run(state, image);
  state.counters["features"] = static_cast<double>(f.keypoints.size());
}
BENCHMARK(BM_BuildWordGroupsSewer)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace bowg

BENCHMARK_MAIN();
