#include "bowg_pipe_sim/odometry_model.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bowg_pipe_sim/pipe_network.h"
#include "bowg_pipe_sim/pipe_sequence.h"
#include "bowg_pipe_sim/random.h"

namespace bowg {
namespace pipe_sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

OdometryNoise noNoise() {
  OdometryNoise n;
  n.scale_bias = n.scale_noise = n.heading_drift_deg = n.roll_drift_deg = 0;
  return n;
}

cv::Matx33d rotZ(double a) {
  return cv::Matx33d(std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1);
}

CameraPose poseAt(double x, double y, double z, const cv::Matx33d& R = cv::Matx33d::eye()) {
  CameraPose p;
  p.position = cv::Vec3d(x, y, z);
  p.R_world_body = R;
  return p;
}

/// `metres` along x from the origin in steps of `step`, facing +x.
std::vector<CameraPose> straightLine(double metres, double step) {
  std::vector<CameraPose> path;
  const int n = static_cast<int>(std::lround(metres / step));
  for (int i = 0; i <= n; ++i) path.push_back(poseAt(i * step, 0, 0));
  return path;
}

/// 3 m along x, a quarter turn to the left on the spot, 4 m along y, in
/// 0.1 m steps.
std::vector<CameraPose> lPath() {
  std::vector<CameraPose> path = straightLine(3, 0.1);
  const cv::Matx33d left(0, -1, 0, 1, 0, 0, 0, 0, 1);  // exactly rotZ(90 deg)
  for (int i = 0; i <= 40; ++i) path.push_back(poseAt(3, 0.1 * i, 0, left));
  return path;
}

/// The frames of the default sequence: bends, roll, wobble, offset.
std::vector<CameraPose> plannedPath(int frames) {
  const Route route(PipeNetwork::figureEight(), defaultRouteNodes(1), 0.12);
  SequenceOptions o;
  o.max_frames = frames;
  std::vector<CameraPose> path;
  for (const FrameState& f : planSequence(route, o)) path.push_back(f.pose);
  return path;
}

double pathLength(const std::vector<CameraPose>& path) {
  double length = 0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    length += cv::norm(path[i].position - path[i - 1].position);
  }
  return length;
}

/// The axis times the angle of a rotation of less than 180 deg.
cv::Vec3d rotationVector(const cv::Matx33d& R) {
  const cv::Vec3d axis(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));  // 2 sin(a) u
  const double sine = cv::norm(axis) / 2, cosine = (R(0, 0) + R(1, 1) + R(2, 2) - 1) / 2;
  if (sine == 0) return cv::Vec3d(0, 0, 0);
  return axis * (std::atan2(sine, cosine) / (2 * sine));
}

void expectPoseNear(const CameraPose& a, const CameraPose& b, double tolerance) {
  EXPECT_LT(cv::norm(a.position - b.position), tolerance);
  EXPECT_LT(cv::norm(a.R_world_body - b.R_world_body, cv::NORM_INF), tolerance);
}

TEST(OdometryModelTest, WithoutNoiseAndSlipTheOdometryIsTheTruth) {
  const std::vector<CameraPose> truth = plannedPath(800);
  const std::vector<CameraPose> odometry = simulateOdometry(truth, noNoise());
  ASSERT_EQ(odometry.size(), truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    SCOPED_TRACE(i);
    expectPoseNear(odometry[i], truth[i], 1e-9);
  }
  EXPECT_TRUE(simulateOdometry({}, noNoise()).empty());
}

TEST(OdometryModelTest, TheFirstPoseIsTheTruthWhateverTheNoise) {
  const std::vector<CameraPose> truth = plannedPath(10);
  OdometryNoise noise;
  noise.scale_noise = noise.heading_drift_deg = noise.roll_drift_deg = 10;
  const std::vector<CameraPose> odometry = simulateOdometry(truth, noise);
  EXPECT_EQ(odometry[0].position, truth[0].position);
  EXPECT_EQ(odometry[0].R_world_body, truth[0].R_world_body);
}

TEST(OdometryModelTest, SlipOverReportsAStraightLine) {
  OdometryNoise noise = noNoise();
  noise.scale_bias = 0.1;
  const std::vector<CameraPose> odometry = simulateOdometry(straightLine(10, 0.02), noise);
  expectPoseNear(odometry.back(), poseAt(11, 0, 0), 1e-9);
  noise.scale_bias = -0.1;
  expectPoseNear(simulateOdometry(straightLine(10, 0.02), noise).back(), poseAt(9, 0, 0), 1e-9);
}

TEST(OdometryModelTest, SlipScalesEveryLegOfAnLPath) {
  // Heading exact, every distance 10 % long: (3, 4) is reported as (3.3, 4.4).
  OdometryNoise noise = noNoise();
  noise.scale_bias = 0.1;
  const std::vector<CameraPose> truth = lPath();
  const std::vector<CameraPose> odometry = simulateOdometry(truth, noise);
  expectPoseNear(odometry.back(), poseAt(3.3, 4.4, 0, truth.back().R_world_body), 1e-9);
  // Slip alone scales the whole trajectory about the start: a closed square
  // closes again.
  std::vector<CameraPose> square;
  for (int side = 0; side < 4; ++side) {
    const cv::Matx33d R = rotZ(side * M_PI / 2);
    const cv::Vec3d start = side == 0 ? cv::Vec3d(0, 0, 0) : square.back().position;
    const cv::Vec3d forward(R(0, 0), R(1, 0), R(2, 0));
    for (int i = 0; i <= 20; ++i) {
      CameraPose p;
      p.position = start + forward * (0.1 * i);
      p.R_world_body = R;
      square.push_back(p);
    }
  }
  ASSERT_LT(cv::norm(square.back().position), 1e-12);
  EXPECT_LT(cv::norm(simulateOdometry(square, noise).back().position), 1e-9);
}

TEST(OdometryModelTest, BackingUpIsOverReportedToo) {
  // 2 m forward, 1 m back (facing +x all the way): reported 2.2 m forward and
  // 1.1 m back, so the odometry ends at 1.1 m, not 1.0 m.
  std::vector<CameraPose> path = straightLine(2, 0.1);
  for (int i = 1; i <= 10; ++i) path.push_back(poseAt(2 - 0.1 * i, 0, 0));
  OdometryNoise noise = noNoise();
  noise.scale_bias = 0.1;
  OdometrySimulator simulator(noise);
  CameraPose end;
  for (const CameraPose& p : path) end = simulator.step(p);
  expectPoseNear(end, poseAt(1.1, 0, 0), 1e-9);
  EXPECT_NEAR(simulator.trueDistance(), 3.0, 1e-9);
  EXPECT_NEAR(simulator.reportedDistance(), 3.3, 1e-9);
  // The angle noise grows with the distance driven either way: backing up
  // keeps the step lengths and moves the end point.
  noise = noNoise();
  noise.heading_drift_deg = 5;
  const std::vector<CameraPose> drifted = simulateOdometry(path, noise);
  EXPECT_NEAR(pathLength(drifted), 3.0, 1e-9);
  EXPECT_GT(cv::norm(drifted.back().position - path.back().position), 1e-3);
}

TEST(OdometryModelTest, AngleDriftKeepsEveryStepLengthAndMovesTheEnd) {
  const std::vector<CameraPose> truth = plannedPath(800);
  OdometryNoise noise = noNoise();
  noise.heading_drift_deg = 2;
  noise.roll_drift_deg = 2;
  const std::vector<CameraPose> odometry = simulateOdometry(truth, noise);
  EXPECT_NEAR(pathLength(odometry), pathLength(truth), 1e-9);
  for (std::size_t i = 1; i < truth.size(); ++i) {
    ASSERT_NEAR(cv::norm(odometry[i].position - odometry[i - 1].position),
                cv::norm(truth[i].position - truth[i - 1].position), 1e-12);
  }
  EXPECT_GT(cv::norm(odometry.back().position - truth.back().position), 0.01);
  // Still rotations.
  const cv::Matx33d& R = odometry.back().R_world_body;
  EXPECT_LT(cv::norm(R.t() * R - cv::Matx33d::eye(), cv::NORM_INF), 1e-9);
  EXPECT_NEAR(cv::determinant(R), 1.0, 1e-9);
}

TEST(OdometryModelTest, RollDriftAloneKeepsAStraightLineStraight) {
  // Roll about the direction of travel does not bend a straight path.
  OdometryNoise noise = noNoise();
  noise.roll_drift_deg = 10;
  const std::vector<CameraPose> odometry = simulateOdometry(straightLine(5, 0.05), noise);
  expectPoseNear(odometry.back(), poseAt(5, 0, 0, odometry.back().R_world_body), 1e-9);
  EXPECT_GT(std::abs(odometry.back().R_world_body(2, 1)), 1e-3);  // but it rolled
}

TEST(OdometryModelTest, TheSeedDecidesTheNoise) {
  const std::vector<CameraPose> truth = plannedPath(300);
  OdometryNoise noise;
  const std::vector<CameraPose> a = simulateOdometry(truth, noise),
                                b = simulateOdometry(truth, noise);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    ASSERT_EQ(a[i].position, b[i].position);
    ASSERT_EQ(a[i].R_world_body, b[i].R_world_body);
  }
  noise.seed = 2;
  const std::vector<CameraPose> c = simulateOdometry(truth, noise);
  EXPECT_GT(cv::norm(c.back().position - a.back().position), 1e-6);
}

TEST(OdometryModelTest, TheNoiseIsTheProjectsOwnGenerator) {
  // The first draw of Random(seed) is the first step's distance noise: the
  // model's output is fixed by random.h, not by a standard library's
  // std::normal_distribution.
  OdometryNoise noise = noNoise();
  noise.scale_noise = 0.02;
  noise.seed = 7;
  const std::vector<CameraPose> odometry = simulateOdometry(straightLine(1, 1), noise);
  Random rng(7);
  EXPECT_NEAR(odometry[1].position[0], 1 + 0.02 * rng.normal(), 1e-15);
}

TEST(OdometryModelTest, SwitchingOneNoiseOffLeavesTheOthersDraws) {
  // Four draws per step whatever the sigmas: the distance noise of a run
  // with and without angle drift is the same.
  const std::vector<CameraPose> truth = straightLine(3, 0.1);
  OdometryNoise noise = noNoise();
  noise.scale_noise = 0.05;
  OdometrySimulator alone(noise);
  noise.roll_drift_deg = 3;  // roll does not bend a straight line
  OdometrySimulator with_roll(noise);
  for (const CameraPose& p : truth) {
    ASSERT_NEAR(alone.step(p).position[0], with_roll.step(p).position[0], 1e-12);
  }
}

TEST(OdometryModelTest, ValidateNamesTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const auto messageOf = [](const OdometryNoise& n) -> std::string {
    try {
      n.validate();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(messageOf(OdometryNoise()), "");
  EXPECT_EQ(messageOf(noNoise()), "");
  for (double bad : {-0.51, 0.51, nan, inf}) {
    OdometryNoise n;
    n.scale_bias = bad;
    EXPECT_NE(messageOf(n).find("scale_bias"), std::string::npos) << bad;
  }
  OdometryNoise edge;
  edge.scale_bias = -0.5;
  EXPECT_EQ(messageOf(edge), "");
  edge.scale_bias = 0.5;
  EXPECT_EQ(messageOf(edge), "");
  for (double bad : {-0.01, nan, inf}) {
    OdometryNoise n;
    n.scale_noise = bad;
    EXPECT_NE(messageOf(n).find("scale_noise"), std::string::npos) << bad;
    n = OdometryNoise();
    n.heading_drift_deg = bad;
    EXPECT_NE(messageOf(n).find("heading_drift_deg"), std::string::npos) << bad;
    n = OdometryNoise();
    n.roll_drift_deg = bad;
    EXPECT_NE(messageOf(n).find("roll_drift_deg"), std::string::npos) << bad;
    EXPECT_THROW(simulateOdometry(straightLine(1, 0.1), n), std::invalid_argument);
    EXPECT_THROW(OdometrySimulator{n}, std::invalid_argument);
  }
}

TEST(OdometryModelTest, CovarianceOfAStraightLineByHand) {
  // n steps of length l along x. Distance noise alone: var(x) = n (s l)^2.
  const int n = 50;
  const double l = 0.1;
  OdometryNoise noise = noNoise();
  noise.scale_noise = 0.05;
  OdometrySimulator distance_only(noise);
  for (const CameraPose& p : straightLine(n * l, l)) distance_only.step(p);
  EXPECT_NEAR(distance_only.covariance()(0, 0), n * std::pow(0.05 * l, 2), 1e-15);
  EXPECT_NEAR(distance_only.covariance()(1, 1), 0, 1e-15);
  // Yaw drift alone (h rad/sqrt(m)): the yaw after k steps has variance
  // h^2 l k, and step k + 1 moves y by l yaw_k, so
  //   var(y_n) = l^2 sum_{j,k<n} h^2 l min(j, k) = h^2 l^3 (n-1) n (2n-1) / 6,
  //   cov(y_n, yaw_n) = l sum_{k<n} h^2 l k = h^2 l^2 (n-1) n / 2.
  // Pitch moves z alike. (The covariance is linearised along the odometry's
  // own trajectory: a tiny drift keeps it on the x axis, so the formulas
  // hold to 1e-4.)
  noise = noNoise();
  noise.heading_drift_deg = 0.001;
  const double h = 0.001 * kDeg;
  OdometrySimulator heading_only(noise);
  for (const CameraPose& p : straightLine(n * l, l)) heading_only.step(p);
  const cv::Matx<double, 6, 6>& P = heading_only.covariance();
  const double var_yaw = h * h * l * n;
  const double var_y = h * h * l * l * l * (n - 1) * n * (2 * n - 1) / 6;
  const double cov_y_yaw = h * h * l * l * (n - 1) * n / 2;
  EXPECT_NEAR(P(5, 5), var_yaw, 1e-4 * var_yaw);
  EXPECT_NEAR(P(4, 4), var_yaw, 1e-4 * var_yaw);
  EXPECT_NEAR(P(1, 1), var_y, 1e-4 * var_y);
  EXPECT_NEAR(P(2, 2), var_y, 1e-4 * var_y);
  EXPECT_NEAR(P(1, 5), cov_y_yaw, 1e-4 * cov_y_yaw);
  EXPECT_NEAR(P(2, 4), -cov_y_yaw, 1e-4 * cov_y_yaw);  // pitch up (about y) moves z down
  EXPECT_NEAR(P(0, 0), 0, 1e-4 * var_y);
  EXPECT_NEAR(P(3, 3), 0, 1e-4 * var_yaw);  // no roll drift
  EXPECT_LT(cv::norm(P - P.t(), cv::NORM_INF), 1e-12 * var_y);
}

TEST(OdometryModelTest, CovarianceMatchesTheSpreadOfManyRuns) {
  // The L path driven 3000 times with other seeds: the covariance the
  // simulator reports is the spread of the end pose around the truth (no
  // slip, so the mean is the truth to first order).
  const std::vector<CameraPose> truth = lPath();
  OdometryNoise noise;
  noise.scale_bias = 0;
  noise.scale_noise = 0.05;
  noise.heading_drift_deg = 2;
  noise.roll_drift_deg = 3;
  const int runs = 3000;
  cv::Matx<double, 6, 6> sample = cv::Matx<double, 6, 6>::zeros(), predicted = sample;
  for (int run = 0; run < runs; ++run) {
    noise.seed = 1000 + run;
    OdometrySimulator simulator(noise);
    CameraPose end;
    for (const CameraPose& p : truth) end = simulator.step(p);
    const cv::Vec3d rotation_error =
        rotationVector(end.R_world_body * truth.back().R_world_body.t());
    const cv::Vec3d position_error = end.position - truth.back().position;
    const cv::Vec<double, 6> e(position_error[0], position_error[1], position_error[2],
                               rotation_error[0], rotation_error[1], rotation_error[2]);
    sample += e * e.t() * (1.0 / runs);
    predicted += simulator.covariance() * (1.0 / runs);
  }
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c <= r; ++c) {
      SCOPED_TRACE(std::to_string(r) + "," + std::to_string(c));
      // 3000 runs: a variance's sampling error is about 2.6 %; 10 % of the
      // larger standard deviation product bounds every entry.
      EXPECT_NEAR(sample(r, c), predicted(r, c),
                  0.1 * std::sqrt(predicted(r, r) * predicted(c, c)));
    }
  }
  EXPECT_GT(predicted(1, 1), 1e-4);  // a real spread, not zeros compared
}

}  // namespace
}  // namespace pipe_sim
}  // namespace bowg
