// What cv::ORB::compute does with provided keypoints (the facts
// orb_descriptor.h relies on) and rBRIEF steering under rotation.
#include <gtest/gtest.h>

#include <iostream>
#include <opencv2/features2d.hpp>
#include <stdexcept>

#include "bowg/features/descriptor_conversion.h"
#include "bowg/features/orb_descriptor.h"
#include "bowg/features/orientation.h"
#include "feature_test_images.h"

namespace bowg {
namespace {

cv::Mat orbCompute(const cv::Mat& img, std::vector<cv::KeyPoint>* kps) {
  cv::Mat d;
  cv::ORB::create()->compute(img, *kps, d);
  return d;
}

TEST(OrbFacts, ProvidedKeypointsKeepAngleAndIgnoreSize) {
  const cv::Mat img = test::texturedImage(200, 200, 80, 5);
  std::vector<cv::KeyPoint> kps = {cv::KeyPoint(100, 100, 31, 0, 0, 0),
                                   cv::KeyPoint(100, 100, 7, 0, 0, 0),
                                   cv::KeyPoint(100, 100, 31, 90, 0, 0)};
  const cv::Mat d = orbCompute(img, &kps);
  ASSERT_EQ(kps.size(), 3u);
  // The angle is used as given, never recomputed.
  EXPECT_EQ(kps[0].angle, 0.f);
  EXPECT_EQ(kps[2].angle, 90.f);
  // Size plays no role.
  EXPECT_EQ(cv::norm(d.row(0), d.row(1), cv::NORM_HAMMING), 0.0);
  // The angle steers the pattern.
  EXPECT_GT(cv::norm(d.row(0), d.row(2), cv::NORM_HAMMING), 40.0);
}

TEST(OrbFacts, ProvidedKeypointsNearTheBorderAreDropped) {
  const cv::Mat img = test::texturedImage(200, 200, 80, 5);
  // Default edgeThreshold 31: x = 20 is dropped.
  std::vector<cv::KeyPoint> kps = {cv::KeyPoint(20, 100, 31, 0, 0, 0),
                                   cv::KeyPoint(100, 100, 31, 0, 0, 0)};
  const cv::Mat d = orbCompute(img, &kps);
  EXPECT_EQ(kps.size(), 1u);
  EXPECT_EQ(d.rows, 1);
}

TEST(OrbDescriptor, ReproducesOrbDetectAndComputeAcrossOctaves) {
  const cv::Mat img = test::texturedImage(320, 240, 150, 21);
  cv::Ptr<cv::ORB> orb = cv::ORB::create(400, 1.2f, 8);
  std::vector<cv::KeyPoint> kps;
  cv::Mat expected;
  orb->detectAndCompute(img, cv::noArray(), kps, expected);
  ASSERT_GT(kps.size(), 100u);
  int max_octave = 0;
  for (const cv::KeyPoint& kp : kps) max_octave = std::max(max_octave, kp.octave);
  EXPECT_GE(max_octave, 2);  // the comparison covers higher pyramid levels
  const std::vector<Descriptor> got = computeOrbDescriptors(img, kps, OrbPyramid{1.2, 8});
  const std::vector<Descriptor> want = descriptorsFromMat(expected);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i], want[i]) << "keypoint " << i;
}

TEST(OrbDescriptor, KeepsInputOrderWhenOctavesAreMixed) {
  const cv::Mat img = test::texturedImage(320, 240, 150, 21);
  const OrbPyramid pyr{1.2, 3};
  // Octave 1 first, then octave 0: cv::ORB would group them by octave.
  const std::vector<cv::KeyPoint> mixed = {cv::KeyPoint(150, 120, 37, 10, 0, 1),
                                           cv::KeyPoint(100, 100, 31, 20, 0, 0)};
  const std::vector<Descriptor> both = computeOrbDescriptors(img, mixed, pyr);
  EXPECT_EQ(both[0], computeOrbDescriptors(img, {mixed[0]}, pyr)[0]);
  EXPECT_EQ(both[1], computeOrbDescriptors(img, {mixed[1]}, pyr)[0]);
}

TEST(OrbDescriptor, RejectsKeypointsTooCloseToTheBorder) {
  const cv::Mat img = test::texturedImage(100, 100, 40, 2);
  const OrbPyramid one{1.2, 1};
  // Steered (angle != 0): 22 px.
  EXPECT_THROW(computeOrbDescriptors(img, {cv::KeyPoint(21, 50, 31, 10)}, one),
               std::invalid_argument);
  EXPECT_NO_THROW(computeOrbDescriptors(img, {cv::KeyPoint(22, 50, 31, 10)}, one));
  // 100 - 1 - 22 = 77 is the last usable coordinate.
  EXPECT_THROW(computeOrbDescriptors(img, {cv::KeyPoint(50, 78, 31, 10)}, one),
               std::invalid_argument);
  // Upright (angle 0): 16 px.
  EXPECT_THROW(computeOrbDescriptors(img, {cv::KeyPoint(15, 50, 31, 0)}, one),
               std::invalid_argument);
  EXPECT_NO_THROW(computeOrbDescriptors(img, {cv::KeyPoint(16, 50, 31, 0)}, one));
  EXPECT_NO_THROW(computeOrbDescriptors(img, {cv::KeyPoint(50, 83, 31, 0)}, one));
  // Octave beyond the pyramid.
  EXPECT_THROW(computeOrbDescriptors(img, {cv::KeyPoint(50, 50, 31, 0, 0, 1)}, OrbPyramid{1.2, 1}),
               std::invalid_argument);
}

// Rotating the image by 90 degrees about a corner: the oriented descriptor
// survives (its angle turns by 90 too), the upright one does not.
TEST(OrbDescriptor, OrientedSurvivesNinetyDegreeRotationUprightDoesNot) {
  const cv::Mat img = test::texturedImage(240, 200, 120, 9);
  cv::Mat rot;
  cv::rotate(img, rot, cv::ROTATE_90_CLOCKWISE);
  std::vector<cv::Point2f> corners;
  cv::goodFeaturesToTrack(img, corners, 200, 0.01, 8);
  std::vector<cv::KeyPoint> a_or, b_or, a_up, b_up;
  for (const cv::Point2f& p : corners) {
    const cv::Point2f q(img.rows - 1 - p.y, p.x);  // the same corner after rotation
    const cv::KeyPoint ka(p, 31), kb(q, 31);
    if (!insideOrbLevel(ka, img.size(), {1.2, 1}, kOrbSteeredRadius) ||
        !insideOrbLevel(kb, rot.size(), {1.2, 1}, kOrbSteeredRadius)) {
      continue;
    }
    a_up.emplace_back(p, 31.f, 0.f);
    b_up.emplace_back(q, 31.f, 0.f);
    a_or.emplace_back(p, 31.f, intensityCentroidAngle(img, p, kOrbHalfPatch));
    b_or.emplace_back(q, 31.f, intensityCentroidAngle(rot, q, kOrbHalfPatch));
  }
  ASSERT_GT(a_or.size(), 30u);
  const OrbPyramid pyr{1.2, 1};
  const auto da_or = computeOrbDescriptors(img, a_or, pyr);
  const auto db_or = computeOrbDescriptors(rot, b_or, pyr);
  const auto da_up = computeOrbDescriptors(img, a_up, pyr);
  const auto db_up = computeOrbDescriptors(rot, b_up, pyr);
  double sum_or = 0, sum_up = 0;
  for (std::size_t i = 0; i < da_or.size(); ++i) {
    sum_or += hammingDistance(da_or[i], db_or[i]);
    sum_up += hammingDistance(da_up[i], db_up[i]);
  }
  const double mean_or = sum_or / da_or.size();
  const double mean_up = sum_up / da_up.size();
  std::cout << "mean Hamming after 90 deg rotation over " << da_or.size() << " corners: oriented "
            << mean_or << ", upright " << mean_up << "\n";
  // Only rounding of the rotated pattern differs: a few bits at most.
  EXPECT_LT(mean_or, 10.0);
  // Unrelated patches differ in about half of the 256 bits.
  EXPECT_GT(mean_up, 60.0);
}

}  // namespace
}  // namespace bowg
