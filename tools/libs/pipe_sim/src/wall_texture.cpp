#include "bowg_pipe_sim/wall_texture.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "bowg_pipe_sim/random.h"

namespace bowg {
namespace pipe_sim {
namespace {

constexpr double kTwoPi = 6.283185307179586;

double smoothstep(double x) {
  x = std::max(0.0, std::min(1.0, x));
  return x * x * (3 - 2 * x);
}

/// Value noise on a lattice of spacing `wavelength` texels, periodic in the
/// column direction with period `cols` (the circumference), so that there is
/// no seam at theta = 0.
double valueNoise(std::uint64_t seed, double row, double col, double wavelength, int cols) {
  const int period = std::max(1, static_cast<int>(std::lround(cols / wavelength)));
  const double x = col / cols * period, y = row / wavelength;
  const double fx = std::floor(x), fy = std::floor(y);
  const long x0 = static_cast<long>(fx), y0 = static_cast<long>(fy);
  auto lattice = [&](long xi, long yi) {
    xi = ((xi % period) + period) % period;
    return toUnit(hashCombine(seed, static_cast<std::uint64_t>(xi), static_cast<std::uint64_t>(yi)));
  };
  const double tx = smoothstep(x - fx), ty = smoothstep(y - fy);
  const double a = lattice(x0, y0), b = lattice(x0 + 1, y0);
  const double c = lattice(x0, y0 + 1), d = lattice(x0 + 1, y0 + 1);
  return (a + (b - a) * tx) * (1 - ty) + (c + (d - c) * tx) * ty - 0.5;
}

/// Blends a patch mask (values in [0, 1], centred on (row, col)) into `tex`:
/// tex = tex * (1 - mask) + mask * value(r, c); columns wrap.
template <typename ValueFn>
void blendPatch(cv::Mat& tex, const cv::Mat& mask, int row, int col, ValueFn value) {
  const int h = mask.rows, w = mask.cols;
  for (int y = 0; y < h; ++y) {
    const int r = row - h / 2 + y;
    if (r < 0 || r >= tex.rows) continue;
    float* out = tex.ptr<float>(r);
    const float* m = mask.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      if (m[x] <= 0.f) continue;
      const int c = ((col - w / 2 + x) % tex.cols + tex.cols) % tex.cols;
      out[c] = out[c] * (1.f - m[x]) + m[x] * value(out[c], y, x);
    }
  }
}

}  // namespace

void WallTextureOptions::validate() const {
  if (!(texel_m > 0)) throw std::invalid_argument("WallTextureOptions.texel_m must be > 0");
  if (circumference_texels < 16) {
    throw std::invalid_argument("WallTextureOptions.circumference_texels must be >= 16");
  }
  if (!(joint_spacing_m >= 20 * texel_m)) {
    throw std::invalid_argument("WallTextureOptions.joint_spacing_m must be >= 20 texels");
  }
  if (!(marks_per_metre >= 0)) {
    throw std::invalid_argument("WallTextureOptions.marks_per_metre must be >= 0");
  }
  if (!(marks_changed >= 0 && marks_changed <= 1)) {
    throw std::invalid_argument("WallTextureOptions.marks_changed must be in [0, 1]");
  }
  if (!(grain_repeat >= 0 && grain_repeat <= 1)) {
    throw std::invalid_argument("WallTextureOptions.grain_repeat must be in [0, 1]");
  }
  if (!(margin_m >= 0)) throw std::invalid_argument("WallTextureOptions.margin_m must be >= 0");
  for (const cv::Mat& image : grain_images) {
    if (image.type() != CV_8UC1 || image.rows < QuiltedGrain::kPatch || image.cols < QuiltedGrain::kPatch) {
      throw std::invalid_argument("WallTextureOptions.grain_images must be grey 8-bit images of at least " +
                                  std::to_string(QuiltedGrain::kPatch) + " x " +
                                  std::to_string(QuiltedGrain::kPatch) + " px");
    }
  }
}

WallTexture::WallTexture(const PipeNetwork& network, const WallTextureOptions& options)
    : options_(options), radius_(network.radius) {
  options_.validate();
  network.validate();
  bakeTile();
  marks_ = placeMarks(network, options_.marks_per_metre, options_.seed);
  if (options_.marks_changed > 0) {
    marks_ = changeMarks(marks_, network, options_.marks_changed, options_.marks_change_seed);
  }

  const int cols = options_.circumference_texels;
  const int tile_rows = tile_.rows;
  levels_.resize(network.edges.size());
  for (std::size_t e = 0; e < network.edges.size(); ++e) {
    const double length = network.edgeLength(static_cast<int>(e));
    const int rows = static_cast<int>(std::ceil((length + 2 * options_.margin_m) / options_.texel_m));
    cv::Mat tex(rows, cols, CV_32F);
    // Sections are anchored at s = 0 of every edge (joints every
    // joint_spacing); each section's grain is the shared tile plus its own.
    long current = std::numeric_limits<long>::min();
    cv::Mat section;
    for (int r = 0; r < rows; ++r) {
      const double s = -options_.margin_m + r * options_.texel_m;
      const long t = static_cast<long>(std::floor(s / options_.texel_m + 0.5));
      const long k = static_cast<long>(std::floor(static_cast<double>(t) / tile_rows));
      if (k != current) {
        section = sectionGrain(static_cast<int>(e), k);
        current = k;
      }
      section.row(static_cast<int>(t - k * tile_rows)).copyTo(tex.row(r));
    }
    // Every mark of this edge, drawn in the order of marks_ (a new mark
    // over an old one).
    for (const WallMark& mark : marks_) {
      if (mark.edge == static_cast<int>(e)) drawMark(tex, mark);
    }
    cv::Mat tex8;
    tex.convertTo(tex8, CV_8U, 255.0);
    levels_[e].push_back(tex8);
    for (int l = 1; l < kLevels; ++l) {
      cv::Mat half;
      cv::resize(levels_[e].back(), half, cv::Size(), 0.5, 0.5, cv::INTER_AREA);
      levels_[e].push_back(half);
    }
  }
}

namespace {

// Cast-iron-like grain: value noise from 128 down to 2 texels.
const double kWavelengths[] = {128, 64, 32, 16, 8, 4, 2};
const double kAmplitudes[] = {0.16, 0.12, 0.10, 0.09, 0.08, 0.06, 0.04};

/// Adds weight * (the grain's multi-octave noise seeded by `seed`) to `tex`.
/// Two independent fields with weights sqrt(g) and sqrt(1 - g) sum to a field
/// with the same variance as one of weight 1: the statistics do not depend
/// on the mix.
void addGrainNoise(cv::Mat& tex, std::uint64_t seed, double weight) {
  if (weight <= 0) return;
  for (int r = 0; r < tex.rows; ++r) {
    float* out = tex.ptr<float>(r);
    for (int c = 0; c < tex.cols; ++c) {
      double v = 0;
      for (int o = 0; o < 7; ++o) {
        v += kAmplitudes[o] * valueNoise(seed + o, r, c, kWavelengths[o], tex.cols);
      }
      out[c] += static_cast<float>(weight * v);
    }
  }
}

}  // namespace

void WallTexture::bakeTile() {
  const int cols = options_.circumference_texels;
  const int rows = static_cast<int>(std::lround(options_.joint_spacing_m / options_.texel_m));
  const std::uint64_t seed = hashCombine(options_.seed, 0x74696c65ULL);
  const double g = options_.grain_repeat;
  if (!options_.grain_images.empty()) {
    quilt_ = std::make_shared<QuiltedGrain>(options_.grain_images);
    // The quilted grain takes the procedural grain's mean and spread (noise,
    // pits and scratches of one whole section), so that the joints, the seam
    // and the marks stand out from it as they do from the procedural one.
    cv::Mat procedural(rows, cols, CV_32F, cv::Scalar(0.48));
    addGrainNoise(procedural, seed, 1.0);
    addGrainFeatures(procedural, seed, 1.0);
    cv::Scalar mean, spread;
    cv::meanStdDev(procedural, mean, spread);
    grain_mean_ = mean[0];
    grain_spread_ = spread[0];
  }
  shared_noise_ = cv::Mat(rows, cols, CV_32F, cv::Scalar(grain_mean_));
  addGrain(shared_noise_, seed, std::sqrt(g));
  tile_ = shared_noise_.clone();
  if (!quilt_) addGrainFeatures(tile_, seed, g);
  addJointAndSeam(tile_);
  cv::min(cv::max(tile_, 0.02), 0.98, tile_);
}

cv::Mat WallTexture::sectionGrain(int edge, long section) const {
  const std::uint64_t shared_seed = hashCombine(options_.seed, 0x74696c65ULL);
  // The section's own grain: a function of (seed, edge, section) only.
  const std::uint64_t own_seed = hashCombine(hashCombine(options_.seed, 0x6772616eULL, edge),
                                             static_cast<std::uint64_t>(section));
  const double g = options_.grain_repeat;
  cv::Mat tex = shared_noise_.clone();
  addGrain(tex, own_seed, std::sqrt(1 - g));
  // Shared features first (their draw sequence is the shared tile's), then
  // this section's own, so that grain_repeat = 1 is exactly the shared tile.
  // A quilted grain brings the pits and scratches of its photographs.
  if (!quilt_) {
    addGrainFeatures(tex, shared_seed, g);
    addGrainFeatures(tex, own_seed, 1 - g);
  }
  addJointAndSeam(tex);
  cv::min(cv::max(tex, 0.02), 0.98, tex);
  return tex;
}

void WallTexture::addGrain(cv::Mat& tex, std::uint64_t seed, double weight) const {
  if (!quilt_) {
    addGrainNoise(tex, seed, weight);
  } else if (weight > 0) {
    tex += quilt_->field(tex.rows, tex.cols, seed) * (weight * grain_spread_);
  }
}

void WallTexture::addGrainFeatures(cv::Mat& tex, std::uint64_t seed, double fraction) const {
  if (fraction <= 0) return;
  const int rows = tex.rows, cols = tex.cols;
  Random rng(seed);
  // Pits (dark) and flecks (bright): the corners GFTT finds everywhere.
  const int pits = static_cast<int>(std::lround(fraction * (rows * cols / 600)));
  for (int i = 0; i < pits; ++i) {
    const bool dark = rng.uniform() < 0.75;
    const double radius = rng.uniform(0.6, dark ? 2.5 : 1.5);
    const int half = static_cast<int>(std::ceil(radius)) + 1;
    cv::Mat mask(2 * half + 1, 2 * half + 1, CV_32F);
    for (int y = 0; y < mask.rows; ++y) {
      for (int x = 0; x < mask.cols; ++x) {
        const double d = std::hypot(x - half, y - half);
        mask.at<float>(y, x) = static_cast<float>(1 - smoothstep((d - radius + 0.7) / 1.4));
      }
    }
    const float value = static_cast<float>(dark ? rng.uniform(0.08, 0.3) : rng.uniform(0.72, 0.9));
    blendPatch(tex, mask, rng.index(rows), rng.index(cols),
               [value](float, int, int) { return value; });
  }
  // Scratches, mostly along the pipe (whatever the pipe carried scoured them).
  const int scratches = static_cast<int>(std::lround(fraction * (rows * cols / 4000)));
  for (int i = 0; i < scratches; ++i) {
    const double length = rng.uniform(6, 30), angle = rng.uniform(-0.35, 0.35);
    const int half = static_cast<int>(length / 2) + 2;
    cv::Mat mask = cv::Mat::zeros(2 * half + 1, 2 * half + 1, CV_32F);
    const cv::Point2d centre(half, half), dir(std::sin(angle), std::cos(angle));
    cv::line(mask, centre - dir * (length / 2), centre + dir * (length / 2), cv::Scalar(0.8), 1,
             cv::LINE_AA);
    const float value = static_cast<float>(rng.uniform() < 0.5 ? rng.uniform(0.15, 0.3) : rng.uniform(0.65, 0.8));
    blendPatch(tex, mask, rng.index(rows), rng.index(cols),
               [value](float, int, int) { return value; });
  }
}

void WallTexture::addJointAndSeam(cv::Mat& tex) const {
  const int rows = tex.rows, cols = tex.cols;
  const std::uint64_t seed = hashCombine(options_.seed, 0x74696c65ULL);
  // Circumferential joint at the section start: a dark groove, then a weld
  // bead with the ripples of the welding pass. Shared by every section.
  for (int r = 0; r < std::min(rows, 34); ++r) {
    float* out = tex.ptr<float>(r);
    for (int c = 0; c < cols; ++c) {
      if (r < 8 || r >= 30) {
        out[c] = 0.12f + 0.05f * static_cast<float>(valueNoise(seed + 11, r, c, 3, cols));
      } else {
        const double ripple = std::sin(kTwoPi * (c / 7.0 + std::abs(r - 18.5) / 12.0));
        out[c] = static_cast<float>(0.66 + 0.12 * ripple + 0.3 * valueNoise(seed + 12, r, c, 4, cols));
      }
    }
  }
  // Longitudinal seam (every pipe is rolled and welded along one line).
  const int seam = cols / 4, seam_half = 4;
  for (int r = 0; r < rows; ++r) {
    float* out = tex.ptr<float>(r);
    for (int dc = -seam_half - 1; dc <= seam_half + 1; ++dc) {
      const int c = seam + dc;
      if (std::abs(dc) > seam_half) {
        out[c] = 0.18f;  // undercut at the seam's edges
      } else {
        const double ripple = std::sin(kTwoPi * (r / 6.0 + std::abs(dc) / 8.0));
        out[c] = static_cast<float>(0.56 + 0.08 * ripple + 0.3 * valueNoise(seed + 13, r, c, 4, cols));
      }
    }
  }
}

void WallTexture::drawMark(cv::Mat& tex, const WallMark& mark) const {
  Random rng(mark.shape_seed);
  const int cols = options_.circumference_texels;
  const double texel_theta_m = kTwoPi * radius_ / cols;  // arc length of one column
  const int row = static_cast<int>(std::lround((mark.s + options_.margin_m) / options_.texel_m));
  const int col = static_cast<int>(std::lround(mark.theta / kTwoPi * cols)) % cols;
  const double size_rows = mark.size_m / options_.texel_m;
  const double size_cols = mark.size_m / texel_theta_m;
  const int half_r = static_cast<int>(size_rows) + 4, half_c = static_cast<int>(size_cols) + 4;
  cv::Mat mask = cv::Mat::zeros(2 * half_r + 1, 2 * half_c + 1, CV_32F);
  const double a1 = rng.uniform(0, kTwoPi), a2 = rng.uniform(0, kTwoPi), a3 = rng.uniform(0, kTwoPi);
  const std::uint64_t nseed = rng.next();

  switch (mark.type) {
    case WallMark::Type::kStain:
    case WallMark::Type::kDeposit: {
      // An irregular blob: radius modulated by a few harmonics of the angle.
      const double radius = 0.5;  // in units of size
      for (int y = 0; y < mask.rows; ++y) {
        for (int x = 0; x < mask.cols; ++x) {
          const double u = (y - half_r) / size_rows, v = (x - half_c) / size_cols;
          const double phi = std::atan2(u, v);
          const double rb = radius * (1 + 0.25 * std::sin(2 * phi + a1) +
                                      0.15 * std::sin(3 * phi + a2) + 0.1 * std::sin(5 * phi + a3));
          const double d = std::hypot(u, v) / rb;
          const double soft = mark.type == WallMark::Type::kStain ? 0.5 : 0.15;
          mask.at<float>(y, x) = static_cast<float>(1 - smoothstep((d - 1 + soft) / soft));
        }
      }
      break;
    }
    case WallMark::Type::kCrack: {
      // A wandering line with one branch, 1-2 texels wide.
      cv::Point2d p(half_c, half_r);
      double heading = rng.uniform(0, kTwoPi);
      const int steps = static_cast<int>(size_rows / 3);
      for (int branch = 0; branch < 2; ++branch) {
        for (int i = 0; i < steps / (branch + 1); ++i) {
          heading += rng.uniform(-0.5, 0.5);
          const cv::Point2d q = p + cv::Point2d(std::cos(heading), std::sin(heading)) * 3.0 *
                                        (size_cols / size_rows > 1 ? 1.0 : 1.0);
          cv::line(mask, p, q, cv::Scalar(1.0), rng.uniform() < 0.6 ? 1 : 2, cv::LINE_AA);
          p = q;
          if (p.x < 2 || p.y < 2 || p.x > mask.cols - 3 || p.y > mask.rows - 3) break;
        }
        p = cv::Point2d(half_c, half_r);
        heading += M_PI * rng.uniform(0.6, 1.4);
      }
      break;
    }
  }
  if (mark.type == WallMark::Type::kStain) {
    const float darkness = static_cast<float>(rng.uniform(0.35, 0.6));
    blendPatch(tex, mask, row, col, [&](float old, int y, int x) {
      return old * (1.f - darkness) +
             0.05f * static_cast<float>(valueNoise(nseed, y, x, 6, 1 << 20));
    });
  } else if (mark.type == WallMark::Type::kDeposit) {
    const bool bright = rng.uniform() < 0.7;
    blendPatch(tex, mask, row, col, [&](float, int y, int x) {
      const double n = valueNoise(nseed, y, x, 3, 1 << 20) + 0.5 * valueNoise(nseed + 1, y, x, 1.5, 1 << 20);
      return static_cast<float>((bright ? 0.8 : 0.2) + 0.35 * n);
    });
  } else {
    blendPatch(tex, mask, row, col, [](float, int, int) { return 0.06f; });
  }
}

float WallTexture::albedo(int edge, double s, double theta, int level) const {
  const cv::Mat& tex = levels_[edge][level];
  const double scale = 1.0 / (1 << level);
  double r = (s + options_.margin_m) / options_.texel_m * scale;
  double c = theta / kTwoPi * tex.cols;
  r = std::max(0.0, std::min(tex.rows - 1.001, r));
  c = c - std::floor(c / tex.cols) * tex.cols;
  const int r0 = static_cast<int>(r), c0 = static_cast<int>(c) % tex.cols;
  const int c1 = (c0 + 1) % tex.cols;
  const double fr = r - r0, fc = c - std::floor(c);
  const uchar* a = tex.ptr<uchar>(r0);
  const uchar* b = tex.ptr<uchar>(r0 + 1);
  const double top = a[c0] + (a[c1] - a[c0]) * fc, bottom = b[c0] + (b[c1] - b[c0]) * fc;
  return static_cast<float>((top + (bottom - top) * fr) / 255.0);
}

}  // namespace pipe_sim
}  // namespace bowg
