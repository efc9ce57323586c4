#include "bowg_pipe_sim/wall_texture.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace bowg {
namespace pipe_sim {
namespace {

TEST(WallTextureTest, GrainJointsAndWeldsRepeatEverywhere) {
  // Without unique marks every joint section of every pipe is the same: the
  // aliasing a naive matcher falls for.
  const PipeNetwork n = PipeNetwork::figureEight();
  WallTextureOptions o;
  o.marks_per_metre = 0;
  const WallTexture tex(n, o);
  for (double s : {0.013, 0.2, 0.377}) {
    for (double theta : {0.1, 1.7, 4.0}) {
      const float a = tex.albedo(0, s, theta);
      EXPECT_FLOAT_EQ(a, tex.albedo(0, s + 0.5, theta));
      EXPECT_FLOAT_EQ(a, tex.albedo(0, s + 1.5, theta));
      EXPECT_FLOAT_EQ(a, tex.albedo(2, s + 1.0, theta));
    }
  }
  // The joint is a dark groove at the section start, a bright bead next to it.
  // Averages around the circumference: groove 0.12, bead 0.66 (the ripple and
  // the noise average out), the bare grain 0.48.
  double groove = 0, bead = 0;
  for (int i = 0; i < 64; ++i) {
    groove += tex.albedo(1, 0.5 + 0.003, i * 2 * M_PI / 64) / 64;
    bead += tex.albedo(1, 0.5 + 0.0185, i * 2 * M_PI / 64) / 64;
  }
  EXPECT_LT(groove, 0.2);
  EXPECT_GT(bead, 0.55);
  EXPECT_TRUE(tex.marks().empty());
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
}

}  // namespace
}  // namespace pipe_sim
}  // namespace bowg
