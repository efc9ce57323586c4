#include "bowg/detection/smallest_eigenvector.h"

#include <cmath>

namespace bowg {
namespace {

const int kN = 9;
const int kMaxSteps = 60;
const double kShift = 1e-13;  // times the trace
const double kSettled = 1e-13;
const double kMargin = 1e-10;

// m - mu I = L D L^T, L unit lower-triangular (row-major, its diagonal
// not stored), D = diag(d). Returns the number of negative pivots, which by
// Sylvester's law of inertia is the number of eigenvalues of m below mu;
// -1 when a pivot is 0 or not finite.
int factorShifted(const double m[kN * kN], double mu, double l[kN * kN], double d[kN]) {
  int negative = 0;
  for (int j = 0; j < kN; ++j) {
    double dj = m[j * kN + j] - mu;
    for (int k = 0; k < j; ++k) dj -= l[j * kN + k] * l[j * kN + k] * d[k];
    if (dj == 0.0 || !std::isfinite(dj)) return -1;
    d[j] = dj;
    if (dj < 0.0) ++negative;
    for (int i = j + 1; i < kN; ++i) {
      double s = m[i * kN + j];
      for (int k = 0; k < j; ++k) s -= l[i * kN + k] * l[j * kN + k] * d[k];
      l[i * kN + j] = s / dj;
    }
  }
  return negative;
}

// x = (L D L^T)^-1 b: forward substitution, the diagonal, back substitution.
void factorSolve(const double l[kN * kN], const double d[kN], const double b[kN], double x[kN]) {
  double y[kN];
  for (int i = 0; i < kN; ++i) {
    double s = b[i];
    for (int k = 0; k < i; ++k) s -= l[i * kN + k] * y[k];
    y[i] = s;
  }
  for (int i = kN - 1; i >= 0; --i) {
    double s = y[i] / d[i];
    for (int k = i + 1; k < kN; ++k) s -= l[k * kN + i] * x[k];
    x[i] = s;
  }
}

}  // namespace

bool smallestEigenvector9(const double m[81], double v[9]) {
  double trace = 0.0;
  for (int i = 0; i < kN * kN; ++i)
    if (!std::isfinite(m[i])) return false;
  for (int i = 0; i < kN; ++i) trace += m[i * kN + i];
  if (!(trace > 0.0)) return false;  // PSD with zero trace: m = 0, every vector
  // m + shift I = L D L^T with every pivot positive, or m is not positive
  // semi-definite.
  double l[kN * kN], d[kN];
  if (factorShifted(m, -kShift * trace, l, d) != 0) return false;
  // Each step shrinks the next eigenvector's component against the
  // smallest's by (lambda_9 + shift) / (lambda_8 + shift): a well-posed fit
  // settles in a few.
  // Start at the axis of the smallest pivot, where the factorisation
  // found m nearest to singular.
  int start = 0;
  for (int i = 1; i < kN; ++i)
    if (d[i] < d[start]) start = i;
  double x[kN];
  for (int i = 0; i < kN; ++i) v[i] = i == start ? 1.0 : 0.0;
  bool settled = false;
  for (int step = 0; step < kMaxSteps && !settled; ++step) {
    factorSolve(l, d, v, x);
    double norm = 0.0;
    for (int i = 0; i < kN; ++i) norm += x[i] * x[i];
    norm = std::sqrt(norm);
    if (!(norm > 0.0) || !std::isfinite(norm)) return false;
    // The iterate may flip sign from step to step: compare with its sign
    // aligned.
    double dot = 0.0;
    for (int i = 0; i < kN; ++i) dot += x[i] * v[i];
    const double sign = dot < 0.0 ? -1.0 : 1.0;
    double change = 0.0;
    for (int i = 0; i < kN; ++i) {
      const double next = sign * x[i] / norm;
      const double moved = std::fabs(next - v[i]);
      if (moved > change) change = moved;
      v[i] = next;
    }
    settled = change < kSettled;
  }
  if (!settled) return false;
  // A start without a component along the smallest eigenvalue's vector
  // settles at another one: v's Rayleigh quotient must be the only
  // eigenvalue below it plus a margin.
  double rayleigh = 0.0;
  for (int i = 0; i < kN; ++i) {
    double mv = 0.0;
    for (int k = 0; k < kN; ++k) mv += m[i * kN + k] * v[k];
    rayleigh += v[i] * mv;
  }
  const double margin = std::fmax(kMargin * trace, 1e-6 * std::fabs(rayleigh));
  return factorShifted(m, rayleigh + margin, l, d) == 1;
}

}  // namespace bowg
