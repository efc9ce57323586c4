// Deterministic pseudo-random numbers for the pipe renderer.
//
// The generated sequence must be identical for a seed on every platform and
// standard library (it is the project's reference data set), so we do not use
// std::*_distribution, whose output is implementation-defined. SplitMix64
// (Steele, Lea, Flood 2014) drives everything; hashing (seed, a, b) lets
// textures and marks be functions of a place rather than of drawing order.
#pragma once

#include <cmath>
#include <cstdint>

namespace bowg {
namespace pipe_sim {

/// One SplitMix64 step: a bijective 64-bit mix with good avalanche.
inline std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

/// A value that depends only on its arguments (order matters).
inline std::uint64_t hashCombine(std::uint64_t seed, std::uint64_t a, std::uint64_t b = 0) {
  return splitMix64(splitMix64(splitMix64(seed) ^ a) ^ (b * 0x9E3779B97F4A7C15ULL));
}

/// Maps 64 random bits to [0, 1) using the top 53 bits.
inline double toUnit(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * (1.0 / 9007199254740992.0);
}

/// Smooth 1-D noise: uniform values in [-1, 1] at knots `spacing` apart,
/// cosine-interpolated; a function of x only (and the stream id), so that a
/// pose or speed is a function of the place or time, not of drawing order.
inline double smoothNoise(std::uint64_t seed, std::uint64_t stream, double x, double spacing) {
  const double k = std::floor(x / spacing), f = x / spacing - k;
  const auto knot = [&](double i) {
    return 2 * toUnit(hashCombine(seed, stream, static_cast<std::uint64_t>(static_cast<long long>(i)))) - 1;
  };
  const double w = 0.5 - 0.5 * std::cos(M_PI * f);
  return knot(k) * (1 - w) + knot(k + 1) * w;
}

class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(splitMix64(seed)) {}

  std::uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1).
  double uniform() { return toUnit(next()); }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Uniform integer in [0, n), n > 0.
  int index(int n) { return static_cast<int>(uniform() * n); }
  /// Standard normal (Box-Muller; the second value is discarded for
  /// simplicity, determinism matters more than speed here).
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]: log is finite
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

 private:
  std::uint64_t state_;
};

}  // namespace pipe_sim
}  // namespace bowg
