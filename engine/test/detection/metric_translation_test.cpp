// Metric translation of a loop: a synthetic scene seen by three known
// cameras (the match M, its neighbour N a known distance ahead, the query
// Q), where the metric pose of M in Q, its scaling with the odometer's
// baseline and the covariance's odometer term are known by construction.
#include "bowg/detection/metric_translation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "bowg/core/errors.h"
#include "detection/two_view_camera.h"
#include "synthetic_vocabulary.h"

namespace bowg {
namespace {

using testing::kPi;
using testing::rotationErrorDeg;
using testing::twoViewCamera;

struct Pose {
  double R[9];  // row-major
  double t[3];
  // y = R x + t
  void apply(const double x[3], double y[3]) const {
    for (int r = 0; r < 3; ++r)
      y[r] = R[3 * r] * x[0] + R[3 * r + 1] * x[1] + R[3 * r + 2] * x[2] + t[r];
  }
};

Pose rotZ(double deg, double tx, double ty, double tz) {
  const double a = deg * kPi / 180;
  return {{std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1}, {tx, ty, tz}};
}

// Points in M's frame, seen by M, by N (X_N = n_from_m(X_M)) and by Q
// (X_Q = q_from_m(X_M), the loop's T_Q_M). Feature i of M and N is point i,
// with the same descriptor (exhaustive matching pairs them); the loop's
// inliers pair query and match feature i.
struct Scene {
  std::vector<ImagePoint> mk, nk, n2k;
  std::vector<Descriptor> md, nd, n2d;
  std::vector<Correspondence> loop;
};

// With `second`, a second neighbour sees every point too (n2k, n2d).
Scene makeScene(const Pose& n_from_m, const Pose& q_from_m, int n, double noise_px,
                std::uint64_t seed, const Pose* second = nullptr) {
  std::mt19937_64 rng(seed);
  // A pipe-like depth range: walls a few metres away at most.
  std::uniform_real_distribution<double> ux(-1.5, 1.5), uz(1.5, 4);
  std::normal_distribution<double> noise(0, noise_px);
  const CameraIntrinsics k = twoViewCamera();
  Scene s;
  auto pixel = [&](const double X[3], float* u, float* v) {
    *u = static_cast<float>(k.fx * X[0] / X[2] + k.cx + (noise_px > 0 ? noise(rng) : 0));
    *v = static_cast<float>(k.fy * X[1] / X[2] + k.cy + (noise_px > 0 ? noise(rng) : 0));
    return *u >= 0 && *u < 640 && *v >= 0 && *v < 480;
  };
  while (static_cast<int>(s.mk.size()) < n) {
    const double X[3] = {ux(rng), 0.7 * ux(rng), uz(rng)};
    double Xn[3], Xq[3], Xn2[3] = {0, 0, 1};
    n_from_m.apply(X, Xn);
    q_from_m.apply(X, Xq);
    if (second) second->apply(X, Xn2);
    ImagePoint a, b, b2;
    Correspondence c;
    if (!pixel(X, &a.x, &a.y) || !pixel(Xn, &b.x, &b.y) || !pixel(Xq, &c.query_x, &c.query_y) ||
        !pixel(Xn2, &b2.x, &b2.y)) {
      continue;
    }
    c.query_index = c.match_index = static_cast<std::uint32_t>(s.mk.size());
    c.match_x = a.x;
    c.match_y = a.y;
    const Descriptor d = testing::randomDescriptor(rng);
    s.mk.push_back(a);
    s.nk.push_back(b);
    s.md.push_back(d);
    s.nd.push_back(d);
    if (second) {
      s.n2k.push_back(b2);
      s.n2d.push_back(d);
    }
    s.loop.push_back(c);
  }
  return s;
}

GeometricVerificationOptions exhaustive() {
  GeometricVerificationOptions g;
  g.exhaustive = true;
  g.ransac_threshold_px = 1.0;
  return g;
}

// N 15 cm ahead of M and 2 cm to the side, turned 3 deg: its centre is
// c = (0.02, 0, 0.15) in M, X_N = R^T (X_M - c).
Pose neighbourFromMatch(double* baseline) {
  const double a = 3 * kPi / 180;
  const double c[3] = {0.02, 0, 0.15};
  // R = rotation about y by a; R^T rows = R columns.
  const double Rt[9] = {std::cos(a), 0, -std::sin(a), 0, 1, 0, std::sin(a), 0, std::cos(a)};
  Pose p;
  for (int i = 0; i < 9; ++i) p.R[i] = Rt[i];
  for (int r = 0; r < 3; ++r)
    p.t[r] = -(Rt[3 * r] * c[0] + Rt[3 * r + 1] * c[1] + Rt[3 * r + 2] * c[2]);
  *baseline = std::sqrt(c[0] * c[0] + c[2] * c[2]);
  return p;
}

MetricTranslation estimate(const Scene& s, double baseline, const MetricTranslationOptions& o,
                           const std::vector<Correspondence>* loop = nullptr) {
  const VerificationView m{&s.mk, &s.md, nullptr};
  const std::vector<ScaleNeighbour> n{{VerificationView{&s.nk, &s.nd, nullptr}, baseline}};
  return estimateMetricTranslation(loop ? *loop : s.loop, twoViewCamera(), m, n, twoViewCamera(),
                                   exhaustive(), o);
}

TEST(MetricTranslation, RecoversTheMetricPoseOfTheMatchInTheQuery) {
  double b = 0;
  const Pose n_from_m = neighbourFromMatch(&b);
  // The place revisited rolled by 25 deg, 4 cm right, 3 cm up, 6 cm behind.
  const Pose q_from_m = rotZ(25, 0.04, -0.03, 0.06);
  const Scene s = makeScene(n_from_m, q_from_m, 120, 0, 7);
  const MetricTranslation m = estimate(s, b, MetricTranslationOptions());
  ASSERT_EQ(m.status, MetricTranslationStatus::kEstimated) << toString(m.status);
  EXPECT_NEAR(m.translation[0], 0.04, 2e-4);
  EXPECT_NEAR(m.translation[1], -0.03, 2e-4);
  EXPECT_NEAR(m.translation[2], 0.06, 2e-4);
  EXPECT_LT(rotationErrorDeg(m.rotation, q_from_m.R), 0.01);
  // Noise-free, every point passes but those seen from M and N at less
  // than 0.2 deg (near the direction N moved in): all of them fit.
  EXPECT_GE(m.triangulated, 80);
  EXPECT_EQ(m.inliers, m.triangulated);
  EXPECT_LT(m.rms_px, 1e-3);
}

TEST(MetricTranslation, TheTranslationScalesWithTheOdometersBaseline) {
  // An odometer that reads twice the distance makes every triangulated
  // point, and so the translation, twice as far.
  double b = 0;
  const Scene s = makeScene(neighbourFromMatch(&b), rotZ(-10, 0.05, 0.02, -0.04), 80, 0, 3);
  const MetricTranslation once = estimate(s, b, MetricTranslationOptions());
  const MetricTranslation twice = estimate(s, 2 * b, MetricTranslationOptions());
  ASSERT_EQ(once.status, MetricTranslationStatus::kEstimated);
  ASSERT_EQ(twice.status, MetricTranslationStatus::kEstimated);
  for (int r = 0; r < 3; ++r) EXPECT_NEAR(twice.translation[r], 2 * once.translation[r], 2e-4);
  EXPECT_NEAR(once.translation[0], 0.05, 2e-4);
  EXPECT_NEAR(twice.translation[0], 0.10, 4e-4);
}

TEST(MetricTranslation, CovarianceAddsTheOdometerErrorAlongTheTranslation) {
  double b = 0;
  const Scene s = makeScene(neighbourFromMatch(&b), rotZ(5, 0.1, 0.0, 0.2), 60, 0, 11);
  MetricTranslationOptions without, with;
  without.covariance_scale = with.covariance_scale = 1.0;
  without.odometer_sigma = 0;
  with.odometer_sigma = 0.1;
  const MetricTranslation a = estimate(s, b, without), c = estimate(s, b, with);
  ASSERT_EQ(a.status, MetricTranslationStatus::kEstimated);
  ASSERT_EQ(c.status, MetricTranslationStatus::kEstimated);
  // (0.1)^2 t t^T with t = (0.1, 0, 0.2): 1e-4 at (0,0), 2e-4 at (0,2), 4e-4 at (2,2).
  const double expected[9] = {1e-4, 0, 2e-4, 0, 0, 0, 2e-4, 0, 4e-4};
  for (int i = 0; i < 9; ++i)
    EXPECT_NEAR(c.covariance[i] - a.covariance[i], expected[i], 2e-6) << i;
  // Noise-free, the fit's part is the pixel floor's: small, symmetric, positive.
  for (int r = 0; r < 3; ++r) {
    EXPECT_GT(a.covariance[4 * r], 0);
    EXPECT_LT(std::sqrt(a.covariance[4 * r]), 0.01);
    for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(a.covariance[3 * r + k], a.covariance[3 * k + r]);
  }
}

TEST(MetricTranslation, WithPixelNoiseTheErrorLiesWithinTheCovariance) {
  double b = 0;
  const Pose q_from_m = rotZ(40, -0.03, 0.05, 0.1);
  int within = 0;
  const int runs = 20;
  double mean_error[3] = {0, 0, 0}, mean_sigma[3] = {0, 0, 0};
  for (int seed = 0; seed < runs; ++seed) {
    const Scene s = makeScene(neighbourFromMatch(&b), q_from_m, 150, 0.5, 100 + seed);
    const MetricTranslation m = estimate(s, b, MetricTranslationOptions());
    ASSERT_EQ(m.status, MetricTranslationStatus::kEstimated) << toString(m.status);
    EXPECT_GT(m.rms_px, 0.2);
    bool ok = true;
    for (int r = 0; r < 3; ++r) {
      ok = ok && std::fabs(m.translation[r] - q_from_m.t[r]) <= 3 * std::sqrt(m.covariance[4 * r]);
    }
    within += ok;
    for (int r = 0; r < 3; ++r) {
      mean_error[r] += (m.translation[r] - q_from_m.t[r]) / runs;
      mean_sigma[r] += std::sqrt(m.covariance[4 * r]) / runs;
    }
  }
  // No bias: the mean error over the runs is a fraction of one run's sigma
  // (a PnP fit on the triangulated points alone fell 20-25 % short of t
  // with points 3-8 m away, several sigmas: refineJointly).
  for (int r = 0; r < 3; ++r) {
    std::printf("[ MEASURED ] axis %d: mean error %.4f m, mean sigma %.4f m\n", r, mean_error[r],
                mean_sigma[r]);
    EXPECT_LT(std::fabs(mean_error[r]), 0.5 * mean_sigma[r]) << "axis " << r;
  }
  // Three sigmas on each axis: 99 % of runs for a calibrated Gaussian; the
  // bootstrap's 20 samples make the sigmas themselves uncertain.
  EXPECT_GE(within, runs * 17 / 20);
}

TEST(MetricTranslation, SaysWhyWhenItCannotEstimate) {
  double b = 0;
  const Scene s = makeScene(neighbourFromMatch(&b), rotZ(0, 0.02, 0, 0.02), 40, 0, 5);
  EXPECT_EQ(estimate(s, 0.0, MetricTranslationOptions()).status,
            MetricTranslationStatus::kNoOdometry);
  EXPECT_EQ(
      estimate(s, std::numeric_limits<double>::quiet_NaN(), MetricTranslationOptions()).status,
      MetricTranslationStatus::kNoOdometry);
  CameraIntrinsics none;
  const VerificationView m{&s.mk, &s.md, nullptr};
  const std::vector<ScaleNeighbour> n{{VerificationView{&s.nk, &s.nd, nullptr}, b}};
  EXPECT_EQ(estimateMetricTranslation(s.loop, none, m, n, twoViewCamera(), exhaustive(),
                                      MetricTranslationOptions())
                .status,
            MetricTranslationStatus::kNoOdometry);
  EXPECT_EQ(estimateMetricTranslation(s.loop, twoViewCamera(), m, {}, twoViewCamera(), exhaustive(),
                                      MetricTranslationOptions())
                .status,
            MetricTranslationStatus::kNoOdometry);
  // A neighbour that shares no feature with the match: nothing to triangulate.
  Scene other = s;
  std::mt19937_64 rng(99);
  for (auto& d : other.nd) d = testing::randomDescriptor(rng);
  EXPECT_EQ(estimate(other, b, MetricTranslationOptions()).status,
            MetricTranslationStatus::kTooFewPoints);
  // One that shares 7: enough for 6 points, too few for its pose (8 pairs).
  MetricTranslationOptions six;
  six.min_points = 6;
  for (std::size_t i = 0; i < 7; ++i) other.nd[i] = s.nd[i];
  EXPECT_EQ(estimate(other, b, six).status, MetricTranslationStatus::kNoNeighbourPose);
  // Loop inliers on too few of the points the neighbour sees.
  const std::vector<Correspondence> few(s.loop.begin(), s.loop.begin() + 7);
  const MetricTranslation f = estimate(s, b, MetricTranslationOptions(), &few);
  EXPECT_EQ(f.status, MetricTranslationStatus::kTooFewPoints);
  EXPECT_LE(f.triangulated, 7);
  EXPECT_STREQ(toString(MetricTranslationStatus::kTooFewPoints), "too_few_points");
  EXPECT_STREQ(toString(MetricTranslationStatus::kOutsideOdometry), "outside_odometry");
}

std::deque<DatabaseEntry> entriesAt(const std::vector<double>& odometers) {
  std::deque<DatabaseEntry> e(odometers.size());
  for (std::size_t i = 0; i < e.size(); ++i) {
    e[i].id = static_cast<EntryId>(i);
    e[i].odometer = odometers[i];
  }
  return e;
}

TEST(MetricTranslation, TheNeighboursAreTheNearestKeyframesAtLeastTheMinimumBaselineAway) {
  MetricTranslationOptions o;
  o.min_baseline_m = 0.03;
  o.max_baseline_m = 0.5;
  const auto e = entriesAt({0, 0.01, 0.02, 0.06, 0.9, 0.91});
  using Ids = std::vector<EntryId>;
  EXPECT_EQ(chooseScaleNeighbours(e, 0, o), Ids({3}));  // 1 and 2 are closer than 3 cm
  EXPECT_EQ(chooseScaleNeighbours(e, 2, o), Ids({3}));  // 4 cm on; 0 is 2 cm back
  EXPECT_EQ(chooseScaleNeighbours(e, 3, o), Ids({2}));  // 4 is 84 cm on; 2 is 4 cm back
  // 4: 5 is 1 cm on, 3 is 84 cm back; 5: the same.
  EXPECT_EQ(chooseScaleNeighbours(e, 4, o), Ids());
  EXPECT_EQ(chooseScaleNeighbours(e, 5, o), Ids());
  EXPECT_EQ(chooseScaleNeighbours(e, 6, o), Ids());  // no such entry
  // Both sides: 0.1 on (index 2), 0.1 back (index 0).
  EXPECT_EQ(chooseScaleNeighbours(entriesAt({0, 0.1, 0.2}), 1, o), Ids({2, 0}));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(chooseScaleNeighbours(entriesAt({nan, nan, nan}), 0, o), Ids());
  // Another odometry run (a restart, a merged mission whose odometer
  // continues this one's) is no baseline: 3 is 4 cm on but in run 1.
  auto runs = entriesAt({0, 0.01, 0.02, 0.06});
  runs[3].odometry_run = 1;
  EXPECT_EQ(chooseScaleNeighbours(runs, 2, o), Ids());
  EXPECT_EQ(chooseScaleNeighbours(runs, 3, o), Ids());
}

TEST(MetricTranslation, ASecondNeighbourAddsThePointsTheFirstDoesNotSee) {
  // N1 ahead of M, N2 behind it; the loop's points are split: N1 sees the
  // first half only (the rest get unrelated descriptors), N2 the second.
  double b1 = 0;
  const Pose n1_from_m = neighbourFromMatch(&b1);
  const Pose n2_from_m = rotZ(0, 0, 0, 0.12);  // centre 12 cm behind: X_N = X_M + (0, 0, 0.12)
  const Pose q_from_m = rotZ(15, 0.03, 0.01, -0.05);
  Scene s1 = makeScene(n1_from_m, q_from_m, 60, 0, 21, &n2_from_m);
  std::mt19937_64 rng(5);
  const std::size_t half = s1.mk.size() / 2;
  for (std::size_t i = half; i < s1.nd.size(); ++i) s1.nd[i] = testing::randomDescriptor(rng);
  for (std::size_t i = 0; i < half; ++i) s1.n2d[i] = testing::randomDescriptor(rng);
  const VerificationView m{&s1.mk, &s1.md, nullptr};
  const ScaleNeighbour first{VerificationView{&s1.nk, &s1.nd, nullptr}, b1};
  const ScaleNeighbour second{VerificationView{&s1.n2k, &s1.n2d, nullptr}, 0.12};
  const MetricTranslationOptions o;
  const MetricTranslation one = estimateMetricTranslation(s1.loop, twoViewCamera(), m, {first},
                                                          twoViewCamera(), exhaustive(), o);
  const MetricTranslation both = estimateMetricTranslation(
      s1.loop, twoViewCamera(), m, {first, second}, twoViewCamera(), exhaustive(), o);
  ASSERT_EQ(one.status, MetricTranslationStatus::kEstimated);
  ASSERT_EQ(both.status, MetricTranslationStatus::kEstimated);
  EXPECT_LE(one.triangulated, static_cast<int>(half));
  EXPECT_GT(both.triangulated, one.triangulated + 10);
  for (int r = 0; r < 3; ++r) EXPECT_NEAR(both.translation[r], q_from_m.t[r], 2e-4);
}

TEST(MetricTranslation, OptionsAreValidated) {
  MetricTranslationOptions o;
  EXPECT_NO_THROW(o.validate());
  o.max_baseline_m = 0.01;  // below min_baseline_m
  EXPECT_THROW(o.validate(), InvalidParameter);
  o = MetricTranslationOptions();
  o.min_points = 5;
  EXPECT_THROW(o.validate(), InvalidParameter);
  o = MetricTranslationOptions();
  o.odometer_sigma = -0.1;
  EXPECT_THROW(o.validate(), InvalidParameter);
  o = MetricTranslationOptions();
  o.covariance_scale = 0.0;
  EXPECT_THROW(o.validate(), InvalidParameter);
}

TEST(MetricTranslation, TheCovarianceScaleMultipliesTheCovarianceOnly) {
  double b = 0;
  const Scene s = makeScene(neighbourFromMatch(&b), rotZ(5, 0.1, 0.0, 0.2), 60, 0, 11);
  MetricTranslationOptions raw, scaled;
  raw.covariance_scale = 1.0;
  scaled.covariance_scale = 2.5;
  const MetricTranslation a = estimate(s, b, raw), c = estimate(s, b, scaled);
  ASSERT_EQ(a.status, MetricTranslationStatus::kEstimated);
  ASSERT_EQ(c.status, MetricTranslationStatus::kEstimated);
  for (int i = 0; i < 9; ++i) EXPECT_DOUBLE_EQ(c.covariance[i], 2.5 * a.covariance[i]) << i;
  for (int r = 0; r < 3; ++r) EXPECT_EQ(c.translation[r], a.translation[r]);
}

}  // namespace
}  // namespace bowg
