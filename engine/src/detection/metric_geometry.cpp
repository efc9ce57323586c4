// Two-view geometry of the metric translation (metric_translation.h): the
// neighbour's pose scaled by the odometer, triangulation, the refits.
#include "detection/metric_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>

namespace bowg {
namespace metric_geometry {

cv::Matx33d cameraMatrix(const CameraIntrinsics& k) {
  return cv::Matx33d(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
}

namespace {

// Reprojection error (px) of X (camera coordinates) against pixel p, or -1
// when X lies behind the camera.
double reprojectionError(const cv::Matx33d& K, const cv::Vec3d& X, double px, double py) {
  if (!(X[2] > 0)) return -1;
  const cv::Vec3d u = K * X;
  return std::hypot(u[0] / u[2] - px, u[1] / u[2] - py);
}

}  // namespace

NeighbourPose neighbourPose(const double r_mn[9], const double u[3], double baseline_m,
                            const cv::Matx33d& K) {
  NeighbourPose p;
  const cv::Matx33d r(r_mn);
  p.centre = cv::Vec3d(u[0], u[1], u[2]) * baseline_m;
  p.R = r.t();
  p.t = -(p.R * p.centre);
  cv::Matx34d Rt;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) Rt(i, j) = p.R(i, j);
    Rt(i, 3) = p.t[i];
  }
  p.projection = K * Rt;
  return p;
}

bool triangulate(const cv::Matx33d& K, const NeighbourPose& n, const Correspondence& mn,
                 double max_error_px, cv::Vec3d* X) {
  // Linear triangulation (the DLT's rows, with X = (x, y, z, 1): least
  // squares through the 3x3 normal equations; no SVD per point).
  // Linear triangulation (the DLT's rows, with X = (x, y, z, 1): least
  // squares through the 3x3 normal equations; no SVD per point).
  const cv::Matx34d P_m(K(0, 0), K(0, 1), K(0, 2), 0, K(1, 0), K(1, 1), K(1, 2), 0, K(2, 0),
                        K(2, 1), K(2, 2), 0);
  const cv::Matx34d* P[2] = {&P_m, &n.projection};
  const double px[2] = {mn.query_x, mn.match_x}, py[2] = {mn.query_y, mn.match_y};
  cv::Matx33d AtA = cv::Matx33d::zeros();
  cv::Vec3d Atb(0, 0, 0);
  for (int v = 0; v < 2; ++v) {
    for (int k = 0; k < 2; ++k) {
      const double p = k == 0 ? px[v] : py[v];
      // Row: p * P.row(2) - P.row(k).
      double row[4];
      for (int c = 0; c < 4; ++c) row[c] = p * (*P[v])(2, c) - (*P[v])(k, c);
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) AtA(i, j) += row[i] * row[j];
        Atb[i] -= row[i] * row[3];
      }
    }
  }
  if (!cv::solve(AtA, Atb, *X, cv::DECOMP_CHOLESKY)) return false;
  const double em = reprojectionError(K, *X, mn.query_x, mn.query_y);
  const double en = reprojectionError(K, n.R * *X + n.t, mn.match_x, mn.match_y);
  if (em < 0 || en < 0 || em > max_error_px || en > max_error_px) return false;
  const cv::Vec3d a = *X, b = *X - n.centre;
  const double cosang = a.dot(b) / (cv::norm(a) * cv::norm(b));
  return std::acos(std::min(1.0, cosang)) >= kMinParallaxRad;
}

namespace {

// Sampson distances (px) of the pairs (M pixel, N pixel) to the epipolar
// geometry of T_M_N = (R, u): F = K^-T [u]x R K^-1, x_M^T F x_N = 0.
void sampsonResiduals(const std::vector<Correspondence>& pairs, const cv::Matx33d& Kinv,
                      const cv::Matx33d& R, const cv::Vec3d& u, std::vector<double>* out) {
  const cv::Matx33d tx(0, -u[2], u[1], u[2], 0, -u[0], -u[1], u[0], 0);
  const cv::Matx33d F = Kinv.t() * tx * R * Kinv;
  out->resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const Correspondence& c = pairs[i];
    const cv::Vec3d xm(c.query_x, c.query_y, 1), xn(c.match_x, c.match_y, 1);
    const cv::Vec3d Fxn = F * xn, Ftxm = F.t() * xm;
    const double d = Fxn[0] * Fxn[0] + Fxn[1] * Fxn[1] + Ftxm[0] * Ftxm[0] + Ftxm[1] * Ftxm[1];
    (*out)[i] = d > 0 ? xm.dot(Fxn) / std::sqrt(d) : 0.0;
  }
}

}  // namespace

std::vector<Correspondence> agreeingPairs(const std::vector<Correspondence>& pairs,
                                          const cv::Matx33d& K, const double r[9],
                                          const double u[3], double thr) {
  std::vector<double> residuals;
  sampsonResiduals(pairs, K.inv(), cv::Matx33d(r), cv::Vec3d(u[0], u[1], u[2]), &residuals);
  std::vector<Correspondence> out;
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (std::abs(residuals[i]) <= thr) out.push_back(pairs[i]);
  }
  return out;
}

bool refitPose(const std::vector<Correspondence>& pairs, const cv::Matx33d& K, const double r0[9],
               const double u0[3], double rotation[9], double direction[3]) {
  if (pairs.size() < 5) return false;
  const cv::Matx33d Kinv = K.inv();
  cv::Matx33d R(r0);
  cv::Vec3d u = cv::normalize(cv::Vec3d(u0[0], u0[1], u0[2]));
  std::vector<double> res, trial;
  const auto cost = [](const std::vector<double>& v) {
    double c = 0;
    for (const double x : v) c += x * x;
    return c;
  };
  // The pose moved by p: R = exp(p0..2) R, u = normalise(u + p3 b1 + p4 b2).
  const auto moved = [](const cv::Matx33d& R0, const cv::Vec3d& u0v, const cv::Vec3d& b1,
                        const cv::Vec3d& b2, const double p[5], cv::Matx33d* Rp, cv::Vec3d* up) {
    cv::Matx33d dR;
    cv::Rodrigues(cv::Vec3d(p[0], p[1], p[2]), dR);
    *Rp = dR * R0;
    *up = cv::normalize(u0v + p[3] * b1 + p[4] * b2);
  };
  sampsonResiduals(pairs, Kinv, R, u, &res);
  double c0 = cost(res), lambda = 1e-3;
  const double h = 1e-6;
  for (int iteration = 0; iteration < 20; ++iteration) {
    // A basis of the directions orthogonal to u.
    const cv::Vec3d any = std::fabs(u[0]) < 0.9 ? cv::Vec3d(1, 0, 0) : cv::Vec3d(0, 1, 0);
    const cv::Vec3d b1 = cv::normalize(u.cross(any)), b2 = u.cross(b1);
    cv::Mat J(static_cast<int>(pairs.size()), 5, CV_64F);
    for (int k = 0; k < 5; ++k) {
      double p[5] = {0, 0, 0, 0, 0};
      p[k] = h;
      cv::Matx33d Rk;
      cv::Vec3d uk;
      moved(R, u, b1, b2, p, &Rk, &uk);
      sampsonResiduals(pairs, Kinv, Rk, uk, &trial);
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        J.at<double>(static_cast<int>(i), k) = (trial[i] - res[i]) / h;
      }
    }
    const cv::Mat r(res, false);
    const cv::Mat JtJ = J.t() * J, Jtr = J.t() * r;
    bool improved = false;
    while (lambda < 1e6) {
      cv::Mat A = JtJ.clone();
      for (int k = 0; k < 5; ++k) A.at<double>(k, k) *= 1 + lambda;
      cv::Mat step;
      if (!cv::solve(A, -Jtr, step, cv::DECOMP_CHOLESKY)) {
        lambda *= 10;
        continue;
      }
      cv::Matx33d Rt;
      cv::Vec3d ut;
      moved(R, u, b1, b2, step.ptr<double>(), &Rt, &ut);
      sampsonResiduals(pairs, Kinv, Rt, ut, &trial);
      const double c1 = cost(trial);
      if (c1 < c0) {
        R = Rt;
        u = ut;
        res.swap(trial);
        improved = c0 - c1 > 1e-12 * c0;
        c0 = c1;
        lambda = std::max(1e-7, lambda / 10);
        break;
      }
      lambda *= 10;
    }
    if (!improved) break;
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) rotation[3 * r + c] = R(r, c);
    direction[r] = u[r];
  }
  return true;
}

namespace {

cv::Point2d project(const cv::Matx33d& K, const cv::Vec3d& X) {
  const cv::Vec3d u = K * X;
  return cv::Point2d(u[0] / u[2], u[1] / u[2]);
}

}  // namespace

namespace {

// Residuals (N then Q, px) of point p for the query pose (Rq, tq).
void jointResiduals(const JointPoint& p, double rho, const cv::Matx33d& K, const cv::Matx33d& Kq,
                    const cv::Matx33d& Rq, const cv::Vec3d& tq, double r[4]) {
  const cv::Vec3d X = p.ray * (1.0 / rho);
  const cv::Point2d a = project(K, p.neighbour->R * X + p.neighbour->t) - p.n;
  const cv::Point2d b = project(Kq, Rq * X + tq) - p.q;
  r[0] = a.x;
  r[1] = a.y;
  r[2] = b.x;
  r[3] = b.y;
}

// Sum of the squared joint residuals at the query pose (rv, tv) and depths
// rho; infinite when a depth is not positive.
double jointCost(const std::vector<JointPoint>& points, const cv::Matx33d& K, const cv::Matx33d& Kq,
                 const cv::Vec3d& rv, const cv::Vec3d& tv, const std::vector<double>& rho) {
  cv::Matx33d R;
  cv::Rodrigues(rv, R);
  double c = 0, r[4];
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!(rho[i] > 0)) return std::numeric_limits<double>::infinity();
    jointResiduals(points[i], rho[i], K, Kq, R, tv, r);
    c += r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + r[3] * r[3];
  }
  return c;
}

// The Gauss-Newton system at one pose and set of depths (numeric Jacobians):
// the pose block S and its gradient g, and per point the depth's diagonal
// term h_rr, its gradient g_r and its coupling with the pose h_pr.
struct JointSystem {
  cv::Matx66d S = cv::Matx66d::zeros();
  cv::Vec6d g = cv::Vec6d(0, 0, 0, 0, 0, 0);
  std::vector<double> h_rr, g_r;
  std::vector<cv::Vec6d> h_pr;
};

JointSystem lineariseJointly(const std::vector<JointPoint>& points, const cv::Matx33d& K,
                             const cv::Matx33d& Kq, const cv::Vec3d& rvec, const cv::Vec3d& tvec,
                             const std::vector<double>& rho) {
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  JointSystem s;
  s.h_rr.resize(rho.size());
  s.g_r.resize(rho.size());
  s.h_pr.resize(rho.size());
  // The pose perturbed along each of its 6 coordinates (numeric Jacobian).
  const double h = 1e-7;
  cv::Matx33d Rk[6];
  cv::Vec3d tk[6];
  for (int k = 0; k < 6; ++k) {
    cv::Vec3d rv = rvec;
    tk[k] = tvec;
    if (k < 3)
      rv[k] += h;
    else
      tk[k][k - 3] += h;
    cv::Rodrigues(rv, Rk[k]);
  }
  for (std::size_t i = 0; i < rho.size(); ++i) {
    const JointPoint& p = points[i];
    double r[4], d[4];
    jointResiduals(p, rho[i], K, Kq, R, tvec, r);
    const double hr = 1e-6 * rho[i];
    jointResiduals(p, rho[i] + hr, K, Kq, R, tvec, d);
    double Jr[4];
    for (int k = 0; k < 4; ++k) Jr[k] = (d[k] - r[k]) / hr;
    // The pose moves the query's residuals (2, 3) only.
    double Jp[2][6];
    for (int k = 0; k < 6; ++k) {
      jointResiduals(p, rho[i], K, Kq, Rk[k], tk[k], d);
      Jp[0][k] = (d[2] - r[2]) / h;
      Jp[1][k] = (d[3] - r[3]) / h;
    }
    s.h_rr[i] = Jr[0] * Jr[0] + Jr[1] * Jr[1] + Jr[2] * Jr[2] + Jr[3] * Jr[3];
    s.g_r[i] = Jr[0] * r[0] + Jr[1] * r[1] + Jr[2] * r[2] + Jr[3] * r[3];
    for (int a = 0; a < 6; ++a) {
      s.g[a] += Jp[0][a] * r[2] + Jp[1][a] * r[3];
      s.h_pr[i][a] = Jp[0][a] * Jr[2] + Jp[1][a] * Jr[3];
      for (int b = 0; b < 6; ++b) s.S(a, b) += Jp[0][a] * Jp[0][b] + Jp[1][a] * Jp[1][b];
    }
  }
  return s;
}

// The damped normal equations of `s` (damping lambda), the depths eliminated
// (Schur complement): the pose step `dp` and the depths after it, `rho_t`.
// False when the reduced pose system cannot be solved.
bool dampedJointStep(const JointSystem& s, const std::vector<double>& rho, double lambda,
                     cv::Vec6d* dp, std::vector<double>* rho_t) {
  cv::Matx66d A = s.S;
  cv::Vec6d b = s.g;
  for (int a = 0; a < 6; ++a) A(a, a) *= 1 + lambda;
  std::vector<double> hd(rho.size());
  for (std::size_t i = 0; i < rho.size(); ++i) {
    hd[i] = s.h_rr[i] * (1 + lambda) + 1e-12;
    A -= s.h_pr[i] * s.h_pr[i].t() * (1.0 / hd[i]);
    b -= s.h_pr[i] * (s.g_r[i] / hd[i]);
  }
  if (!cv::solve(A, -b, *dp, cv::DECOMP_CHOLESKY)) return false;
  rho_t->resize(rho.size());
  for (std::size_t i = 0; i < rho.size(); ++i) {
    (*rho_t)[i] = rho[i] - (s.g_r[i] + s.h_pr[i].dot(*dp)) / hd[i];
  }
  return true;
}

}  // namespace

bool refineJointly(std::vector<JointPoint>* points, const cv::Matx33d& K, const cv::Matx33d& Kq,
                   cv::Vec3d* rvec, cv::Vec3d* tvec) {
  std::vector<double> rho(points->size());
  for (std::size_t i = 0; i < rho.size(); ++i) rho[i] = (*points)[i].rho;
  double cost = jointCost(*points, K, Kq, *rvec, *tvec, rho), lambda = 1e-4;
  if (!std::isfinite(cost)) return false;
  for (int iteration = 0; iteration < 10; ++iteration) {
    const JointSystem s = lineariseJointly(*points, K, Kq, *rvec, *tvec, rho);
    // Levenberg-Marquardt: the damping grows until a step lowers the cost.
    bool improved = false;
    while (lambda < 1e8) {
      cv::Vec6d dp;
      std::vector<double> rho_t;
      if (!dampedJointStep(s, rho, lambda, &dp, &rho_t)) {
        lambda *= 10;
        continue;
      }
      const cv::Vec3d rv = *rvec + cv::Vec3d(dp[0], dp[1], dp[2]);
      const cv::Vec3d tv = *tvec + cv::Vec3d(dp[3], dp[4], dp[5]);
      const double c1 = jointCost(*points, K, Kq, rv, tv, rho_t);
      if (c1 < cost) {
        improved = cost - c1 > 1e-10 * cost;
        cost = c1;
        *rvec = rv;
        *tvec = tv;
        rho.swap(rho_t);
        lambda = std::max(1e-8, lambda / 10);
        break;
      }
      lambda *= 10;
    }
    if (!improved) break;
  }
  for (std::size_t i = 0; i < rho.size(); ++i) (*points)[i].rho = rho[i];
  return std::isfinite(cost);
}

}  // namespace metric_geometry
}  // namespace bowg
