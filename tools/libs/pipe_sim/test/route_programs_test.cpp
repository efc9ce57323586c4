#include "bowg_pipe_sim/route_programs.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "bowg_evaluation/ground_truth.h"
#include "bowg_pipe_sim/pipe_network.h"
#include "bowg_pipe_sim/pipe_sequence.h"

namespace bowg {
namespace pipe_sim {
namespace {

/// The generator's ground truth for a route at 2 cm per frame (speed
/// variation `v`, backing up allowed), as bowg_generate_pipe_sequence
/// computes it: positions, the camera's heading and the odometer.
eval::GroundTruth groundTruthOf(const std::vector<int>& nodes, double v = 0) {
  const Route route(PipeNetwork::figureEight(), nodes, 0.12);
  SequenceOptions o;
  o.speed_variation = v;
  o.allow_reverse = v > 0;
  std::vector<eval::TravelPose> poses;
  for (const FrameState& f : planSequence(route, o)) {
    eval::TravelPose p;
    p.x = f.pose.position[0], p.y = f.pose.position[1], p.z = f.pose.position[2];
    p.hx = f.tangent[0], p.hy = f.tangent[1], p.hz = f.tangent[2];
    p.distance = f.odometer;
    poses.push_back(p);
  }
  return eval::groundTruthFromPoses(poses, eval::GroundTruthOptions());
}

TEST(RouteProgramsTest, NamedProgramsAreValidRoutes) {
  const PipeNetwork n = PipeNetwork::figureEight();
  EXPECT_EQ(routeProgramNames().front(), "figure-eight");
  for (const std::string& name : routeProgramNames()) {
    EXPECT_NO_THROW(Route(n, routeProgramNodes(name, 1), 0.12)) << name;
  }
  EXPECT_EQ(routeProgramNodes("figure-eight", 2), defaultRouteNodes(2));
  EXPECT_EQ(routeProgramNodes("circuit", 2), (std::vector<int>{0, 1, 2, 3, 4, 5, 0, 1, 2, 3, 4, 5, 0}));
  EXPECT_NO_THROW(Route(n, routeProgramNodes("circuit", 3), 0.12));
}

TEST(RouteProgramsTest, RejectsUnknownNamesAndLaps) {
  EXPECT_THROW(routeProgramNodes("spiral", 1), std::invalid_argument);
  EXPECT_THROW(routeProgramNodes("partial", 2), std::invalid_argument);
  EXPECT_THROW(routeProgramNodes("no-revisit", 2), std::invalid_argument);
  EXPECT_THROW(routeProgramNodes("circuit", 0), std::invalid_argument);
  try {
    routeProgramNodes("spiral", 1);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("spiral"), std::string::npos);
  }
}

TEST(RouteProgramsTest, ParsesCustomNodeLists) {
  EXPECT_EQ(parseRouteNodes("0,1,4,5", "--route-nodes"), (std::vector<int>{0, 1, 4, 5}));
  for (const char* bad : {"", "0", "0,,1", "0,1,", "0, 1", "-1,0", "a,b"}) {
    EXPECT_THROW(parseRouteNodes(bad, "--route-nodes"), std::invalid_argument) << bad;
  }
  try {
    parseRouteNodes("0,x", "--route-nodes");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("--route-nodes"), std::string::npos);
  }
  // Joined and without U-turn is the Route's check.
  const PipeNetwork n = PipeNetwork::figureEight();
  EXPECT_THROW(Route(n, parseRouteNodes("0,2", "x"), 0.12), std::invalid_argument);
  EXPECT_THROW(Route(n, parseRouteNodes("0,1,0", "x"), 0.12), std::invalid_argument);
  EXPECT_THROW(Route(n, parseRouteNodes("0,9", "x"), 0.12), std::invalid_argument);
}

TEST(RouteProgramsTest, NoRevisitHasAnEmptyGroundTruth) {
  EXPECT_EQ(groundTruthOf(routeProgramNodes("no-revisit", 1)).positives(), 0);
  // Also when the robot dawdles and backs up: the odometer, not the frame
  // count, measures the immediate past.
  EXPECT_EQ(groundTruthOf(routeProgramNodes("no-revisit", 1), 1.5).positives(), 0);
}

TEST(RouteProgramsTest, CircuitRevisitsAllAndPartialOnlyPart) {
  // One circuit lap: nothing seen twice; the second lap: every frame of it
  // (but the first 3 m, the immediate past of the lap's end) is a revisit.
  const int one = static_cast<int>(planSequence(Route(PipeNetwork::figureEight(),
                                                      routeProgramNodes("circuit", 1), 0.12),
                                                SequenceOptions()).size());
  EXPECT_EQ(groundTruthOf(routeProgramNodes("circuit", 1)).positives(), 0);
  const eval::GroundTruth two = groundTruthOf(routeProgramNodes("circuit", 2));
  EXPECT_GT(two.positives(), one - 1 - 20);
  EXPECT_LE(two.positives(), one);
  // partial: the second pass drives 0-1-2-3-4 again (9 of the 14 m of the
  // first lap), then the unseen cross pipe.
  const eval::GroundTruth partial = groundTruthOf(routeProgramNodes("partial", 1));
  EXPECT_GT(partial.positives(), 0.55 * one);
  EXPECT_LT(partial.positives(), 0.72 * one);
}

}  // namespace
}  // namespace pipe_sim
}  // namespace bowg
