#include "bowg/detection/fundamental_matrix.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

#include "bowg/detection/smallest_eigenvector.h"

namespace bowg {
namespace {

double det3(const double m[9]) {
  return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
         m[2] * (m[3] * m[7] - m[4] * m[6]);
}

// The real roots of c[3] a^3 + c[2] a^2 + c[1] a + c[0]; returns how many.
int realCubicRoots(const double c[4], double roots[3]) {
  const double scale = std::max(std::max(std::fabs(c[0]), std::fabs(c[1])),
                                std::max(std::fabs(c[2]), std::fabs(c[3])));
  if (!(scale > 0.0)) return 0;
  int n = 0;
  if (std::fabs(c[3]) <= 1e-12 * scale) {
    // Degree 2 or 1 (the pencil's difference F1 - F2 is singular).
    if (std::fabs(c[2]) <= 1e-12 * scale) {
      if (std::fabs(c[1]) <= 1e-12 * scale) return 0;
      roots[n++] = -c[0] / c[1];
    } else {
      const double disc = c[1] * c[1] - 4.0 * c[2] * c[0];
      if (disc < 0.0) return 0;
      // The stable pair of quadratic roots.
      const double q = -0.5 * (c[1] + std::copysign(std::sqrt(disc), c[1]));
      roots[n++] = q / c[2];
      if (q != 0.0) roots[n++] = c[0] / q;
    }
  } else {
    // Monic a^3 + A a^2 + B a + C, depressed by a = t - A / 3 to
    // t^3 + p t + q (Cardano; three real roots by the trigonometric form).
    const double A = c[2] / c[3], B = c[1] / c[3], C = c[0] / c[3];
    const double p = B - A * A / 3.0;
    const double q = 2.0 * A * A * A / 27.0 - A * B / 3.0 + C;
    const double disc = q * q / 4.0 + p * p * p / 27.0;
    const double shift = -A / 3.0;
    if (disc > 0.0) {
      const double s = std::sqrt(disc);
      roots[n++] = std::cbrt(-q / 2.0 + s) + std::cbrt(-q / 2.0 - s) + shift;
    } else if (p == 0.0) {
      roots[n++] = shift;  // triple root
    } else {
      const double r = 2.0 * std::sqrt(-p / 3.0);
      const double arg = std::max(-1.0, std::min(1.0, 3.0 * q / (p * r)));
      const double phi = std::acos(arg) / 3.0;
      const double kThird = 2.0 * 3.14159265358979323846 / 3.0;
      for (int k = 0; k < 3; ++k) roots[n++] = r * std::cos(phi - k * kThird) + shift;
    }
  }
  // Two Newton steps on the original polynomial against the closed forms'
  // cancellation.
  for (int i = 0; i < n; ++i) {
    for (int it = 0; it < 2; ++it) {
      const double a = roots[i];
      const double f = ((c[3] * a + c[2]) * a + c[1]) * a + c[0];
      const double df = (3.0 * c[3] * a + 2.0 * c[2]) * a + c[1];
      if (df == 0.0) break;
      roots[i] = a - f / df;
    }
  }
  return n;
}

// Row i of A: x2^T F x1 = 0 as a linear equation in F's nine elements.
// Rows padded to ten so that the elimination runs on whole rows as pairs of
// doubles. False when a coordinate is not finite.
bool epipolarRows(const PointPair pairs[7], double a[7][10]) {
  for (int i = 0; i < 7; ++i) {
    const PointPair& p = pairs[i];
    if (!std::isfinite(p.x1) || !std::isfinite(p.y1) || !std::isfinite(p.x2) ||
        !std::isfinite(p.y2)) {
      return false;
    }
    const double row[9] = {p.x2 * p.x1, p.x2 * p.y1, p.x2, p.y2 * p.x1, p.y2 * p.y1,
                           p.y2,        p.x1,        p.y1, 1.0};
    std::copy(row, row + 9, a[i]);
    a[i][9] = 0.0;
  }
  return true;
}

// Gauss-Jordan with column pivoting: row by row, the pivot is the row's
// largest entry among the columns not yet chosen (the columns are swapped,
// `col` records their order). A becomes [I | B] in the permuted columns and
// the null space is spanned by the free columns. A row with no pivot left
// depends on the rows before it: it goes last and the rank drops. Full
// pivoting (searching every remaining row as well) gives the same null
// space to ~1e-13 at three times the search; the free columns are chosen by
// the data either way, which is what keeps an ill-conditioned choice of free
// columns away. Returns the rank (0 for a zero matrix).
int eliminate(double a[7][10], int col[9]) {
  // The largest entry, one running maximum per row: a single one chains 63
  // dependent comparisons. The maximum does not depend on the order.
  double row_largest[7];
  for (int i = 0; i < 7; ++i) {
    double m = 0.0;
    for (int j = 0; j < 9; ++j) m = std::max(m, std::fabs(a[i][j]));
    row_largest[i] = m;
  }
  double largest = 0.0;
  for (int i = 0; i < 7; ++i) largest = std::max(largest, row_largest[i]);
  if (!(largest > 0.0)) return 0;
  int rows = 7, rank = 0;
  while (rank < rows) {
    const int k = rank;
    int pc = k;
    double best = std::fabs(a[k][k]);
    for (int j = k + 1; j < 9; ++j) {
      const double v = std::fabs(a[k][j]);
      if (v > best) {
        best = v;
        pc = j;
      }
    }
    if (best <= 1e-10 * largest) {
      --rows;
      if (k != rows)
        for (int j = 0; j < 9; ++j) std::swap(a[k][j], a[rows][j]);
      continue;
    }
    if (pc != k) {
      for (int i = 0; i < 7; ++i) std::swap(a[i][k], a[i][pc]);
      std::swap(col[k], col[pc]);
    }
    // Whole rows: columns before k (pivot columns already done) are not
    // read again, so what the full width does to them is immaterial, and
    // every column from k on sees the same operations as a loop from k.
    const double inv = 1.0 / a[k][k];
    for (int j = 0; j < 10; ++j) a[k][j] *= inv;
    for (int i = 0; i < 7; ++i) {
      if (i == k || a[i][k] == 0.0) continue;
      const double f = a[i][k];
      for (int j = 0; j < 10; ++j) a[i][j] -= f * a[k][j];
    }
    ++rank;
  }
  return rank;
}

// The null-space vector of free column `f` of the eliminated A (the free
// columns are rank..8).
void nullVector(const double a[7][10], const int col[9], int rank, int f, double v[9]) {
  for (int j = rank; j < 9; ++j) v[col[j]] = j == f ? 1.0 : 0.0;
  for (int k = 0; k < rank; ++k) v[col[k]] = -a[k][f];
}

// Rank 6, a three-dimensional null space: degenerate for the 7-point
// algorithm. When the pairs do not move at all (x1 = x2: the robot stood
// still) every F of it is skew-symmetric, singular and fits every pair: keep
// the basis vectors that are singular.
int singularBasis(const double a[7][10], const int col[9], double solutions[3][9]) {
  int n = 0;
  for (int f = 6; f < 9; ++f) {
    double* v = solutions[n];
    nullVector(a, col, 6, f, v);
    double scale = 0.0;
    for (int j = 0; j < 9; ++j) scale = std::max(scale, std::fabs(v[j]));
    if (std::fabs(det3(v)) > 1e-9 * scale * scale * scale) continue;
    for (int j = 0; j < 9; ++j) v[j] /= scale;
    ++n;
  }
  return n;
}

// The singular F = F2 + a (F1 - F2) of a two-dimensional null space:
// det(F2 + a D), D = F1 - F2, is a cubic c0 + c1 a + c2 a^2 + c3 a^3 with
// c0 = det F2, c3 = det D; its values at a = 1 (det F1) and a = -1 give c1
// and c2. One solution per real root, scaled to a largest element of 1.
int singularPencil(const double f1[9], const double f2[9], double solutions[3][9]) {
  double d[9], fm[9];
  for (int j = 0; j < 9; ++j) {
    d[j] = f1[j] - f2[j];
    fm[j] = f2[j] - d[j];
  }
  const double p0 = det3(f2), p1 = det3(f1), pm1 = det3(fm), c3 = det3(d);
  const double coeffs[4] = {p0, 0.5 * (p1 - pm1) - c3, 0.5 * (p1 + pm1) - p0, c3};
  double roots[3];
  const int nroots = realCubicRoots(coeffs, roots);
  int n = 0;
  for (int r = 0; r < nroots; ++r) {
    double* f = solutions[n];
    double scale = 0.0;
    for (int j = 0; j < 9; ++j) {
      f[j] = f2[j] + roots[r] * d[j];
      scale = std::max(scale, std::fabs(f[j]));
    }
    if (!(scale > 0.0) || !std::isfinite(scale)) continue;
    for (int j = 0; j < 9; ++j) f[j] /= scale;
    ++n;
  }
  return n;
}

}  // namespace

int sevenPointFundamental(const PointPair pairs[7], double solutions[3][9]) {
  alignas(16) double a[7][10];
  if (!epipolarRows(pairs, a)) return 0;
  int col[9] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  const int rank = eliminate(a, col);
  if (rank < 6) return 0;  // degenerate sample
  if (rank == 6) return singularBasis(a, col, solutions);
  double f1[9], f2[9];
  nullVector(a, col, rank, 7, f1);
  nullVector(a, col, rank, 8, f2);
  return singularPencil(f1, f2, solutions);
}

bool eightPointFundamental(const PointPair* pairs, int n, double f[9]) {
  if (n < 8) return false;
  // A^T A, accumulated row by row (9 x 9, symmetric).
  cv::Matx<double, 9, 9> ata = cv::Matx<double, 9, 9>::zeros();
  for (int i = 0; i < n; ++i) {
    const PointPair& p = pairs[i];
    const double row[9] = {p.x2 * p.x1, p.x2 * p.y1, p.x2, p.y2 * p.x1, p.y2 * p.y1,
                           p.y2,        p.x1,        p.y1, 1.0};
    for (int r = 0; r < 9; ++r)
      for (int c = r; c < 9; ++c) ata(r, c) += row[r] * row[c];
  }
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < r; ++c) ata(r, c) = ata(c, r);
  for (int r = 0; r < 9; ++r)
    if (!std::isfinite(ata(r, r))) return false;
  // The smallest eigenvalue's vector: by inverse iteration, or by the full
  // decomposition when that does not settle (smallestEigenvector9).
  double smallest[9];
  if (!smallestEigenvector9(ata.val, smallest)) {
    cv::Matx<double, 9, 1> values;
    cv::Matx<double, 9, 9> vectors;
    if (!cv::eigen(ata, values, vectors)) return false;
    // Eigenvalues in descending order: the last row is the smallest's vector.
    for (int j = 0; j < 9; ++j) smallest[j] = vectors(8, j);
  }
  cv::Matx33d fm;
  for (int j = 0; j < 9; ++j) fm(j / 3, j % 3) = smallest[j];
  cv::Matx31d w;
  cv::Matx33d u, vt;
  cv::SVD::compute(fm, w, u, vt);
  const cv::Matx33d rank2 = u * cv::Matx33d::diag(cv::Vec3d(w(0), w(1), 0.0)) * vt;
  double scale = 0.0;
  for (int j = 0; j < 9; ++j) scale = std::max(scale, std::fabs(rank2(j / 3, j % 3)));
  if (!(scale > 0.0) || !std::isfinite(scale)) return false;
  for (int j = 0; j < 9; ++j) f[j] = rank2(j / 3, j % 3) / scale;
  return true;
}

double epipolarErrorSquared(const double f[9], const PointPair& p) {
  const EpipolarResidual e = epipolarResidual(f, p);
  if (!(e.normal > 0.0)) return std::numeric_limits<double>::infinity();
  return e.residual * e.residual / e.normal;
}

}  // namespace bowg
