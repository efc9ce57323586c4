// The metric translation's steps alone, against values worked out by hand:
// the loop inliers triangulated from a neighbour at a known baseline, and the
// covariance's sum of bootstrap spread, fit noise and odometer scale error.
#include "detection/metric_translation_steps.h"

#include <gtest/gtest.h>

namespace bowg {
namespace metric_steps {
namespace {

// f = 500 px, principal point (320, 240).
cv::Matx33d camera() { return cv::Matx33d(500, 0, 320, 0, 500, 240, 0, 0, 1); }

Correspondence pair(std::uint32_t m_feature, float mx, float my, float nx, float ny) {
  Correspondence c;
  c.query_index = m_feature;  // in a track, M is the "query" side
  c.match_index = 7;
  c.query_x = mx;
  c.query_y = my;
  c.match_x = nx;
  c.match_y = ny;
  return c;
}

Correspondence loopInlier(std::uint32_t m_feature, float qx, float qy) {
  Correspondence c;
  c.match_index = m_feature;  // in the loop, M is the "match" side
  c.query_x = qx;
  c.query_y = qy;
  return c;
}

// N 0.1 m along M's x axis, no rotation: X_M = X_N + u b with u = (1, 0, 0).
NeighbourTrack trackAlongX(const cv::Matx33d& K, std::vector<Correspondence> pairs) {
  NeighbourTrack t;
  const double r[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, u[3] = {1, 0, 0};
  t.pose = metric_geometry::neighbourPose(r, u, 0.1, K);
  t.pairs = std::move(pairs);
  t.pair_of_feature.assign(10, -1);
  for (std::size_t i = 0; i < t.pairs.size(); ++i) {
    t.pair_of_feature[t.pairs[i].query_index] = static_cast<int>(i);
  }
  return t;
}

TEST(MetricTranslationSteps, TriangulatesTheLoopInliersANeighbourSees) {
  const cv::Matx33d K = camera();
  // X_M = (0.5, 0.2, 4): in M at (320 + 500 * 0.5 / 4, 240 + 500 * 0.2 / 4)
  // = (382.5, 265); X_N = (0.4, 0.2, 4) at (370, 265). Parallax 0.1 / 4 rad.
  std::vector<NeighbourTrack> tracks;
  tracks.push_back(trackAlongX(K, {pair(3, 382.5f, 265, 370, 265)}));
  // A second neighbour that sees feature 5 only: X_M = (0, 0, 2) at (320,
  // 240) in M, X_N = (-0.1, 0, 2) at (295, 240).
  tracks.push_back(trackAlongX(K, {pair(5, 320, 240, 295, 240)}));
  const std::vector<Correspondence> loop = {loopInlier(3, 100, 50), loopInlier(4, 1, 2),
                                            loopInlier(5, 200, 60)};
  const TriangulatedLoop out = triangulateLoopInliers(loop, tracks, K, 1.0);
  ASSERT_EQ(out.points.size(), 2u);  // feature 4: no neighbour sees it
  EXPECT_NEAR(out.points[0].x, 0.5, 1e-9);
  EXPECT_NEAR(out.points[0].y, 0.2, 1e-9);
  EXPECT_NEAR(out.points[0].z, 4.0, 1e-9);
  EXPECT_NEAR(out.points[1].z, 2.0, 1e-9);
  EXPECT_EQ(out.sources[0].neighbour, 0u);
  EXPECT_EQ(out.sources[1].neighbour, 1u);
  EXPECT_EQ(out.sources[1].pair, 0u);
  EXPECT_EQ(out.sources[0].pixel, cv::Point2d(100, 50));  // the query's pixel
}

TEST(MetricTranslationSteps, CovarianceSumsSpreadFitNoiseAndOdometerScale) {
  // Samples (1, 2, 0) and (3, 2, 2): mean (2, 2, 1), unbiased spread
  // S = [[2, 0, 2], [0, 0, 0], [2, 0, 2]].
  const std::vector<cv::Vec3d> samples = {{1, 2, 0}, {3, 2, 2}};
  LoopPoseFit fit;
  fit.tvec = cv::Vec3d(1, 0, 2);
  fit.fit_sigma_px = 0.1;  // below the floor: sigma = 0.3 px, sigma^2 = 0.09
  fit.pose_covariance = cv::Matx66d::zeros();
  // The translation block, not symmetric (symmetrised: [[4, 2, 0], [2, 2,
  // 0], [0, 0, 10]]); sigma^2 C_t = [[0.36, 0.18, 0], [0.18, 0.18, 0], [0,
  // 0, 0.9]].
  const double block[3][3] = {{4, 1, 0}, {3, 2, 0}, {0, 0, 10}};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) fit.pose_covariance(3 + r, 3 + c) = block[r][c];
  }
  MetricTranslationOptions options;
  options.odometer_sigma = 0.1;  // f^2 t t^T = [[0.01, 0, 0.02], [0, 0, 0], [0.02, 0, 0.04]]
  options.covariance_scale = 2;
  const std::array<double, 9> cov = translationCovariance(samples, fit, options);
  const double expected[9] = {4.74, 0.36, 4.04, 0.36, 0.36, 0, 4.04, 0, 5.88};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(cov[i], expected[i], 1e-12) << i;

  // A fit noisier than the floor counts as measured: sigma^2 = 0.25 adds
  // 2 * 0.25 * 4 = 2 to the first entry instead of 2 * 0.09 * 4 = 0.72.
  fit.fit_sigma_px = 0.5;
  EXPECT_NEAR(translationCovariance(samples, fit, options)[0], 2 * (2 + 1.0 + 0.01), 1e-12);
}

}  // namespace
}  // namespace metric_steps
}  // namespace bowg
