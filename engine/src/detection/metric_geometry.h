// Two-view geometry of the metric translation (metric_translation.h):
// internal to the detection stage.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "bowg/core/correspondence.h"
#include "bowg/core/types.h"

namespace bowg {
namespace metric_geometry {

// Rays from M and N closer than this in angle triangulate a depth that
// pixel noise dominates: at 0.5 px of noise and f = 450 px the depth's
// relative error is about 0.5 / (450 x parallax), 10 % at 0.6 deg.
const double kMinParallaxRad = 0.6 * 3.14159265358979323846 / 180.0;

// The neighbour N in M's frame: X_N = R X_M + t, N's centre c in M.
struct NeighbourPose {
  cv::Matx33d R;
  cv::Vec3d t, centre;
  cv::Matx34d projection;  // K [R | t]
};

// One point of the joint refinement: seen at m in M (its ray, exact), at
// n in the neighbour (fixed pose), at q in the query.
struct JointPoint {
  cv::Vec3d ray;  // K_M^-1 (m, 1), scaled to z = 1
  cv::Point2d n, q;
  const NeighbourPose* neighbour;
  double rho;  // inverse depth along the ray
};

cv::Matx33d cameraMatrix(const CameraIntrinsics& k);

// From the essential matrix's T_M_N (X_M = r X_N + u, |u| = 1) and the
// metres driven: X_N = r^T X_M - r^T u b.
NeighbourPose neighbourPose(const double r_mn[9], const double u[3], double baseline_m,
                            const cv::Matx33d& K);

// The point seen at pixel a in M and b in N, in M's frame (metres); false
// when behind either camera, beyond `max_error_px` from either pixel, or
// seen from M and N at less than kMinParallaxRad.
bool triangulate(const cv::Matx33d& K, const NeighbourPose& n, const Correspondence& mn,
                 double max_error_px, cv::Vec3d* X);

// The pairs (M pixel, N pixel) within `thr` pixels (Sampson distance) of the
// epipolar geometry of T_M_N = (r, u): F = K^-T [u]x r K^-1, x_M^T F x_N = 0.
std::vector<Correspondence> agreeingPairs(const std::vector<Correspondence>& pairs,
                                          const cv::Matx33d& K, const double r[9],
                                          const double u[3], double thr);

// T_M_N fitted to inlier pairs (all of them, or a bootstrap resample) from
// (r0, u0): Levenberg-Marquardt on the pairs' Sampson distances over the 5
// degrees of freedom (a rotation increment, the direction on its sphere).
// RANSAC's 5-point pose is a minimal sample's: its error bends every
// triangulated depth the same way (10-20 % of scale at half a pixel of noise
// on the corridor of loop_detector_test.cpp); the linear 8-point fit is
// poorly conditioned for a camera moving along its axis, as in a pipe.
bool refitPose(const std::vector<Correspondence>& pairs, const cv::Matx33d& K, const double r0[9],
               const double u0[3], double rotation[9], double direction[3]);

// The query's pose and the points' depths refined together (Gauss-Newton
// with the Schur complement on the depths, M and the neighbours fixed). A
// PnP fit takes the triangulated points as exact; their depth noise then
// shrinks the translation (errors in variables: 20-25 % short at half a
// pixel of noise, points 3-8 m from a 15 cm baseline); letting the query's
// own observations move the depths removes that. False when it diverges.
bool refineJointly(std::vector<JointPoint>* points, const cv::Matx33d& K, const cv::Matx33d& Kq,
                   cv::Vec3d* rvec, cv::Vec3d* tvec);

}  // namespace metric_geometry
}  // namespace bowg
