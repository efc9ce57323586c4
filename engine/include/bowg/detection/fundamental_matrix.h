// The fundamental matrix's two equations the geometric verification needs:
// the 7-point solution through a minimal sample and the epipolar distance an
// inlier is judged by. F is row-major and relates a point x1 of the first
// image to a point x2 of the second by x2^T F x1 = 0 (OpenCV's
// findFundamentalMat(points1, points2) convention).
#pragma once

namespace bowg {

/// A point pair: (x1, y1) in the first image, (x2, y2) in the second.
struct PointPair {
  double x1 = 0, y1 = 0, x2 = 0, y2 = 0;
};

/// The 7-point algorithm (Hartley & Zisserman, Sec. 11.1.2): the 7 x 9
/// system x2^T F x1 = 0 has a two-dimensional null space F2 + a (F1 - F2);
/// det F = 0 is a cubic in a with one or three real roots. Writes the
/// solutions to `solutions` (up to three, 9 values each, scaled so that
/// their largest element is 1 in magnitude) and returns how many. A system
/// of rank 6 (pairs that do not move, x1 = x2, fit every skew-symmetric F)
/// gives the singular vectors of its three-dimensional null space; below
/// rank 6 the sample is degenerate: 0. The points should be normalised
/// (centred, ~unit spread) for a well-conditioned system.
int sevenPointFundamental(const PointPair pairs[7], double solutions[3][9]);

/// The least-squares fundamental matrix through n >= 8 pairs (the
/// normalised 8-point algorithm, Hartley & Zisserman Sec. 11.1-11.2): the
/// unit f minimising |A f| (the smallest eigenvector of A^T A), then the
/// nearest rank-2 matrix (its smallest singular value set to 0). Scaled so
/// that its largest element is 1 in magnitude. false when the pairs do not
/// determine it (fewer than 8, not finite). The points should be normalised.
bool eightPointFundamental(const PointPair* pairs, int n, double f[9]);

/// The two distances to the epipolar lines share their numerator, the
/// residual x2^T F x1; `normal` is the smaller squared norm of the lines'
/// normals, (F x1)_12 and (F^T x2)_12. The larger squared distance is
/// residual^2 / normal. Inline: RANSAC evaluates it for every pair and model.
struct EpipolarResidual {
  double residual;
  double normal;
};

inline EpipolarResidual epipolarResidual(const double f[9], const PointPair& p) {
  const double l2a = f[0] * p.x1 + f[1] * p.y1 + f[2];
  const double l2b = f[3] * p.x1 + f[4] * p.y1 + f[5];
  const double l2c = f[6] * p.x1 + f[7] * p.y1 + f[8];
  const double l1a = f[0] * p.x2 + f[3] * p.y2 + f[6];
  const double l1b = f[1] * p.x2 + f[4] * p.y2 + f[7];
  const double n2 = l2a * l2a + l2b * l2b, n1 = l1a * l1a + l1b * l1b;
  return {p.x2 * l2a + p.y2 * l2b + l2c, n1 < n2 ? n1 : n2};
}

/// The squared distance of the pair to its epipolar lines, the larger of
/// the two images': max(d(x2, F x1)^2, d(x1, F^T x2)^2), in the points'
/// units (OpenCV's findFundamentalMat RANSAC error). Infinite when a line
/// is undefined (F x1 or F^T x2 has no direction).
double epipolarErrorSquared(const double f[9], const PointPair& p);

}  // namespace bowg
