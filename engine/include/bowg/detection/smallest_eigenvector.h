// The eigenvector of the smallest eigenvalue of a symmetric positive
// semi-definite 9x9 matrix: the least-squares solution of A f = 0, |f| = 1,
// from M = A^T A (the 8-point fundamental matrix, Hartley & Zisserman
// Sec. 11.1). Inverse iteration needs one L D L^T factorisation and a few
// triangular solves where a full eigen-decomposition (cv::eigen's Jacobi
// sweeps) computes all nine vectors: ~40,000 instructions a refit.
#pragma once

namespace bowg {

/// Writes to v (unit length; its sign is arbitrary) the eigenvector of the
/// smallest eigenvalue of the symmetric 9x9 matrix m (row-major), which must
/// be positive semi-definite. Inverse iteration on m + s I = L D L^T,
/// s = 1e-13 trace (so that every pivot is positive when the smallest
/// eigenvalue is 0),
/// from the axis of the factorisation's smallest pivot, until v changes by
/// less than 1e-13 in every element; then v's eigenvalue (its Rayleigh
/// quotient r) must be the only one below r + max(1e-10 trace, 1e-6 r)
/// (Sylvester's inertia of m - (r + margin) I), or v may be another
/// eigenvector. Returns false when it cannot tell: m has a non-finite
/// element, is 0 or not positive semi-definite (a non-positive pivot), the
/// iteration did not settle in 60 steps, or the inertia check fails (the
/// two smallest eigenvalues closer than the margin).
bool smallestEigenvector9(const double m[81], double v[9]);

}  // namespace bowg
