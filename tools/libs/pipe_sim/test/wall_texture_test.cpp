#include "bowg_pipe_sim/wall_texture.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace bowg {
namespace pipe_sim {
namespace {

/// Pearson correlation of the bare grain of two 0.5 m sections (texture rows
/// [start, start + 500) of the given edges), leaving out the joint (rows
/// 0-33 of a section) and the seam (columns 128 +- 5), which every section
/// shares by construction.
double grainCorrelation(const WallTexture& tex, int edge_a, double s_a, int edge_b, double s_b) {
  const double margin = tex.options().margin_m, texel = tex.options().texel_m;
  const int ra = static_cast<int>(std::lround((s_a + margin) / texel));
  const int rb = static_cast<int>(std::lround((s_b + margin) / texel));
  const cv::Mat& ta = tex.texture(edge_a, 0);
  const cv::Mat& tb = tex.texture(edge_b, 0);
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, n = 0;
  for (int r = 40; r < 500; ++r) {
    for (int c = 0; c < ta.cols; ++c) {
      if (std::abs(c - ta.cols / 4) <= 6) continue;
      const double x = ta.at<uchar>(ra + r, c), y = tb.at<uchar>(rb + r, c);
      sa += x, sb += y, saa += x * x, sbb += y * y, sab += x * y, n += 1;
    }
  }
  const double cov = sab / n - sa / n * sb / n;
  return cov / std::sqrt((saa / n - sa / n * sa / n) * (sbb / n - sb / n * sb / n));
}

TEST(WallTextureTest, FullGrainRepeatMakesEverySectionIdentical) {
  // grain_repeat = 1 and no marks: every joint section of every pipe is the
  // same to the texel, the aliasing a naive matcher falls for.
  const PipeNetwork n = PipeNetwork::figureEight();
  WallTextureOptions o;
  o.marks_per_metre = 0;
  o.grain_repeat = 1;
  const WallTexture tex(n, o);
  for (double s : {0.013, 0.2, 0.377}) {
    for (double theta : {0.1, 1.7, 4.0}) {
      const float a = tex.albedo(0, s, theta);
      EXPECT_FLOAT_EQ(a, tex.albedo(0, s + 0.5, theta));
      EXPECT_FLOAT_EQ(a, tex.albedo(0, s + 1.5, theta));
      EXPECT_FLOAT_EQ(a, tex.albedo(2, s + 1.0, theta));
    }
  }
  EXPECT_GT(grainCorrelation(tex, 0, 0.0, 2, 1.0), 0.999);
  EXPECT_TRUE(tex.marks().empty());
}

TEST(WallTextureTest, DefaultGrainRepeatsOnlyPartly) {
  // The default mix (grain_repeat 0.5): joints and seam are identical in every
  // section, the grain is not. Two independent noise fields with weights
  // sqrt(g) and sqrt(1 - g) correlate with another section's by g = 0.5; the
  // pits and scratches are also half shared, half own, but the own ones cover
  // some of the shared ones, so the measured value sits somewhat below 0.5.
  const PipeNetwork n = PipeNetwork::figureEight();
  WallTextureOptions o;
  o.marks_per_metre = 0;
  ASSERT_DOUBLE_EQ(o.grain_repeat, 0.5);
  const WallTexture tex(n, o);
  const struct { int edge_a; double s_a; int edge_b; double s_b; } pairs[] = {
      {0, 0.0, 0, 0.5}, {0, 0.5, 0, 1.5}, {0, 1.0, 2, 1.0}, {1, 0.0, 3, 0.5}};
  for (const auto& p : pairs) {
    const double rho = grainCorrelation(tex, p.edge_a, p.s_a, p.edge_b, p.s_b);
    EXPECT_GT(rho, 0.3) << "edges " << p.edge_a << "/" << p.edge_b;
    EXPECT_LT(rho, 0.6) << "edges " << p.edge_a << "/" << p.edge_b;
  }
  // Not a copy: the bare grain differs at most points.
  int differ = 0;
  for (int i = 0; i < 100; ++i) {
    const double s = 0.05 + 0.004 * i, theta = 0.37 + 0.05 * i;
    if (std::abs(tex.albedo(0, s, theta) - tex.albedo(0, s + 0.5, theta)) > 0.01) ++differ;
  }
  EXPECT_GT(differ, 50);
  // Statistically the same: mean and spread of the grain of two sections
  // within 0.03 (albedo units; the bare grain's spread is about 0.15).
  for (int s_b : {1, 3}) {
    double ma = 0, mb = 0, va = 0, vb = 0;
    const int count = 4000;
    for (int i = 0; i < count; ++i) {
      const double s = 0.04 + 0.45 * (i % 200) / 200.0, theta = 2 * M_PI * (i / 200) / 20.0 + 0.01;
      const double a = tex.albedo(0, s, theta), b = tex.albedo(0, s + 0.5 * s_b, theta);
      ma += a / count, mb += b / count, va += a * a / count, vb += b * b / count;
    }
    EXPECT_NEAR(ma, mb, 0.03);
    EXPECT_NEAR(std::sqrt(va - ma * ma), std::sqrt(vb - mb * mb), 0.03);
  }
  // The joint is shared: a dark groove at the section start, a bright bead
  // next to it, identical in every section. Averages around the
  // circumference: groove 0.12, bead 0.66 (ripple and noise average out).
  double groove = 0, bead = 0;
  for (int i = 0; i < 64; ++i) {
    const double theta = i * 2 * M_PI / 64;
    groove += tex.albedo(1, 0.5 + 0.003, theta) / 64;
    bead += tex.albedo(1, 0.5 + 0.0185, theta) / 64;
    EXPECT_FLOAT_EQ(tex.albedo(1, 0.5 + 0.003, theta), tex.albedo(3, 1.0 + 0.003, theta));
    EXPECT_FLOAT_EQ(tex.albedo(1, 0.5 + 0.0185, theta), tex.albedo(1, 1.5 + 0.0185, theta));
  }
  EXPECT_LT(groove, 0.2);
  EXPECT_GT(bead, 0.55);
  EXPECT_TRUE(tex.marks().empty());
}

TEST(WallTextureTest, NoGrainRepeatLeavesOnlyJointsAndSeamShared) {
  const PipeNetwork n = PipeNetwork::figureEight();
  WallTextureOptions o;
  o.marks_per_metre = 0;
  o.grain_repeat = 0;
  const WallTexture tex(n, o);
  // Independent grains: correlation ~0 (460 x 500 texels, but the noise has
  // wavelengths up to 128 texels, so allow +-0.15).
  EXPECT_LT(std::abs(grainCorrelation(tex, 0, 0.0, 0, 0.5)), 0.15);
  EXPECT_LT(std::abs(grainCorrelation(tex, 0, 1.0, 2, 1.0)), 0.15);
}

TEST(WallTextureTest, UniqueMarksAreFixedToPlacesAndSeeded) {
  const PipeNetwork n = PipeNetwork::figureEight();
  WallTextureOptions o;
  o.marks_per_metre = 2.0;
  const WallTexture a(n, o), b(n, o);
  ASSERT_EQ(a.marks().size(), b.marks().size());
  double total_length = 0;
  for (std::size_t e = 0; e < n.edges.size(); ++e) total_length += n.edgeLength(static_cast<int>(e));
  // floor(2 * L + u) per edge: within one mark per edge of 2 per metre.
  EXPECT_NEAR(static_cast<double>(a.marks().size()), 2.0 * total_length,
              static_cast<double>(n.edges.size()));
  for (std::size_t i = 0; i < a.marks().size(); ++i) {
    EXPECT_EQ(a.marks()[i].s, b.marks()[i].s);
    EXPECT_EQ(a.marks()[i].theta, b.marks()[i].theta);
  }
  for (std::size_t e = 0; e < n.edges.size(); ++e) {
    EXPECT_EQ(cv::norm(a.texture(static_cast<int>(e), 0), b.texture(static_cast<int>(e), 0), cv::NORM_INF), 0);
  }
  // A mark changes the wall where it sits, relative to the bare grain.
  WallTextureOptions bare = o;
  bare.marks_per_metre = 0;
  const WallTexture plain(n, bare);
  for (const WallMark& m : a.marks()) {
    if (m.type == WallMark::Type::kCrack) continue;  // thin: may miss the centre
    EXPECT_GT(std::abs(a.albedo(m.edge, m.s, m.theta) - plain.albedo(m.edge, m.s, m.theta)), 0.02)
        << "mark on edge " << m.edge << " at s = " << m.s;
  }
  // Another seed, other marks.
  o.seed = 2;
  const WallTexture c(n, o);
  EXPECT_NE(c.marks().front().s, a.marks().front().s);
}

TEST(WallTextureTest, ThetaWrapsAround) {
  const PipeNetwork n = PipeNetwork::figureEight();
  const WallTexture tex(n, WallTextureOptions());
  EXPECT_NEAR(tex.albedo(0, 0.3, 0.2), tex.albedo(0, 0.3, 0.2 + 2 * M_PI), 1e-5);
}

TEST(WallTextureTest, RejectsBadOptions) {
  WallTextureOptions o;
  o.marks_per_metre = -1;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o = WallTextureOptions();
  o.texel_m = 0;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o = WallTextureOptions();
  o.circumference_texels = 4;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o = WallTextureOptions();
  o.grain_repeat = 1.5;
  EXPECT_THROW(o.validate(), std::invalid_argument);
  o.grain_repeat = -0.1;
  EXPECT_THROW(o.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace pipe_sim
}  // namespace bowg
