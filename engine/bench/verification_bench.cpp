// Cost of the geometric verification's RANSAC on one candidate
// (verifyCorrespondences: the fundamental matrix on correspondences already
// found). First argument: OpenCV's findFundamentalMat (0) or the native
// 7-point RANSAC (1, GeometricVerificationOptions::native_ransac); second:
// OpenCV's 1,000 samples (0) or the samples bounded by the acceptance (1,
// ransac_bound_confidence 0.9999, the pipe preset's). Two candidates as the
// pipe's re-ranking sees them, 640x480, min_inliers 30:
//   BM_VerifyLookAlike: 48 correspondences, 22 of one rigid scene and 26
//     scattered (a look-alike: ~18 inliers, rejected). The bound is 243
//     samples; unbounded, RANSAC draws all 1,000 (its adaptive stop at
//     18 / 48 would be ~3,500).
//   BM_VerifyLoop: 64 correspondences, 44 consistent (accepted): the
//     adaptive stop comes first and the bound changes nothing.
// Counters: inliers found, whether the candidate was accepted, and the
// sample limit. BM_SevenPointFundamental: the 7-point solver alone.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "bowg/detection/fundamental_matrix.h"
#include "bowg/detection/geometric_verification.h"
#include "core/cpu_features.h"
#include "detection/epipolar_inliers.h"

namespace bowg {
namespace {

struct Candidate {
  std::vector<ImagePoint> query, match;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
};

// `consistent` points of a scene 4-9 m ahead seen from two cameras 0.4 m
// apart (a yaw of ~3 degrees between them, 0.5 px noise), then `scattered`
// pairs whose match positions are random: what a look-alike's
// correspondences look like to RANSAC.
Candidate makeCandidate(int consistent, int scattered, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(-3, 3), uz(4, 9), px(0, 640), py(0, 480);
  std::normal_distribution<double> noise(0, 0.5);
  const double f = 500, cx = 320, cy = 240, yaw = 0.05, tx = 0.4;
  Candidate c;
  while (static_cast<int>(c.query.size()) < consistent) {
    const double X = ux(rng), Y = ux(rng) * 0.7, Z = uz(rng);
    const double Xm = std::cos(yaw) * (X - tx) - std::sin(yaw) * Z;
    const double Zm = std::sin(yaw) * (X - tx) + std::cos(yaw) * Z;
    ImagePoint q, m;
    q.x = static_cast<float>(f * X / Z + cx + noise(rng));
    q.y = static_cast<float>(f * Y / Z + cy + noise(rng));
    m.x = static_cast<float>(f * Xm / Zm + cx + noise(rng));
    m.y = static_cast<float>(f * Y / Zm + cy + noise(rng));
    if (q.x < 0 || q.x >= 640 || q.y < 0 || q.y >= 480) continue;
    if (m.x < 0 || m.x >= 640 || m.y < 0 || m.y >= 480) continue;
    c.query.push_back(q);
    c.match.push_back(m);
  }
  for (int i = 0; i < scattered; ++i) {
    ImagePoint q, m;
    q.x = static_cast<float>(px(rng));
    q.y = static_cast<float>(py(rng));
    m.x = static_cast<float>(px(rng));
    m.y = static_cast<float>(py(rng));
    c.query.push_back(q);
    c.match.push_back(m);
  }
  // Interleave consistent and scattered pairs, as a real search returns them.
  std::vector<std::uint32_t> order(c.query.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  for (std::uint32_t i = 0; i < order.size(); ++i) c.pairs.emplace_back(order[i], order[i]);
  return c;
}

void runVerification(benchmark::State& state, const Candidate& c) {
  GeometricVerificationOptions o;
  o.min_inliers = 30;
  o.native_ransac = state.range(0) != 0;
  o.ransac_bound_confidence = state.range(1) ? 0.9999 : 0.0;
  const VerificationView q{&c.query, nullptr, nullptr}, m{&c.match, nullptr, nullptr};
  GeometricVerificationResult r;
  for (auto _ : state) {
    r = verifyCorrespondences(c.pairs, q, m, CameraIntrinsics(), o);
    benchmark::DoNotOptimize(r.inliers);
  }
  state.counters["inliers"] = r.inliers;
  state.counters["accepted"] = r.status == LoopStatus::kLoopDetected ? 1 : 0;
  state.counters["sample_bound"] = o.ransac_bound_confidence > 0
                                       ? ransacSampleBound(static_cast<int>(c.pairs.size()),
                                                           o.min_inliers, o.ransac_bound_confidence)
                                       : kOpenCvRansacSamples;
}

void BM_VerifyLookAlike(benchmark::State& state) {
  static const Candidate c = makeCandidate(22, 26, 5);
  runVerification(state, c);
}
BENCHMARK(BM_VerifyLookAlike)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);

void BM_VerifyLoop(benchmark::State& state) {
  static const Candidate c = makeCandidate(44, 20, 6);
  runVerification(state, c);
}
BENCHMARK(BM_VerifyLoop)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMillisecond);

// The 7-point solver alone (RANSAC's cost per sample besides the inlier
// count) on 1,024 samples of random pairs in conditioned coordinates
// (|x| <= 1.5, as fundamentalRansac hands them over), taken in turn.
void BM_SevenPointFundamental(benchmark::State& state) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::vector<PointPair> pairs(7 * 1024);
  for (PointPair& p : pairs) p = {u(rng), u(rng), u(rng), u(rng)};
  double solutions[3][9];
  std::size_t i = 0, models = 0;
  for (auto _ : state) {
    const int n = sevenPointFundamental(pairs.data() + 7 * (i++ & 1023), solutions);
    models += static_cast<std::size_t>(n);
    benchmark::DoNotOptimize(solutions[0][0]);
  }
  state.counters["models_per_sample"] = static_cast<double>(models) / static_cast<double>(i);
}
BENCHMARK(BM_SevenPointFundamental);

// RANSAC's inner loop alone (epipolar_inliers.h): the inliers of one model
// among the 48 pairs of the look-alike above, without giving up: the
// portable count (SSE2, two pairs an instruction) and, where the CPU has
// AVX2, four.
void countInliers(benchmark::State& state, epipolar_inliers::CountInliers count) {
  const Candidate c = makeCandidate(22, 26, 11);
  std::vector<double> x1, y1, x2, y2;
  for (const auto& p : c.pairs) {
    x1.push_back(c.query[p.first].x);
    y1.push_back(c.query[p.first].y);
    x2.push_back(c.match[p.second].x);
    y2.push_back(c.match[p.second].y);
  }
  const epipolar_inliers::PairArrays arrays{x1.data(), y1.data(), x2.data(), y2.data()};
  // A pixel-scale model: rows (pure sideways motion) slightly tilted.
  const double f[9] = {0, 1e-6, -2e-4, -1e-6, 0, -1, 2e-4, 1, 0};
  int n = 0;
  for (auto _ : state) {
    n = count(arrays, static_cast<std::uint32_t>(x1.size()), f, 4.0, -1);
    benchmark::DoNotOptimize(n);
  }
  state.counters["inliers"] = n;
}

void BM_CountInliersPortable(benchmark::State& state) {
  countInliers(state, epipolar_inliers::countInliersPortable);
}
BENCHMARK(BM_CountInliersPortable);

void BM_CountInliersAvx2(benchmark::State& state) {
  if (!cpuHasAvx2()) {
    state.SkipWithError("this CPU has no AVX2");
    return;
  }
  countInliers(state, epipolar_inliers::countInliersAvx2);
}
BENCHMARK(BM_CountInliersAvx2);

}  // namespace
}  // namespace bowg

BENCHMARK_MAIN();
