// Cost of the word groups of one image (buildWordGroups, paper Sec. III-A):
// every keypoint's neighbours within its own radius (radius_scale * size).
// The keypoints are laid out as the pipe preset's multi-scale ORB gives them
// on a 640x480 frame: 500 over 8 levels of scale 1.2 (ORB's per-level share,
// sizes 31 * 1.2^level), half of them in six textured patches (a pipe
// frame's joints and stains), half spread over the image. Radii of 31-111 px
// make a point's disc hold tens of others, so this is where the stage's time
// goes.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "bowg/scoring/word_groups.h"

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

void BM_BuildWordGroups(benchmark::State& state) {
  const Image image = orbLikeImage(static_cast<int>(state.range(0)), 7);
  const WordGroupOptions options;
  std::size_t groups = 0;
  for (auto _ : state) {
    const GroupVector g = buildWordGroups(image.keypoints, image.words, options);
    groups = g.size();
    benchmark::DoNotOptimize(g.data());
  }
  state.counters["groups"] = static_cast<double>(groups);
}
BENCHMARK(BM_BuildWordGroups)->Arg(500)->Arg(1000)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace bowg

BENCHMARK_MAIN();
