#include "bowg/detection/fundamental_ransac.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "detection/epipolar_inliers.h"

namespace bowg {
namespace {

// splitmix64: a small, fast generator whose sequence is fixed by its seed.
struct SampleGenerator {
  std::uint64_t state;
  std::uint32_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return static_cast<std::uint32_t>((z ^ (z >> 31)) >> 32);
  }
  // Uniform in [0, n) by a 32 x 32 -> 64-bit product (bias < n / 2^32).
  std::uint32_t below(std::uint32_t n) {
    return static_cast<std::uint32_t>((static_cast<std::uint64_t>(next()) * n) >> 32);
  }
};

// Hartley's conditioning of one image's points: centred on their centroid,
// scaled to a mean distance of sqrt(2). x_n = s (x - cx).
struct Conditioning {
  double s = 1, cx = 0, cy = 0;
};

Conditioning conditioning(const std::vector<PointPair>& pairs, bool second) {
  Conditioning c;
  const double n = static_cast<double>(pairs.size());
  for (const PointPair& p : pairs) {
    c.cx += second ? p.x2 : p.x1;
    c.cy += second ? p.y2 : p.y1;
  }
  c.cx /= n;
  c.cy /= n;
  double mean = 0;
  for (const PointPair& p : pairs) {
    mean += std::hypot((second ? p.x2 : p.x1) - c.cx, (second ? p.y2 : p.y1) - c.cy);
  }
  mean /= n;
  c.s = mean > 0 ? std::sqrt(2.0) / mean : 1.0;
  return c;
}

// F in pixels from F_n of the conditioned points: T2^T F_n T1 with
// T = [s 0 -s cx; 0 s -s cy; 0 0 1].
void unconditionModel(const double fn[9], const Conditioning& c1, const Conditioning& c2,
                      double f[9]) {
  const double t1[9] = {c1.s, 0, -c1.s * c1.cx, 0, c1.s, -c1.s * c1.cy, 0, 0, 1};
  const double t2[9] = {c2.s, 0, -c2.s * c2.cx, 0, c2.s, -c2.s * c2.cy, 0, 0, 1};
  double m[9];  // F_n T1
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      m[3 * r + k] = fn[3 * r] * t1[k] + fn[3 * r + 1] * t1[3 + k] + fn[3 * r + 2] * t1[6 + k];
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      f[3 * r + k] = t2[r] * m[k] + t2[3 + r] * m[3 + k] + t2[6 + r] * m[6 + k];
}

// epipolarErrorSquared(f, p) <= t2 without its division.
inline bool isInlier(const double f[9], const PointPair& p, double t2) {
  const EpipolarResidual e = epipolarResidual(f, p);
  return e.normal > 0.0 && e.residual * e.residual <= t2 * e.normal;
}

// The pairs' coordinates one array each, for the vector inlier count
// (epipolar_inliers.h): counting inliers is most of RANSAC's time.
class PairColumns {
 public:
  explicit PairColumns(const std::vector<PointPair>& pairs)
      : x1_(pairs.size()),
        y1_(pairs.size()),
        x2_(pairs.size()),
        y2_(pairs.size()),
        count_(epipolar_inliers::bestCountInliers()) {
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      x1_[i] = pairs[i].x1;
      y1_[i] = pairs[i].y1;
      x2_[i] = pairs[i].x2;
      y2_[i] = pairs[i].y2;
    }
  }

  /// How many pairs isInlier(f, pair, t2) accepts, or at most `best` once
  /// that is all that can be (epipolar_inliers.h).
  int inliers(const double f[9], double t2, int best) const {
    const epipolar_inliers::PairArrays arrays{x1_.data(), y1_.data(), x2_.data(), y2_.data()};
    return count_(arrays, static_cast<std::uint32_t>(x1_.size()), f, t2, best);
  }

 private:
  std::vector<double> x1_, y1_, x2_, y2_;
  epipolar_inliers::CountInliers count_;
};

}  // namespace

int adaptiveSampleCount(double inlier_ratio, double confidence, int limit) {
  const double w = std::max(0.0, std::min(1.0, inlier_ratio));
  // The 7-point solver's samples are all inliers with probability w^7; N of
  // them miss with (1 - w^7)^N <= 1 - confidence.
  const double all_inliers = std::pow(w, 7);
  if (all_inliers >= 1.0) return 1;
  const double num = std::log(std::max(1.0 - confidence, std::numeric_limits<double>::min()));
  const double denom = std::log(1.0 - all_inliers);
  if (!(denom < 0.0) || -num >= limit * -denom) return limit;
  return std::max(1, static_cast<int>(std::lround(num / denom)));
}

FundamentalRansacResult fundamentalRansac(const std::vector<PointPair>& pairs,
                                          const FundamentalRansacOptions& options) {
  FundamentalRansacResult result;
  const std::uint32_t n = static_cast<std::uint32_t>(pairs.size());
  if (n < 7 || options.max_samples < 1) return result;
  const Conditioning c1 = conditioning(pairs, false), c2 = conditioning(pairs, true);
  std::vector<PointPair> conditioned(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const PointPair& p = pairs[i];
    conditioned[i] = {c1.s * (p.x1 - c1.cx), c1.s * (p.y1 - c1.cy), c2.s * (p.x2 - c2.cx),
                      c2.s * (p.y2 - c2.cy)};
  }
  const double t2 = options.threshold_px * options.threshold_px;
  const PairColumns columns(pairs);
  SampleGenerator rng{options.seed};
  int best = 6;  // a model needs 7 inliers: at least its own sample
  int limit = options.max_samples;
  std::uint32_t idx[7];
  PointPair sample[7];
  double solutions[3][9], f[9], fn[9];
  std::vector<PointPair> support;
  for (int s = 0; s < limit; ++s) {
    // 7 distinct pairs.
    for (int k = 0; k < 7; ++k) {
      std::uint32_t i;
      do {
        i = rng.below(n);
      } while (std::find(idx, idx + k, i) != idx + k);
      idx[k] = i;
      sample[k] = conditioned[i];
    }
    ++result.samples;
    const int models = sevenPointFundamental(sample, solutions);
    const int before = best;
    for (int m = 0; m < models; ++m) {
      unconditionModel(solutions[m], c1, c2, f);
      const int count = columns.inliers(f, t2, best);
      if (count > best) {
        best = count;
        std::copy(f, f + 9, result.f);
      }
    }
    if (best == before) continue;
    // Local optimisation (LO-RANSAC, Chum et al. 2003): a new best model is
    // refitted by least squares to its inliers while that gains inliers. A
    // 7-point model fits its sample's noise; the refit fits the scene, so
    // a loop keeps the inliers a longer run would find.
    for (int round = 0; round < options.refits; ++round) {
      support.clear();
      for (std::uint32_t i = 0; i < n; ++i) {
        if (isInlier(result.f, pairs[i], t2)) support.push_back(conditioned[i]);
      }
      if (!eightPointFundamental(support.data(), static_cast<int>(support.size()), fn)) break;
      unconditionModel(fn, c1, c2, f);
      const int count = columns.inliers(f, t2, best);
      if (count <= best) break;
      best = count;
      std::copy(f, f + 9, result.f);
    }
    limit = std::min(limit, adaptiveSampleCount(static_cast<double>(best) / n, options.confidence,
                                                options.max_samples));
  }
  if (best < 7) return result;
  result.found = true;
  result.inliers = best;
  result.inlier_mask.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) result.inlier_mask[i] = isInlier(result.f, pairs[i], t2);
  return result;
}

}  // namespace bowg
