#include "bowg_pipe_sim/pipe_network.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "bowg_pipe_sim/pipe_sequence.h"

namespace bowg {
namespace pipe_sim {
namespace {

/// An L: (0,0,0) -> (1,0,0) -> (1,1,0), one 90-degree bend.
PipeNetwork lShape() {
  PipeNetwork n;
  n.nodes = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  n.edges = {{0, 1}, {1, 2}};
  return n;
}

TEST(RouteTest, FilletedBendHasHandComputedLengthAndPoints) {
  const Route route(lShape(), {0, 1, 2}, 0.1);
  // Tangent length T = R tan(45 deg) = 0.1; straights 1 - 0.1 = 0.9 each;
  // arc R * pi/2 = 0.15708. Total 1.8 + 0.15708.
  EXPECT_NEAR(route.length(), 1.8 + 0.1 * M_PI / 2, 1e-12);
  const CentrelinePoint start = route.at(0);
  EXPECT_NEAR(cv::norm(start.position - cv::Vec3d(0, 0, 0)), 0, 1e-12);
  EXPECT_NEAR(cv::norm(start.tangent - cv::Vec3d(1, 0, 0)), 0, 1e-12);
  EXPECT_EQ(start.leg, 0);
  // A quarter of the way into the arc: phi = pi/8, p = P1 + n1 R (1 - cos phi)
  // + d1 R sin phi with P1 = (0.9, 0, 0), n1 = y, d1 = x.
  const double phi = M_PI / 8;
  const CentrelinePoint a = route.at(0.9 + 0.1 * phi);
  EXPECT_NEAR(a.position[0], 0.9 + 0.1 * std::sin(phi), 1e-12);
  EXPECT_NEAR(a.position[1], 0.1 * (1 - std::cos(phi)), 1e-12);
  EXPECT_NEAR(a.tangent[0], std::cos(phi), 1e-12);
  EXPECT_NEAR(a.tangent[1], std::sin(phi), 1e-12);
  // Before the mitre plane (x + y = 1 through the corner (1, 0)): still leg 0.
  EXPECT_EQ(a.leg, 0);
  // Three quarters: past the mitre plane, in leg 1.
  const CentrelinePoint b = route.at(0.9 + 0.1 * 3 * phi);
  EXPECT_EQ(b.leg, 1);
  const CentrelinePoint end = route.at(1e9);  // clamped
  EXPECT_NEAR(cv::norm(end.position - cv::Vec3d(1, 1, 0)), 0, 1e-12);
  EXPECT_NEAR(cv::norm(end.tangent - cv::Vec3d(0, 1, 0)), 0, 1e-12);
}

TEST(RouteTest, CameraStaysInsideThePipe) {
  const PipeNetwork network = PipeNetwork::figureEight();
  const Route route(network, defaultRouteNodes(1), 0.12);
  const std::vector<RouteLeg>& legs = route.renderLegs();
  for (double s = 0; s < route.length(); s += 0.01) {
    const CentrelinePoint c = route.at(s);
    const RouteLeg& leg = legs[c.leg + 1];
    const cv::Vec3d w = c.position - leg.start;
    const cv::Vec3d radial = w - leg.direction * w.dot(leg.direction);
    ASSERT_LT(cv::norm(radial), network.radius) << "at s = " << s;
  }
}

TEST(RouteTest, DefaultLapLengthIsHandCounted) {
  // One lap: 0-1-2-3-4-5-0 (14 m), 1-4-5-0 (10 m from 0), 1-2-3-4-1 (12 m),
  // 2-3-4-5-0 (12 m): 48 m of pipe. Each of its 15 right-angle bends
  // shortens the path by 2T - R pi/2 = R (2 - pi/2).
  const Route route(PipeNetwork::figureEight(), defaultRouteNodes(1), 0.12);
  EXPECT_NEAR(route.length(), 48 - 15 * 0.12 * (2 - M_PI / 2), 1e-9);
  const Route two(PipeNetwork::figureEight(), defaultRouteNodes(2), 0.12);
  EXPECT_NEAR(two.length(), 2 * route.length() - 0.12 * (2 - M_PI / 2), 1e-9);  // + bend at 0
}

TEST(RouteTest, RejectsBadRoutes) {
  const PipeNetwork n = PipeNetwork::figureEight();
  EXPECT_THROW(Route(n, {0, 2}, 0.1), std::invalid_argument);     // not joined
  EXPECT_THROW(Route(n, {0, 1, 0}, 0.1), std::invalid_argument);  // U-turn
  EXPECT_THROW(Route(n, {0}, 0.1), std::invalid_argument);
  EXPECT_THROW(Route(n, {0, 1, 2, 3}, 5.0), std::invalid_argument);  // bend too big
  PipeNetwork bad = n;
  bad.edges.push_back({0, 9});
  EXPECT_THROW(bad.validate(), std::invalid_argument);
}

TEST(RouteTest, RenderLegsContinueIntoTheNetwork) {
  const PipeNetwork n = PipeNetwork::figureEight();
  const Route route(n, {0, 1, 2}, 0.1);
  ASSERT_EQ(route.renderLegs().size(), 4u);
  // Before node 0 heading east: the pipe from node 5 (heading south).
  EXPECT_EQ(route.renderLegs()[0].edge, n.findEdge(5, 0));
  // After node 2 heading east: the pipe to node 3.
  EXPECT_EQ(route.renderLegs()[3].edge, n.findEdge(2, 3));
}

}  // namespace
}  // namespace pipe_sim
}  // namespace bowg
