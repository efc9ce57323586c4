#include "bowg/detection/metric_translation.h"

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <random>

#include "detection/metric_geometry.h"

namespace bowg {
namespace {

using namespace metric_geometry;

// Corner positions are good to a fraction of a pixel, not better: the
// covariance's noise never drops below this even when the fit is exact.
const double kPixelNoiseFloor = 0.3;

}  // namespace

const char* toString(MetricTranslationStatus s) {
  switch (s) {
    case MetricTranslationStatus::kEstimated:
      return "estimated";
    case MetricTranslationStatus::kDisabled:
      return "disabled";
    case MetricTranslationStatus::kNoOdometry:
      return "no_odometry";
    case MetricTranslationStatus::kNoNeighbour:
      return "no_neighbour";
    case MetricTranslationStatus::kNoNeighbourPose:
      return "no_neighbour_pose";
    case MetricTranslationStatus::kTooFewPoints:
      return "too_few_points";
    case MetricTranslationStatus::kPerspectiveFailed:
      return "perspective_failed";
    case MetricTranslationStatus::kOutsideOdometry:
      return "outside_odometry";
  }
  return "unknown";
}

std::vector<EntryId> chooseScaleNeighbours(const std::deque<DatabaseEntry>& entries, EntryId match,
                                           const MetricTranslationOptions& options) {
  std::vector<EntryId> out;
  if (match >= entries.size() || !std::isfinite(entries[match].odometer)) return out;
  const double at = entries[match].odometer;
  // Odometers never decrease, so each direction stops at the first entry
  // beyond max_baseline_m.
  for (std::size_t j = match + 1; j < entries.size(); ++j) {
    const double d = entries[j].odometer - at;
    if (!std::isfinite(d) || d > options.max_baseline_m) break;
    if (d >= options.min_baseline_m) {
      out.push_back(static_cast<EntryId>(j));
      break;
    }
  }
  for (std::size_t j = match; j-- > 0;) {
    const double d = at - entries[j].odometer;
    if (!std::isfinite(d) || d > options.max_baseline_m) break;
    if (d >= options.min_baseline_m) {
      out.push_back(static_cast<EntryId>(j));
      break;
    }
  }
  return out;
}

namespace {

// One neighbour N of the match M: their RANSAC inlier correspondences (M
// feature as "query", N feature as "match"), N's pose in M scaled by the
// odometer, and which pair sees each M feature.
struct NeighbourTrack {
  const ScaleNeighbour* input = nullptr;
  std::vector<Correspondence> pairs;
  double r[9], u[3];
  NeighbourPose pose;
  std::vector<int> pair_of_feature;  // M feature -> index into pairs, -1
};

// A triangulated loop inlier: its neighbour, its pair there, the query pixel.
struct PointSource {
  std::size_t neighbour;
  std::size_t pair;
  cv::Point2d pixel;
};

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

}  // namespace

MetricTranslation estimateMetricTranslation(const std::vector<Correspondence>& loop_inliers,
                                            const CameraIntrinsics& query_intrinsics,
                                            const VerificationView& match,
                                            const std::vector<ScaleNeighbour>& neighbours,
                                            const CameraIntrinsics& match_intrinsics,
                                            const GeometricVerificationOptions& geometric,
                                            const MetricTranslationOptions& options) {
  MetricTranslation out;
  bool baselines = !neighbours.empty();
  for (const ScaleNeighbour& n : neighbours) {
    baselines = baselines && std::isfinite(n.baseline_m) && n.baseline_m > 0;
  }
  if (!query_intrinsics.valid || !match_intrinsics.valid || !baselines) {
    out.status = MetricTranslationStatus::kNoOdometry;
    return out;
  }
  const double thr = geometric.ransac_threshold_px, conf = geometric.ransac_confidence;
  const cv::Matx33d K = cameraMatrix(match_intrinsics);
  const cv::Matx33d Kinv = K.inv();
  // 1. The pose of each neighbour N in M up to scale, then the odometer's
  //    metres for it.
  // As the loop's own verification: correspondences, a fundamental matrix
  // by RANSAC (cheap, outliers out), then the essential matrix on its
  // inliers (few RANSAC rounds of the costly 5-point solver).
  GeometricVerificationOptions track_options = geometric;
  track_options.min_inliers = 8;
  // The neighbour's fundamental matrix by the loop's RANSAC (native_ransac).
  // OpenCV's was most of the metric path's time (its 7-point SVDs: 46 % of
  // bowg_evaluate's run on the pose-graph demo). The native one's refitted
  // model can take in pairs within the threshold band whose depths are
  // wrong on a short forward baseline; the estimates it spoils that way are
  // long, and the odometry check (odometryDistanceBound) keeps them out.
  // RANSAC is the cost: first the correspondences alone say whether enough
  // loop inliers could get a depth.
  std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> candidate_pairs;
  std::vector<char> loop_feature(match.points->size(), 0), covered(match.points->size(), 0);
  for (const Correspondence& c : loop_inliers) {
    if (c.match_index < loop_feature.size()) loop_feature[c.match_index] = 1;
  }
  std::vector<int> covering(neighbours.size(), 0);
  int coverable = 0;
  for (std::size_t k = 0; k < neighbours.size(); ++k) {
    candidate_pairs.push_back(findCorrespondences(match, neighbours[k].view, geometric));
    for (const auto& p : candidate_pairs.back()) {
      if (!loop_feature[p.first]) continue;
      ++covering[k];
      if (!covered[p.first]) ++coverable;
      covered[p.first] = 1;
    }
  }
  if (coverable < options.min_points) {
    out.status = MetricTranslationStatus::kTooFewPoints;
    out.triangulated = 0;
    return out;
  }
  std::vector<NeighbourTrack> tracks;
  for (std::size_t k = 0; k < neighbours.size(); ++k) {
    const ScaleNeighbour& n = neighbours[k];
    if (covering[k] == 0) continue;
    GeometricVerificationResult g =
        verifyCorrespondences(candidate_pairs[k], match, n.view, match_intrinsics, track_options);
    if (g.status != LoopStatus::kLoopDetected || !g.has_relative_pose) continue;
    NeighbourTrack t;
    t.input = &n;
    std::copy(g.rotation, g.rotation + 9, t.r);
    std::copy(g.translation_direction, g.translation_direction + 3, t.u);
    // The pairs the essential matrix agrees with (the fundamental matrix's
    // inliers may not all be): the refit and the bootstrap's resamples hold
    // no outliers.
    t.pairs = agreeingPairs(g.inlier_correspondences, K, t.r, t.u, thr);
    if (t.pairs.size() < 8) continue;
    // RANSAC's pose is a minimal sample's: refit on all the pairs it agrees
    // with, by the estimator the bootstrap repeats.
    double r_fit[9], u_fit[3];
    if (!refitPose(t.pairs, K, t.r, t.u, r_fit, u_fit)) continue;
    std::copy(r_fit, r_fit + 9, t.r);
    std::copy(u_fit, u_fit + 3, t.u);
    t.pose = neighbourPose(t.r, t.u, n.baseline_m, K);
    t.pair_of_feature.assign(match.points->size(), -1);
    for (std::size_t i = 0; i < t.pairs.size(); ++i) {
      t.pair_of_feature[t.pairs[i].query_index] = static_cast<int>(i);
    }
    tracks.push_back(std::move(t));
  }
  if (tracks.empty()) {
    out.status = MetricTranslationStatus::kNoNeighbourPose;
    return out;
  }

  // 2. The loop inliers a neighbour sees, triangulated in M's frame (from
  //    the first neighbour that triangulates them).
  std::vector<cv::Point3d> object;
  std::vector<PointSource> source;
  for (const Correspondence& c : loop_inliers) {
    for (std::size_t k = 0; k < tracks.size(); ++k) {
      const NeighbourTrack& t = tracks[k];
      if (c.match_index >= t.pair_of_feature.size() || t.pair_of_feature[c.match_index] < 0) {
        continue;
      }
      const std::size_t pair = static_cast<std::size_t>(t.pair_of_feature[c.match_index]);
      cv::Vec3d X;
      if (!triangulate(K, t.pose, t.pairs[pair], thr, &X)) continue;
      object.emplace_back(X[0], X[1], X[2]);
      source.push_back({k, pair, cv::Point2d(c.query_x, c.query_y)});
      break;
    }
  }
  out.triangulated = static_cast<int>(object.size());
  if (out.triangulated < options.min_points) {
    out.status = MetricTranslationStatus::kTooFewPoints;
    return out;
  }

  // 3. T_Q_M by PnP (RANSAC, then least squares on its inliers), then the
  //    pose and the points' depths refined together (refineJointly). The
  //    RANSAC threshold is twice the verification's: the points carry their
  //    triangulation error into the query.
  const cv::Mat Kq(cameraMatrix(query_intrinsics));
  const cv::Mat dist = cv::Mat::zeros(5, 1, CV_64F);
  std::vector<cv::Point2d> image;
  for (const PointSource& p : source) image.push_back(p.pixel);
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  std::vector<cv::Point3d> obj_in;
  std::vector<cv::Point2d> img_in;
  std::vector<PointSource> src_in;
  cv::Mat cov6;
  double fit_sigma_px = 0;
  try {
    if (!cv::solvePnPRansac(object, image, Kq, dist, rvec, tvec, false, 200,
                            static_cast<float>(2 * thr), conf, inliers, cv::SOLVEPNP_ITERATIVE) ||
        static_cast<int>(inliers.size()) < options.min_points) {
      out.status = MetricTranslationStatus::kPerspectiveFailed;
      out.inliers = static_cast<int>(inliers.size());
      return out;
    }
    for (const int i : inliers) {
      obj_in.push_back(object[static_cast<std::size_t>(i)]);
      img_in.push_back(image[static_cast<std::size_t>(i)]);
      src_in.push_back(source[static_cast<std::size_t>(i)]);
    }
    cv::solvePnP(obj_in, img_in, Kq, dist, rvec, tvec, true, cv::SOLVEPNP_ITERATIVE);
    // The pose and the depths together (refineJointly): the estimate.
    std::vector<JointPoint> joint;
    for (std::size_t i = 0; i < src_in.size(); ++i) {
      joint.push_back(
          jointPoint(tracks, src_in[i], Kinv, &tracks[src_in[i].neighbour].pose, obj_in[i].z));
    }
    cv::Vec3d rv(rvec.at<double>(0, 0), rvec.at<double>(1, 0), rvec.at<double>(2, 0));
    cv::Vec3d tv(tvec.at<double>(0, 0), tvec.at<double>(1, 0), tvec.at<double>(2, 0));
    if (!refineJointly(&joint, K, cameraMatrix(query_intrinsics), &rv, &tv)) {
      out.status = MetricTranslationStatus::kPerspectiveFailed;
      return out;
    }
    rvec = cv::Mat(rv).clone();
    tvec = cv::Mat(tv).clone();
    for (std::size_t i = 0; i < joint.size(); ++i) {
      const cv::Vec3d X = joint[i].ray * (1.0 / joint[i].rho);
      obj_in[i] = cv::Point3d(X[0], X[1], X[2]);
    }
    std::vector<cv::Point2d> projected;
    cv::Mat J;
    cv::projectPoints(obj_in, rvec, tvec, Kq, dist, projected, J);
    double sq = 0;
    for (std::size_t i = 0; i < img_in.size(); ++i) {
      const cv::Point2d d = projected[i] - img_in[i];
      sq += d.dot(d);
    }
    out.inliers = static_cast<int>(img_in.size());
    out.rms_px = std::sqrt(sq / (2.0 * out.inliers));
    fit_sigma_px = std::sqrt(sq / std::max(1.0, 2.0 * out.inliers - 6));
    const cv::Mat J6 = J.colRange(0, 6);
    if (cv::invert(J6.t() * J6, cov6, cv::DECOMP_SVD) == 0) {
      out.status = MetricTranslationStatus::kPerspectiveFailed;
      return out;
    }
  } catch (const cv::Exception&) {
    out.status = MetricTranslationStatus::kPerspectiveFailed;  // degenerate configuration
    return out;
  }
  const cv::Vec3d t(tvec.at<double>(0, 0), tvec.at<double>(1, 0), tvec.at<double>(2, 0));

  // 4. Covariance. Most of the error is shared by all points: a neighbour's
  //    pose (its direction, from the essential matrix) bends every depth
  //    the same way, which no residual shows. A bootstrap over every set of
  //    correspondences (each neighbour's and the loop's, resampled with
  //    replacement, deterministic seed) repeats the refits of steps 1-3 from
  //    the estimate and measures the spread of t. Added: the fit's own
  //    noise through its Jacobian (the query's residual sigma, at least
  //    kPixelNoiseFloor) and the odometer's scale error along t (every
  //    point, and so t, scales with the baseline). The sum times the
  //    calibrated covariance_scale.
  std::mt19937 rng(20260101u);
  std::vector<cv::Vec3d> samples;
  std::vector<NeighbourPose> poses_s(tracks.size());
  std::vector<Correspondence> pairs_s;
  for (int s = 0; s < options.covariance_samples; ++s) {
    bool posed = true;
    for (std::size_t k = 0; k < tracks.size() && posed; ++k) {
      const NeighbourTrack& tr = tracks[k];
      std::uniform_int_distribution<std::size_t> pick_pair(0, tr.pairs.size() - 1);
      pairs_s.resize(tr.pairs.size());
      for (auto& c : pairs_s) c = tr.pairs[pick_pair(rng)];
      double r_s[9], u_s[3];
      posed = refitPose(pairs_s, K, tr.r, tr.u, r_s, u_s);
      if (posed) poses_s[k] = neighbourPose(r_s, u_s, tr.input->baseline_m, K);
    }
    if (!posed) continue;
    std::uniform_int_distribution<std::size_t> pick(0, img_in.size() - 1);
    std::vector<JointPoint> joint_s;
    for (std::size_t i = 0; i < img_in.size(); ++i) {
      const PointSource& p = src_in[pick(rng)];
      cv::Vec3d X;
      // No thresholds here: the point was accepted once; a resample moves it.
      if (!triangulate(K, poses_s[p.neighbour], tracks[p.neighbour].pairs[p.pair], 1e9, &X)) {
        continue;
      }
      joint_s.push_back(jointPoint(tracks, p, Kinv, &poses_s[p.neighbour], X[2]));
    }
    if (joint_s.size() < 6) continue;
    cv::Vec3d rv(rvec.at<double>(0, 0), rvec.at<double>(1, 0), rvec.at<double>(2, 0));
    cv::Vec3d tv(tvec.at<double>(0, 0), tvec.at<double>(1, 0), tvec.at<double>(2, 0));
    if (!refineJointly(&joint_s, K, cameraMatrix(query_intrinsics), &rv, &tv)) continue;
    samples.push_back(tv);
  }
  if (static_cast<int>(samples.size()) * 2 < options.covariance_samples || samples.size() < 2) {
    out.status = MetricTranslationStatus::kPerspectiveFailed;  // the estimate does not hold up
    return out;
  }
  cv::Vec3d mean(0, 0, 0);
  for (const cv::Vec3d& v : samples) mean += v;
  mean *= 1.0 / static_cast<double>(samples.size());
  const double f2 = options.odometer_sigma * options.odometer_sigma;
  const double sigma_px = std::max(kPixelNoiseFloor, fit_sigma_px);
  const double s2 = sigma_px * sigma_px;
  for (int r = 0; r < 3; ++r) {
    for (int c = r; c < 3; ++c) {
      double spread = 0;
      for (const cv::Vec3d& v : samples) spread += (v[r] - mean[r]) * (v[c] - mean[c]);
      spread /= static_cast<double>(samples.size() - 1);
      const double floor =
          0.5 * s2 * (cov6.at<double>(3 + r, 3 + c) + cov6.at<double>(3 + c, 3 + r));
      out.covariance[3 * r + c] = out.covariance[3 * c + r] =
          options.covariance_scale * (spread + floor + f2 * t[r] * t[c]);
    }
  }
  cv::Mat Rq;
  cv::Rodrigues(rvec, Rq);
  for (int r = 0; r < 3; ++r) {
    out.translation[r] = t[r];
    for (int c = 0; c < 3; ++c) out.rotation[3 * r + c] = Rq.at<double>(r, c);
  }
  out.status = MetricTranslationStatus::kEstimated;
  return out;
}

}  // namespace bowg
