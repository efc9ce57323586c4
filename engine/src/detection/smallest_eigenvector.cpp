#include "bowg/detection/smallest_eigenvector.h"

#include <cmath>

namespace bowg {
namespace {

const int kN = 9;
const int kMaxSteps = 60;
const double kShift = 1e-13;
const double kSettled = 1e-13;
const double kMargin = 1e-10;

// x = (L L^T)^-1 b, L lower-triangular (row-major), by forward and back
// substitution.
void choleskySolve(const double l[kN * kN], const double b[kN], double x[kN]) {
  double y[kN];
  for (int i = 0; i < kN; ++i) {
    double s = b[i];
    for (int k = 0; k < i; ++k) s -= l[i * kN + k] * y[k];
    y[i] = s / l[i * kN + i];
  }
  for (int i = kN - 1; i >= 0; --i) {
    double s = y[i];
    for (int k = i + 1; k < kN; ++k) s -= l[k * kN + i] * x[k];
    x[i] = s / l[i * kN + i];
  }
}

// The number of eigenvalues of the symmetric m below mu: the negative
// pivots of m - mu I = L D L^T (Sylvester's law of inertia); -1 when a pivot
// is 0.
int eigenvaluesBelow(const double m[kN * kN], double mu) {
  double l[kN * kN] = {}, d[kN];
  int negative = 0;
  for (int j = 0; j < kN; ++j) {
    double dj = m[j * kN + j] - mu;
    for (int k = 0; k < j; ++k) dj -= l[j * kN + k] * l[j * kN + k] * d[k];
    if (dj == 0.0) return -1;
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

}  // namespace

bool smallestEigenvector9(const double m[81], double v[9]) {
  double trace = 0.0;
  for (int i = 0; i < kN * kN; ++i)
    if (!std::isfinite(m[i])) return false;
  for (int i = 0; i < kN; ++i) trace += m[i * kN + i];
  if (!(trace > 0.0)) return false;  // PSD with zero trace: m = 0, every vector
  const double shift = kShift * trace;
  // Cholesky of m + shift I: L L^T, L lower-triangular.
  double l[kN * kN] = {};
  for (int j = 0; j < kN; ++j) {
    double d = m[j * kN + j] + shift;
    for (int k = 0; k < j; ++k) d -= l[j * kN + k] * l[j * kN + k];
    if (!(d > 0.0)) return false;
    const double ljj = std::sqrt(d);
    l[j * kN + j] = ljj;
    for (int i = j + 1; i < kN; ++i) {
      double s = m[i * kN + j];
      for (int k = 0; k < j; ++k) s -= l[i * kN + k] * l[j * kN + k];
      l[i * kN + j] = s / ljj;
    }
  }
  // Each step multiplies the smallest eigenvalue's component against the
  // next one's by (l8 + s) / (l9 + s): a well-posed fit settles in a few.
  // Start at the axis of the smallest pivot, where the factorisation
  // found m nearest to singular.
  int start = 0;
  for (int i = 1; i < kN; ++i)
    if (l[i * kN + i] < l[start * kN + start]) start = i;
  double x[kN];
  for (int i = 0; i < kN; ++i) v[i] = i == start ? 1.0 : 0.0;
  bool settled = false;
  for (int step = 0; step < kMaxSteps && !settled; ++step) {
    choleskySolve(l, v, x);
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
      const double d = std::fabs(next - v[i]);
      if (d > change) change = d;
      v[i] = next;
    }
    settled = change < kSettled;
  }
  if (!settled) return false;
  // A start without a component along the smallest eigenvalue's vector
  // settles at another one: v's Rayleigh quotient must be the only
  // eigenvalue below it plus a margin.
  double mv[kN];
  double rayleigh = 0.0;
  for (int i = 0; i < kN; ++i) {
    mv[i] = 0.0;
    for (int k = 0; k < kN; ++k) mv[i] += m[i * kN + k] * v[k];
    rayleigh += v[i] * mv[i];
  }
  const double margin = std::fmax(kMargin * trace, 1e-6 * std::fabs(rayleigh));
  return eigenvaluesBelow(m, rayleigh + margin) == 1;
}

}  // namespace bowg
