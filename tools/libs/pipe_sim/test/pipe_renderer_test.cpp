#include "bowg_pipe_sim/pipe_renderer.h"

#include <chrono>
#include <cmath>

#include <gtest/gtest.h>

#include "bowg_pipe_sim/pipe_sequence.h"

namespace bowg {
namespace pipe_sim {
namespace {

/// One straight pipe along world x, 4 m, and a route through it.
struct StraightPipe {
  PipeNetwork network;
  std::unique_ptr<Route> route;
  std::unique_ptr<WallTexture> texture;
  StraightPipe() {
    network.nodes = {{0, 0, 0}, {4, 0, 0}};
    network.edges = {{0, 1}};
    route.reset(new Route(network, {0, 1}, 0.1));
    texture.reset(new WallTexture(network, WallTextureOptions()));
  }
};

CameraModel smallCamera() {
  CameraModel c;
  c.width = 201;
  c.height = 101;
  c.fx = c.fy = 100;
  c.cx = 100;
  c.cy = 50;
  return c;
}

TEST(PipeRendererTest, WallPixelMatchesTheHandComputedRingLight) {
  StraightPipe pipe;
  const LightModel light;
  const PipeRenderer renderer(pipe.network, *pipe.route, *pipe.texture, smallCamera(), light,
                              SensorModel());
  CameraPose pose;  // on the axis at x = 2, body x = world x, no roll
  pose.position = cv::Vec3d(2, 0, 0);
  const cv::Mat linear = renderer.renderLinear(pose);
  // Pixel (u = 200, v = 50): optical ray (1, 0, 1)/sqrt2, i.e. 45 deg to the
  // right; right = body -y = world -y, so d = (1, -1, 0)/sqrt2. It meets the
  // wall (radius r) at t = r sqrt2, point (2 + r, -r, 0); the wall normal is
  // +y, cos(incidence) = 1/sqrt2; off-axis factor cos(45)^2 = 1/2. On the
  // edge: s = 2 + r, theta = atan2(w.side, w.up) with up = z, side = x * z =
  // -y: theta = atan2(r, 0) = pi/2.
  const double r = pipe.network.radius, t = r * std::sqrt(2.0);
  const double albedo = pipe.texture->albedo(0, 2 + r, M_PI / 2);
  const double expected = light.power * albedo * (1 / std::sqrt(2.0)) /
                          (t * t + light.core_m * light.core_m) * std::exp(-t / light.falloff_m) * 0.5;
  EXPECT_NEAR(linear.at<float>(50, 200), expected, 2e-3 * expected);
  // The centre pixel looks down the axis: nothing within max_distance -> 0.
  EXPECT_EQ(linear.at<float>(50, 100), 0.f);
}

TEST(PipeRendererTest, RollRotatesTheImageAboutThePipeAxis) {
  // With the camera on the axis, rolling by 90 deg moves the wall point seen
  // to the right (u = 200) to the one seen below (v = 150, a 201 x 201 image).
  StraightPipe pipe;
  CameraModel cam = smallCamera();
  cam.height = 201;
  cam.cy = 100;
  const PipeRenderer renderer(pipe.network, *pipe.route, *pipe.texture, cam, LightModel(),
                              SensorModel());
  CameraPose pose;
  pose.position = cv::Vec3d(2, 0, 0);
  const cv::Mat upright = renderer.renderLinear(pose);
  // Roll +90 deg about body x: body y -> z. The optical "right" (-y body)
  // now points to world -z, i.e. what was "down" (optical +y = -z body).
  pose.R_world_body = cv::Matx33d(1, 0, 0, 0, 0, -1, 0, 1, 0);
  const cv::Mat rolled = renderer.renderLinear(pose);
  EXPECT_NEAR(rolled.at<float>(100, 200), upright.at<float>(200, 100), 1e-3 * upright.at<float>(200, 100));
}

TEST(PipeRendererTest, DeterministicForASeedAndNoisy) {
  const PipeNetwork network = PipeNetwork::figureEight();
  const Route route(network, defaultRouteNodes(1), 0.12);
  const WallTexture texture(network, WallTextureOptions());
  const PipeRenderer renderer(network, route, texture, CameraModel(), LightModel(), SensorModel());
  SequenceOptions so;
  so.max_frames = 40;
  const std::vector<FrameState> frames = planSequence(route, so);
  const FrameState& f = frames[37];
  const auto t0 = std::chrono::steady_clock::now();
  const cv::Mat a = renderer.render(f.pose, f.exposure, 7);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("640x480 render: %.1f ms\n", ms);
  const cv::Mat b = renderer.render(f.pose, f.exposure, 7);
  const cv::Mat c = renderer.render(f.pose, f.exposure, 8);
  ASSERT_EQ(a.type(), CV_8UC1);
  ASSERT_EQ(a.size(), cv::Size(640, 480));
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1) / a.total(), 0.5);  // noise differs
  // A ring-lit pipe: bright near wall at the border, dark far end at the centre.
  const double border = cv::mean(a(cv::Rect(0, 0, 640, 40)))[0];
  const double centre = cv::mean(a(cv::Rect(300, 220, 40, 40)))[0];
  EXPECT_GT(border, 100);
  EXPECT_LT(centre, 60);
  // Exposure scales the signal.
  EXPECT_GT(cv::mean(renderer.render(f.pose, 1.5 * f.exposure, 7))[0], cv::mean(a)[0] + 5);
}

TEST(PipeRendererTest, QuaternionOfKnownRotations) {
  const cv::Vec4d identity = rotationToQuaternion(cv::Matx33d::eye());
  EXPECT_NEAR(cv::norm(identity - cv::Vec4d(0, 0, 0, 1)), 0, 1e-12);
  // 90 deg about z: (x, y, z, w) = (0, 0, sin 45, cos 45).
  const cv::Vec4d z90 = rotationToQuaternion(cv::Matx33d(0, -1, 0, 1, 0, 0, 0, 0, 1));
  EXPECT_NEAR(cv::norm(z90 - cv::Vec4d(0, 0, std::sqrt(0.5), std::sqrt(0.5))), 0, 1e-12);
  // 180 deg about x (trace -1 branch): (1, 0, 0, 0).
  const cv::Vec4d x180 = rotationToQuaternion(cv::Matx33d(1, 0, 0, 0, -1, 0, 0, 0, -1));
  EXPECT_NEAR(cv::norm(x180 - cv::Vec4d(1, 0, 0, 0)), 0, 1e-12);
}

TEST(PipeRendererTest, RejectsBadModels) {
  CameraModel c;
  c.fx = 0;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  LightModel l;
  l.power = -1;
  EXPECT_THROW(l.validate(), std::invalid_argument);
  SensorModel s;
  s.gamma = 0;
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace pipe_sim
}  // namespace bowg
