#include "bowg/detection/geometric_verification.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/version.hpp>
#include <random>
#include <stdexcept>

#include "bowg/detection/fundamental_ransac.h"
#include "detection/metric_geometry.h"

// findFundamentalMat takes a sample limit (maxIters) from OpenCV 3.4.10 / 4.3.
#if CV_VERSION_MAJOR > 4 || (CV_VERSION_MAJOR == 4 && CV_VERSION_MINOR >= 3) || \
    (CV_VERSION_MAJOR == 3 && CV_VERSION_MINOR == 4 && CV_VERSION_REVISION >= 10)
#define BOWG_CV_FUNDAMENTAL_MAX_ITERS 1
#else
#define BOWG_CV_FUNDAMENTAL_MAX_ITERS 0
#endif

namespace bowg {
namespace {

using Pair = std::pair<std::uint32_t, std::uint32_t>;

// The per-group best matches of matchGroup, kept across the groups of one
// image pair so that a node of the direct index costs no allocation.
struct MatchScratch {
  // Per match feature of the group: the key (below) of its nearest query
  // feature of the group.
  std::vector<std::uint64_t> nearest_query;
  // Per query feature of the group: the key of its nearest match feature and
  // the second smallest distance, counting a tie with the nearest.
  struct Row {
    std::uint64_t nearest;
    int second;
  };
  std::vector<Row> rows;
};

// Distance and position in the group as one number: the smallest key is
// the nearest feature, the first of equals, so that min() alone keeps it.
// Selects instead of branches: which distance is smallest is a coin toss the
// branch predictor loses.
inline std::uint64_t matchKey(int distance, std::size_t position) {
  return static_cast<std::uint64_t>(distance) << 32 | position;
}
inline int keyDistance(std::uint64_t key) { return static_cast<int>(key >> 32); }
inline std::uint32_t keyPosition(std::uint64_t key) { return static_cast<std::uint32_t>(key); }

// The features of one node: a run of a DirectIndex's (node, feature) pairs.
struct Run {
  const DirectIndex::value_type* begin;
  std::size_t n;
  std::size_t size() const { return n; }
  bool empty() const { return n == 0; }
  std::uint32_t operator[](std::size_t i) const { return begin[i].second; }
};

// Matches the query features `qs` against the match features `ms` (one node of
// the direct index, or everything when exhaustive) and appends the pairs that
// pass the distance, ratio and mutual tests.
void matchGroup(const std::vector<Descriptor>& qd, Run qs, const std::vector<Descriptor>& md,
                Run ms, const GeometricVerificationOptions& options, MatchScratch* scratch,
                std::vector<Pair>* out) {
  if (qs.empty() || ms.empty()) return;
  const int kInf = std::numeric_limits<int>::max();
  const std::uint64_t kNone = matchKey(kInf, 0);
  std::vector<std::uint64_t>& nearest_query = scratch->nearest_query;
  std::vector<MatchScratch::Row>& rows = scratch->rows;
  nearest_query.assign(ms.size(), kNone);
  rows.resize(qs.size());
  for (std::size_t a = 0; a < qs.size(); ++a) {
    const Descriptor& d = qd[qs[a]];
    std::uint64_t nearest = kNone;
    int second = kInf;
    for (std::size_t b = 0; b < ms.size(); ++b) {
      const int dist = hammingDistance(d, md[ms[b]]);
      // A nearer feature makes the old nearest the second; a farther one
      // may be the second itself.
      second = std::min(second, std::max(keyDistance(nearest), dist));
      nearest = std::min(nearest, matchKey(dist, b));
      nearest_query[b] = std::min(nearest_query[b], matchKey(dist, a));
    }
    rows[a] = {nearest, second};
  }
  for (std::size_t a = 0; a < qs.size(); ++a) {
    const int best = keyDistance(rows[a].nearest), second = rows[a].second;
    const std::uint32_t b = keyPosition(rows[a].nearest);
    if (best > options.max_hamming) continue;
    if (second != kInf && !(best < options.max_neighbour_ratio * second)) continue;
    if (keyPosition(nearest_query[b]) != a) continue;  // not mutual
    out->emplace_back(qs[a], ms[b]);
  }
}

void checkView(const VerificationView& v, const char* name, bool need_direct) {
  if (!v.points || !v.descriptors || (need_direct && !v.direct)) {
    throw std::invalid_argument(std::string("verifyGeometry: ") + name + " view is incomplete");
  }
  if (v.points->size() != v.descriptors->size()) {
    throw std::invalid_argument(std::string("verifyGeometry: ") + name +
                                " keypoints and descriptors differ in number");
  }
}

// The inliers of the fundamental matrix by our RANSAC (fundamental_ransac.h);
// empty when it finds no model.
std::vector<unsigned char> nativeInlierMask(const std::vector<PointPair>& points,
                                            const GeometricVerificationOptions& options,
                                            int samples) {
  FundamentalRansacOptions ransac;
  ransac.threshold_px = options.ransac_threshold_px;
  ransac.confidence = options.ransac_confidence;
  ransac.max_samples = samples;
  ransac.refits = options.ransac_refits;
  ransac.seed += static_cast<std::uint64_t>(options.ransac_seed);
  return fundamentalRansac(points, ransac).inlier_mask;
}

// The same by cv::findFundamentalMat(FM_RANSAC) (DLoopDetector's
// verification). OpenCV runs LMedS instead below 15 pairs and, before 3.4.10
// / 4.3, always draws up to its 1,000 samples.
std::vector<unsigned char> openCvInlierMask(const std::vector<PointPair>& points,
                                            const GeometricVerificationOptions& options,
                                            int samples) {
  // OpenCV seeds its generator the same way on every call: another
  // sequence is another order of the pairs (Fisher-Yates by mt19937, whose
  // output the standard fixes).
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  if (options.ransac_seed > 0) {
    std::mt19937 rng(static_cast<std::uint32_t>(options.ransac_seed));
    for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng() % i]);
  }
  std::vector<cv::Point2f> pq, pm;
  pq.reserve(points.size());
  pm.reserve(points.size());
  for (const std::size_t k : order) {
    pq.emplace_back(static_cast<float>(points[k].x1), static_cast<float>(points[k].y1));
    pm.emplace_back(static_cast<float>(points[k].x2), static_cast<float>(points[k].y2));
  }
  std::vector<unsigned char> mask;
  cv::Mat F;
  try {
#if BOWG_CV_FUNDAMENTAL_MAX_ITERS
    F = cv::findFundamentalMat(pq, pm, cv::FM_RANSAC, options.ransac_threshold_px,
                               options.ransac_confidence, samples, mask);
#else
    (void)samples;
    F = cv::findFundamentalMat(pq, pm, cv::FM_RANSAC, options.ransac_threshold_px,
                               options.ransac_confidence, mask);
#endif
  } catch (const cv::Exception&) {
    F.release();  // degenerate configuration: no model, no inliers
  }
  if (F.empty() || mask.size() != points.size()) return {};
  std::vector<unsigned char> in_pair_order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) in_pair_order[order[i]] = mask[i];
  return in_pair_order;
}

}  // namespace

std::vector<Pair> findCorrespondences(const VerificationView& query, const VerificationView& match,
                                      const GeometricVerificationOptions& options) {
  checkView(query, "query", !options.exhaustive);
  checkView(match, "match", !options.exhaustive);
  std::vector<Pair> out;
  MatchScratch scratch;
  if (options.exhaustive) {
    // Every feature under one node.
    DirectIndex qs(query.descriptors->size()), ms(match.descriptors->size());
    for (std::uint32_t i = 0; i < qs.size(); ++i) qs[i] = {0, i};
    for (std::uint32_t i = 0; i < ms.size(); ++i) ms[i] = {0, i};
    matchGroup(*query.descriptors, Run{qs.data(), qs.size()}, *match.descriptors,
               Run{ms.data(), ms.size()}, options, &scratch, &out);
  } else {
    // Both direct indexes are sorted by node: walk them together, one run of
    // equal nodes at a time.
    const DirectIndex& q = *query.direct;
    const DirectIndex& m = *match.direct;
    std::size_t qi = 0, mi = 0;
    while (qi < q.size() && mi < m.size()) {
      if (q[qi].first < m[mi].first) {
        ++qi;
      } else if (m[mi].first < q[qi].first) {
        ++mi;
      } else {
        const NodeId node = q[qi].first;
        std::size_t qj = qi, mj = mi;
        while (qj < q.size() && q[qj].first == node) ++qj;
        while (mj < m.size() && m[mj].first == node) ++mj;
        matchGroup(*query.descriptors, Run{q.data() + qi, qj - qi}, *match.descriptors,
                   Run{m.data() + mi, mj - mi}, options, &scratch, &out);
        qi = qj;
        mi = mj;
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

int ransacSampleBound(int correspondences, int min_inliers, double confidence) {
  if (correspondences <= 0 || min_inliers <= 0) return kOpenCvRansacSamples;
  return adaptiveSampleCount(static_cast<double>(min_inliers) / correspondences, confidence,
                             kOpenCvRansacSamples);
}

bool ransacSampleBoundAvailable(const GeometricVerificationOptions& options) {
  return options.native_ransac || BOWG_CV_FUNDAMENTAL_MAX_ITERS != 0;
}

bool relativePoseFromCorrespondences(const std::vector<Correspondence>& pairs,
                                     const CameraIntrinsics& intrinsics, double ransac_threshold_px,
                                     double confidence, double rotation[9],
                                     double translation_direction[3]) {
  if (!intrinsics.valid || pairs.size() < 5) return false;
  std::vector<cv::Point2d> pq, pm;
  pq.reserve(pairs.size());
  pm.reserve(pairs.size());
  for (const auto& c : pairs) {
    pq.emplace_back(c.query_x, c.query_y);
    pm.emplace_back(c.match_x, c.match_y);
  }
  const cv::Mat K = (cv::Mat_<double>(3, 3) << intrinsics.fx, 0, intrinsics.cx, 0, intrinsics.fy,
                     intrinsics.cy, 0, 0, 1);
  // recoverPose(E, points1, points2) returns R, t with X2 = R * X1 + t for a
  // point X1 in camera 1. With camera 1 = match and camera 2 = query this is
  // X_Q = R * X_M + t, i.e. the pose of the match camera in the query frame.
  cv::Mat mask, R, t;
  try {
    const cv::Mat E =
        cv::findEssentialMat(pm, pq, K, cv::RANSAC, confidence, ransac_threshold_px, mask);
    if (E.rows != 3 || E.cols != 3) return false;  // none, or several stacked solutions
    if (cv::recoverPose(E, pm, pq, K, R, t, mask) <= 0) return false;
  } catch (const cv::Exception&) {
    return false;  // degenerate configuration
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) rotation[3 * r + c] = R.at<double>(r, c);
    translation_direction[r] = t.at<double>(r, 0);
  }
  // RANSAC's model is a 5-point sample's (a degree or two off on a clean
  // scene): refit it to every pair it agrees with, as the metric
  // translation does (metric_geometry.h).
  const cv::Matx33d k(K);
  const std::vector<Correspondence> agreeing = metric_geometry::agreeingPairs(
      pairs, k, rotation, translation_direction, ransac_threshold_px);
  double r_fit[9], u_fit[3];
  if (agreeing.size() >= 8 &&
      metric_geometry::refitPose(agreeing, k, rotation, translation_direction, r_fit, u_fit)) {
    std::copy(r_fit, r_fit + 9, rotation);
    std::copy(u_fit, u_fit + 3, translation_direction);
  }
  return true;
}

GeometricVerificationResult verifyGeometry(const VerificationView& query,
                                           const VerificationView& match,
                                           const CameraIntrinsics& intrinsics,
                                           const GeometricVerificationOptions& options) {
  return verifyCorrespondences(findCorrespondences(query, match, options), query, match, intrinsics,
                               options);
}

GeometricVerificationResult verifyCorrespondences(
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
    const VerificationView& query, const VerificationView& match,
    const CameraIntrinsics& intrinsics, const GeometricVerificationOptions& options,
    int decisive_inliers) {
  GeometricVerificationResult result;
  result.correspondences = static_cast<int>(pairs.size());
  // 8 points: the minimum of the 8-point algorithm findFundamentalMat runs.
  if (pairs.size() < 8) {
    result.status = LoopStatus::kTooFewCorrespondences;
    return result;
  }
  std::vector<PointPair> points;
  points.reserve(pairs.size());
  for (const auto& p : pairs) {
    const ImagePoint& a = (*query.points)[p.first];
    const ImagePoint& b = (*match.points)[p.second];
    points.push_back({a.x, a.y, b.x, b.y});
  }
  const int samples = options.ransac_bound_confidence > 0.0
                          ? ransacSampleBound(static_cast<int>(pairs.size()),
                                              std::max(options.min_inliers, decisive_inliers),
                                              options.ransac_bound_confidence)
                          : kOpenCvRansacSamples;
  const std::vector<unsigned char> mask = options.native_ransac
                                              ? nativeInlierMask(points, options, samples)
                                              : openCvInlierMask(points, options, samples);
  if (mask.size() == pairs.size()) {
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (!mask[i]) continue;
      Correspondence c;
      c.query_index = pairs[i].first;
      c.match_index = pairs[i].second;
      c.query_x = static_cast<float>(points[i].x1);
      c.query_y = static_cast<float>(points[i].y1);
      c.match_x = static_cast<float>(points[i].x2);
      c.match_y = static_cast<float>(points[i].y2);
      result.inlier_correspondences.push_back(c);
    }
  }
  result.inliers = static_cast<int>(result.inlier_correspondences.size());
  if (result.inliers < options.min_inliers) {
    result.status = LoopStatus::kTooFewInliers;
    result.inlier_correspondences.clear();
    return result;
  }
  result.status = LoopStatus::kLoopDetected;
  result.has_relative_pose = relativePoseFromCorrespondences(
      result.inlier_correspondences, intrinsics, options.ransac_threshold_px,
      options.ransac_confidence, result.rotation, result.translation_direction);
  return result;
}

}  // namespace bowg
