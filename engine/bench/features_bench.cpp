// Feature extraction cost per 640x480 frame (paper Sec. III-A; the paper's
// per-image times, Sec. IV "Execution Time": 16 ms on average over 17,565
// images on an i9).
// The image is synthetic texture drawn once; each run reports the features
// found as the counter "features".
#include <benchmark/benchmark.h>

#include <fstream>
#include <string>

#include "bowg/features/feature_extractor.h"
#include "feature_test_images.h"
#include "shared_data_dir.h"

namespace {

const cv::Mat& frame() {
  static const cv::Mat img = bowg::test::texturedImage(640, 480, 400, 42);
  return img;
}

void run(benchmark::State& state, const bowg::FeatureOptions& options) {
  const bowg::FeatureExtractor fx(options);
  std::size_t n = 0;
  for (auto _ : state) {
    const bowg::ImageFeatures f = fx.extract(frame());
    n = f.size();
    benchmark::DoNotOptimize(f.descriptors.data());
  }
  state.counters["features"] = static_cast<double>(n);
}

void BM_GfttOrientedOrb(benchmark::State& state) {
  bowg::FeatureOptions o;
  run(state, o);
}

void BM_GfttUprightOrb(benchmark::State& state) {
  bowg::FeatureOptions o;
  o.compute_orientation = false;
  run(state, o);
}

void BM_OrbMultiScaleOriented(benchmark::State& state) {
  bowg::FeatureOptions o;
  o.detector = bowg::FeatureOptions::Detector::kOrb;
  run(state, o);
}

void BM_OrbMultiScaleUpright(benchmark::State& state) {
  bowg::FeatureOptions o;
  o.detector = bowg::FeatureOptions::Detector::kOrb;
  o.compute_orientation = false;
  run(state, o);
}

// config/pipe.yaml's features: multi-scale ORB-500 at FAST threshold 10.
void BM_OrbPipePreset(benchmark::State& state) {
  bowg::FeatureOptions o;
  o.detector = bowg::FeatureOptions::Detector::kOrb;
  o.orb_fast_threshold = 10;
  run(state, o);
}

// config/pipe_gftt.yaml's corners: 1,000 at least 7 px apart, one level.
void BM_GfttPipePreset(benchmark::State& state) {
  bowg::FeatureOptions o;
  o.gftt_max_corners = 1000;
  o.gftt_min_distance = 7;
  run(state, o);
}

// GFTT corners on pyramid levels (gftt_levels): 2,000 at 7 px on 4 levels of
// the 1.2 pyramid, 2.5x the pixels of one level.
void BM_GfttFourLevels(benchmark::State& state) {
  bowg::FeatureOptions o;
  o.gftt_max_corners = 2000;
  o.gftt_min_distance = 7;
  o.gftt_levels = 4;
  run(state, o);
}

void BM_GfttVinsBrief(benchmark::State& state) {
  const std::string pattern = bowg::bench::sharedDataDir() + "/vocabularies/brief_pattern.yml";
  if (!std::ifstream(pattern).good()) {
    state.SkipWithError(("shared BRIEF pattern absent: " + pattern).c_str());
    return;
  }
  bowg::FeatureOptions o;
  o.descriptor = bowg::FeatureOptions::DescriptorType::kBrief;
  o.compute_orientation = false;
  o.brief_pattern_path = pattern;
  run(state, o);
}

}  // namespace

BENCHMARK(BM_GfttOrientedOrb)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GfttUprightOrb)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OrbMultiScaleOriented)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OrbMultiScaleUpright)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OrbPipePreset)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GfttPipePreset)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GfttFourLevels)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GfttVinsBrief)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
