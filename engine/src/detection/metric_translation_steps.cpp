#include "detection/metric_translation_steps.h"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>

namespace bowg {
namespace metric_steps {
namespace {

using namespace metric_geometry;

// The joint refinement's view of point `p` at depth z along M's ray, its
// neighbour posed at `pose`.
JointPoint jointPoint(const std::vector<NeighbourTrack>& tracks, const PointSource& p,
                      const cv::Matx33d& Kinv, const NeighbourPose* pose, double z) {
  const Correspondence& c = tracks[p.neighbour].pairs[p.pair];
  JointPoint j;
  j.ray = Kinv * cv::Vec3d(c.query_x, c.query_y, 1);
  j.ray *= 1.0 / j.ray[2];
  j.n = cv::Point2d(c.match_x, c.match_y);
  j.q = p.pixel;
  j.neighbour = pose;
  j.rho = 1.0 / z;
  return j;
}

// A neighbour's pose from its candidate pairs with M, or false. As the
// loop's own verification: a fundamental matrix by RANSAC (cheap, outliers
// out), then the essential matrix on its inliers (few RANSAC rounds of the
// costly 5-point solver). The native RANSAC's refitted model can take in
// pairs within the threshold band whose depths are wrong on a short forward
// baseline; the estimates it spoils that way are long, and the odometry
// check (odometryDistanceBound) keeps them out.
bool poseNeighbour(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
                   const VerificationView& match, const ScaleNeighbour& n,
                   const CameraIntrinsics& match_intrinsics,
                   const GeometricVerificationOptions& geometric, NeighbourTrack* t) {
  GeometricVerificationOptions track_options = geometric;
  track_options.min_inliers = 8;
  const GeometricVerificationResult g =
      verifyCorrespondences(pairs, match, n.view, match_intrinsics, track_options);
  if (g.status != LoopStatus::kLoopDetected || !g.has_relative_pose) return false;
  const cv::Matx33d K = cameraMatrix(match_intrinsics);
  t->input = &n;
  std::copy(g.rotation, g.rotation + 9, t->r);
  std::copy(g.translation_direction, g.translation_direction + 3, t->u);
  // The pairs the essential matrix agrees with (the fundamental matrix's
  // inliers may not all be): the refit and the bootstrap's resamples hold no
  // outliers.
  t->pairs = agreeingPairs(g.inlier_correspondences, K, t->r, t->u, geometric.ransac_threshold_px);
  if (t->pairs.size() < 8) return false;
  // RANSAC's pose is a minimal sample's: refit on all the pairs it agrees
  // with, by the estimator the bootstrap repeats.
  double r_fit[9], u_fit[3];
  if (!refitPose(t->pairs, K, t->r, t->u, r_fit, u_fit)) return false;
  std::copy(r_fit, r_fit + 9, t->r);
  std::copy(u_fit, u_fit + 3, t->u);
  t->pose = neighbourPose(t->r, t->u, n.baseline_m, K);
  t->pair_of_feature.assign(match.points->size(), -1);
  for (std::size_t i = 0; i < t->pairs.size(); ++i) {
    t->pair_of_feature[t->pairs[i].query_index] = static_cast<int>(i);
  }
  return true;
}

cv::Vec3d vec3(const cv::Mat& m) {
  return cv::Vec3d(m.at<double>(0, 0), m.at<double>(1, 0), m.at<double>(2, 0));
}

// PnP by RANSAC, then least squares on its inliers; the inliers' sources and
// their first depths. False when it fails or keeps fewer than min_points.
bool solvePerspective(const TriangulatedLoop& loop, const cv::Mat& Kq,
                      const GeometricVerificationOptions& geometric,
                      const MetricTranslationOptions& options, cv::Mat* rvec, cv::Mat* tvec,
                      std::vector<cv::Point3d>* points, LoopPoseFit* fit) {
  const cv::Mat dist = cv::Mat::zeros(5, 1, CV_64F);
  std::vector<cv::Point2d> image;
  for (const PointSource& p : loop.sources) image.push_back(p.pixel);
  std::vector<int> inliers;
  if (!cv::solvePnPRansac(loop.points, image, Kq, dist, *rvec, *tvec, false, 200,
                          static_cast<float>(2 * geometric.ransac_threshold_px),
                          geometric.ransac_confidence, inliers, cv::SOLVEPNP_ITERATIVE) ||
      static_cast<int>(inliers.size()) < options.min_points) {
    fit->inlier_count = static_cast<int>(inliers.size());
    return false;
  }
  std::vector<cv::Point2d> pixels;
  for (const int i : inliers) {
    points->push_back(loop.points[static_cast<std::size_t>(i)]);
    pixels.push_back(image[static_cast<std::size_t>(i)]);
    fit->inliers.push_back(loop.sources[static_cast<std::size_t>(i)]);
  }
  cv::solvePnP(*points, pixels, Kq, dist, *rvec, *tvec, true, cv::SOLVEPNP_ITERATIVE);
  return true;
}

// The refined fit's residuals and the pose's covariance from the Jacobian
// of the projection; false when J^T J is singular.
bool measureFit(const std::vector<cv::Point3d>& points, const cv::Mat& Kq, LoopPoseFit* fit) {
  std::vector<cv::Point2d> projected;
  cv::Mat J;
  cv::projectPoints(points, cv::Mat(fit->rvec), cv::Mat(fit->tvec), Kq,
                    cv::Mat::zeros(5, 1, CV_64F), projected, J);
  double sq = 0;
  for (std::size_t i = 0; i < fit->inliers.size(); ++i) {
    const cv::Point2d d = projected[i] - fit->inliers[i].pixel;
    sq += d.dot(d);
  }
  fit->inlier_count = static_cast<int>(fit->inliers.size());
  fit->rms_px = std::sqrt(sq / (2.0 * fit->inlier_count));
  fit->fit_sigma_px = std::sqrt(sq / std::max(1.0, 2.0 * fit->inlier_count - 6));
  const cv::Mat J6 = J.colRange(0, 6);
  cv::Mat cov6;
  if (cv::invert(J6.t() * J6, cov6, cv::DECOMP_SVD) == 0) return false;
  cov6.copyTo(cv::Mat(6, 6, CV_64F, fit->pose_covariance.val));
  return true;
}

}  // namespace

NeighbourCandidates findNeighbourCandidates(const std::vector<Correspondence>& loop_inliers,
                                            const VerificationView& match,
                                            const std::vector<ScaleNeighbour>& neighbours,
                                            const GeometricVerificationOptions& geometric) {
  NeighbourCandidates out;
  std::vector<char> loop_feature(match.points->size(), 0), covered(match.points->size(), 0);
  for (const Correspondence& c : loop_inliers) {
    if (c.match_index < loop_feature.size()) loop_feature[c.match_index] = 1;
  }
  out.covering.assign(neighbours.size(), 0);
  for (std::size_t k = 0; k < neighbours.size(); ++k) {
    out.pairs.push_back(findCorrespondences(match, neighbours[k].view, geometric));
    for (const auto& p : out.pairs.back()) {
      if (!loop_feature[p.first]) continue;
      ++out.covering[k];
      if (!covered[p.first]) ++out.coverable;
      covered[p.first] = 1;
    }
  }
  return out;
}

std::vector<NeighbourTrack> poseNeighbours(const NeighbourCandidates& candidates,
                                           const VerificationView& match,
                                           const std::vector<ScaleNeighbour>& neighbours,
                                           const CameraIntrinsics& match_intrinsics,
                                           const GeometricVerificationOptions& geometric) {
  std::vector<NeighbourTrack> tracks;
  for (std::size_t k = 0; k < neighbours.size(); ++k) {
    if (candidates.covering[k] == 0) continue;
    NeighbourTrack t;
    if (poseNeighbour(candidates.pairs[k], match, neighbours[k], match_intrinsics, geometric, &t)) {
      tracks.push_back(std::move(t));
    }
  }
  return tracks;
}

TriangulatedLoop triangulateLoopInliers(const std::vector<Correspondence>& loop_inliers,
                                        const std::vector<NeighbourTrack>& tracks,
                                        const cv::Matx33d& K, double threshold_px) {
  TriangulatedLoop out;
  for (const Correspondence& c : loop_inliers) {
    for (std::size_t k = 0; k < tracks.size(); ++k) {
      const NeighbourTrack& t = tracks[k];
      if (c.match_index >= t.pair_of_feature.size() || t.pair_of_feature[c.match_index] < 0) {
        continue;
      }
      const std::size_t pair = static_cast<std::size_t>(t.pair_of_feature[c.match_index]);
      cv::Vec3d X;
      if (!triangulate(K, t.pose, t.pairs[pair], threshold_px, &X)) continue;
      out.points.emplace_back(X[0], X[1], X[2]);
      out.sources.push_back({k, pair, cv::Point2d(c.query_x, c.query_y)});
      break;
    }
  }
  return out;
}

MetricTranslationStatus fitLoopPose(const TriangulatedLoop& loop,
                                    const std::vector<NeighbourTrack>& tracks,
                                    const CameraIntrinsics& query_intrinsics, const cv::Matx33d& K,
                                    const GeometricVerificationOptions& geometric,
                                    const MetricTranslationOptions& options, LoopPoseFit* fit) {
  const cv::Mat Kq(cameraMatrix(query_intrinsics));
  const cv::Matx33d Kinv = K.inv();
  try {
    cv::Mat rvec, tvec;
    std::vector<cv::Point3d> points;
    if (!solvePerspective(loop, Kq, geometric, options, &rvec, &tvec, &points, fit)) {
      return MetricTranslationStatus::kPerspectiveFailed;
    }
    // The pose and the depths together (refineJointly): the estimate.
    std::vector<JointPoint> joint;
    for (std::size_t i = 0; i < fit->inliers.size(); ++i) {
      const PointSource& p = fit->inliers[i];
      joint.push_back(jointPoint(tracks, p, Kinv, &tracks[p.neighbour].pose, points[i].z));
    }
    fit->rvec = vec3(rvec);
    fit->tvec = vec3(tvec);
    if (!refineJointly(&joint, K, cameraMatrix(query_intrinsics), &fit->rvec, &fit->tvec)) {
      return MetricTranslationStatus::kPerspectiveFailed;
    }
    for (std::size_t i = 0; i < joint.size(); ++i) {
      const cv::Vec3d X = joint[i].ray * (1.0 / joint[i].rho);
      points[i] = cv::Point3d(X[0], X[1], X[2]);
    }
    if (!measureFit(points, Kq, fit)) return MetricTranslationStatus::kPerspectiveFailed;
  } catch (const cv::Exception&) {
    return MetricTranslationStatus::kPerspectiveFailed;  // degenerate configuration
  }
  return MetricTranslationStatus::kEstimated;
}

std::vector<cv::Vec3d> bootstrapTranslations(const std::vector<NeighbourTrack>& tracks,
                                             const LoopPoseFit& fit,
                                             const CameraIntrinsics& query_intrinsics,
                                             const cv::Matx33d& K, int samples, std::mt19937* rng) {
  const cv::Matx33d Kinv = K.inv();
  std::vector<cv::Vec3d> out;
  std::vector<NeighbourPose> poses_s(tracks.size());
  std::vector<Correspondence> pairs_s;
  for (int s = 0; s < samples; ++s) {
    bool posed = true;
    for (std::size_t k = 0; k < tracks.size() && posed; ++k) {
      const NeighbourTrack& tr = tracks[k];
      std::uniform_int_distribution<std::size_t> pick_pair(0, tr.pairs.size() - 1);
      pairs_s.resize(tr.pairs.size());
      for (auto& c : pairs_s) c = tr.pairs[pick_pair(*rng)];
      double r_s[9], u_s[3];
      posed = refitPose(pairs_s, K, tr.r, tr.u, r_s, u_s);
      if (posed) poses_s[k] = neighbourPose(r_s, u_s, tr.input->baseline_m, K);
    }
    if (!posed) continue;
    std::uniform_int_distribution<std::size_t> pick(0, fit.inliers.size() - 1);
    std::vector<JointPoint> joint_s;
    for (std::size_t i = 0; i < fit.inliers.size(); ++i) {
      const PointSource& p = fit.inliers[pick(*rng)];
      cv::Vec3d X;
      // No thresholds here: the point was accepted once; a resample moves it.
      if (!triangulate(K, poses_s[p.neighbour], tracks[p.neighbour].pairs[p.pair], 1e9, &X)) {
        continue;
      }
      joint_s.push_back(jointPoint(tracks, p, Kinv, &poses_s[p.neighbour], X[2]));
    }
    if (joint_s.size() < 6) continue;
    cv::Vec3d rv = fit.rvec, tv = fit.tvec;
    if (!refineJointly(&joint_s, K, cameraMatrix(query_intrinsics), &rv, &tv)) continue;
    out.push_back(tv);
  }
  return out;
}

std::array<double, 9> translationCovariance(const std::vector<cv::Vec3d>& samples,
                                            const LoopPoseFit& fit,
                                            const MetricTranslationOptions& options) {
  std::array<double, 9> out{};
  cv::Vec3d mean(0, 0, 0);
  for (const cv::Vec3d& v : samples) mean += v;
  mean *= 1.0 / static_cast<double>(samples.size());
  const double f2 = options.odometer_sigma * options.odometer_sigma;
  const double sigma_px = std::max(kPixelNoiseFloor, fit.fit_sigma_px);
  const double s2 = sigma_px * sigma_px;
  const cv::Vec3d& t = fit.tvec;
  const cv::Matx66d& cov6 = fit.pose_covariance;
  for (int r = 0; r < 3; ++r) {
    for (int c = r; c < 3; ++c) {
      double spread = 0;
      for (const cv::Vec3d& v : samples) spread += (v[r] - mean[r]) * (v[c] - mean[c]);
      spread /= static_cast<double>(samples.size() - 1);
      const double floor = 0.5 * s2 * (cov6(3 + r, 3 + c) + cov6(3 + c, 3 + r));
      out[3 * r + c] = out[3 * c + r] =
          options.covariance_scale * (spread + floor + f2 * t[r] * t[c]);
    }
  }
  return out;
}

}  // namespace metric_steps
}  // namespace bowg
