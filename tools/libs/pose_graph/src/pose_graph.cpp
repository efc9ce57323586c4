// The pose graph and its Ceres problem (see pose_graph.h).
#include "bowg_pose_graph/pose_graph.h"

#include <ceres/ceres.h>
#include <ceres/version.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

namespace bowg {
namespace pose_graph {
namespace {

constexpr double kDegree = M_PI / 180.0;

void requirePositive(double v, const char* name) {
  if (!(v > 0.0) || !std::isfinite(v)) {
    throw std::invalid_argument(std::string("pose graph: ") + name + " must be a finite value > 0");
  }
}
void requireNonNegative(double v, const char* name) {
  if (!(v >= 0.0) || !std::isfinite(v)) {
    throw std::invalid_argument(std::string("pose graph: ") + name + " must be a finite value >= 0");
  }
}

/// Error of a measured relative pose b-in-a: position difference in a's
/// frame whitened by its square-root information (1/sigma for an isotropic
/// sigma), and the rotation difference (twice the vector part of the error
/// quaternion: the angle for small errors) over its sigma.
struct RelativePoseError {
  Eigen::Vector3d position;
  Eigen::Quaterniond rotation;
  Eigen::Matrix3d position_weight;
  double rotation_weight;
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW

  template <typename T>
  bool operator()(const T* pa, const T* qa, const T* pb, const T* qb, T* residual) const {
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> p_a(pa), p_b(pb);
    const Eigen::Map<const Eigen::Quaternion<T>> q_a(qa), q_b(qb);
    const Eigen::Quaternion<T> a_inv = q_a.conjugate();
    const Eigen::Matrix<T, 3, 1> p_ab = a_inv * (p_b - p_a);
    const Eigen::Quaternion<T> q_ab = a_inv * q_b;
    const Eigen::Quaternion<T> error = rotation.cast<T>().conjugate() * q_ab;
    const Eigen::Matrix<T, 3, 1> e = position_weight.cast<T>() * (p_ab - position.cast<T>());
    for (int i = 0; i < 3; ++i) {
      residual[i] = e[i];
      residual[3 + i] = T(2.0) * error.vec()[i] * T(rotation_weight);
    }
    return true;
  }
};

/// The same for the position only (a loop whose rotation is unknown).
struct RelativePositionError {
  Eigen::Vector3d position;
  Eigen::Matrix3d position_weight;
  EIGEN_MAKE_ALIGNED_OPERATOR_NEW

  template <typename T>
  bool operator()(const T* pa, const T* qa, const T* pb, T* residual) const {
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> p_a(pa), p_b(pb);
    const Eigen::Map<const Eigen::Quaternion<T>> q_a(qa);
    const Eigen::Matrix<T, 3, 1> p_ab = q_a.conjugate() * (p_b - p_a);
    const Eigen::Matrix<T, 3, 1> e = position_weight.cast<T>() * (p_ab - position.cast<T>());
    for (int i = 0; i < 3; ++i) residual[i] = e[i];
    return true;
  }
};

Eigen::Matrix3d isotropic(double sigma) { return Eigen::Matrix3d::Identity() / sigma; }

/// U with U^T U = covariance^-1: the residual U e has e^T covariance^-1 e as
/// its squared norm.
Eigen::Matrix3d squareRootInformation(const Eigen::Matrix3d& covariance) {
  const Eigen::LLT<Eigen::Matrix3d> llt(covariance.inverse());
  return llt.matrixL().transpose();
}

void setQuaternionManifold(ceres::Problem* problem, double* q) {
  // Ceres 2.1 replaced local parameterizations by manifolds (2.2 dropped
  // the former); legacy robots (Melodic: Ceres 1.13) have only the former.
#if CERES_VERSION_MAJOR > 2 || (CERES_VERSION_MAJOR == 2 && CERES_VERSION_MINOR >= 1)
  problem->SetManifold(q, new ceres::EigenQuaternionManifold);
#else
  problem->SetParameterization(q, new ceres::EigenQuaternionParameterization);
#endif
}

}  // namespace

void PoseGraphOptions::validate() const {
  requireNonNegative(odometry_position_fraction, "odometry_position_fraction");
  requirePositive(odometry_position_floor, "odometry_position_floor");
  requireNonNegative(odometry_rotation_deg_per_sqrt_m, "odometry_rotation_deg_per_sqrt_m");
  requirePositive(odometry_rotation_floor_deg, "odometry_rotation_floor_deg");
  requirePositive(loop_position_sigma, "loop_position_sigma");
  requirePositive(loop_rotation_sigma_deg, "loop_rotation_sigma_deg");
  requireNonNegative(loop_robust_sigmas, "loop_robust_sigmas");
  if (max_iterations < 1) throw std::invalid_argument("pose graph: max_iterations must be >= 1");
}

PoseGraph::PoseGraph(const PoseGraphOptions& options) : options_(options) { options_.validate(); }

std::size_t PoseGraph::addPose(const Eigen::Isometry3d& initial) {
  positions_.push_back(initial.translation());
  rotations_.push_back(Eigen::Quaterniond(initial.rotation()).normalized());
  return positions_.size() - 1;
}

void PoseGraph::addOdometry(std::size_t from, std::size_t to, const Eigen::Isometry3d& from_T_to) {
  if (from >= size() || to >= size() || from == to) {
    throw std::invalid_argument("pose graph: odometry edge " + std::to_string(from) + " -> " +
                                std::to_string(to) + " does not join two nodes of " +
                                std::to_string(size()));
  }
  odometry_.push_back({from, to, from_T_to});
}

void PoseGraph::addLoop(const LoopEdge& loop) {
  if (!(loop.extra_position_sigma >= 0.0) || !std::isfinite(loop.extra_position_sigma)) {
    throw std::invalid_argument("pose graph: a loop's extra position sigma must be finite and >= 0");
  }
  if (loop.has_position_covariance) {
    const Eigen::Matrix3d& c = loop.position_covariance;
    const Eigen::LLT<Eigen::Matrix3d> llt(c);
    if (!c.allFinite() || !c.isApprox(c.transpose(), 1e-9) || llt.info() != Eigen::Success) {
      throw std::invalid_argument(
          "pose graph: a loop's position covariance must be finite, symmetric and positive "
          "definite");
    }
  }
  if (loop.query >= size() || loop.match >= size() || loop.query == loop.match) {
    throw std::invalid_argument("pose graph: loop edge " + std::to_string(loop.query) + " -> " +
                                std::to_string(loop.match) + " does not join two nodes of " +
                                std::to_string(size()));
  }
  loops_.push_back(loop);
}

Eigen::Isometry3d PoseGraph::pose(std::size_t i) const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rotations_.at(i).normalized().toRotationMatrix();
  t.translation() = positions_.at(i);
  return t;
}

SolveSummary PoseGraph::optimize() {
  SolveSummary out;
  if (size() < 2) return out;
  ceres::Problem problem;
  for (const Odometry& o : odometry_) {
    const double length = o.from_T_to.translation().norm();
    const double sigma_p = options_.odometry_position_fraction * length + options_.odometry_position_floor;
    const double sigma_r = (options_.odometry_rotation_deg_per_sqrt_m * std::sqrt(length) +
                            options_.odometry_rotation_floor_deg) * kDegree;
    auto* cost = new ceres::AutoDiffCostFunction<RelativePoseError, 6, 3, 4, 3, 4>(
        new RelativePoseError{o.from_T_to.translation(), Eigen::Quaterniond(o.from_T_to.rotation()),
                              isotropic(sigma_p), 1.0 / sigma_r});
    problem.AddResidualBlock(cost, nullptr, positions_[o.from].data(), rotations_[o.from].coeffs().data(),
                             positions_[o.to].data(), rotations_[o.to].coeffs().data());
  }
  const double a = options_.loop_robust_sigmas;
  // Ceres takes ownership of each loss it is given (one per block).
  const auto loss = [a]() -> ceres::LossFunction* {
    return a > 0 ? new ceres::CauchyLoss(a) : nullptr;
  };
  for (const LoopEdge& l : loops_) {
    // A measured position brings its covariance; else the query is at the
    // match's place within loop_position_sigma.
    const Eigen::Matrix3d weight =
        l.has_position_covariance
            ? squareRootInformation(l.position_covariance + Eigen::Matrix3d::Identity() *
                                                                l.extra_position_sigma *
                                                                l.extra_position_sigma)
            : isotropic(std::hypot(options_.loop_position_sigma, l.extra_position_sigma));
    // The match is the older keyframe: the query's pose is expressed in it.
    if (l.has_rotation) {
      auto* cost =
          new ceres::AutoDiffCostFunction<RelativePoseError, 6, 3, 4, 3, 4>(new RelativePoseError{
              l.position, l.rotation, weight, 1.0 / (options_.loop_rotation_sigma_deg * kDegree)});
      problem.AddResidualBlock(cost, loss(), positions_[l.match].data(),
                               rotations_[l.match].coeffs().data(), positions_[l.query].data(),
                               rotations_[l.query].coeffs().data());
    } else {
      auto* cost = new ceres::AutoDiffCostFunction<RelativePositionError, 3, 3, 4, 3>(
          new RelativePositionError{l.position, weight});
      problem.AddResidualBlock(cost, loss(), positions_[l.match].data(),
                               rotations_[l.match].coeffs().data(), positions_[l.query].data());
    }
  }
  for (std::size_t i = 0; i < size(); ++i) {
    if (!problem.HasParameterBlock(positions_[i].data())) continue;  // a node without edges
    setQuaternionManifold(&problem, rotations_[i].coeffs().data());
  }
  // Gauge: the first pose anchors the graph.
  if (problem.HasParameterBlock(positions_[0].data())) {
    problem.SetParameterBlockConstant(positions_[0].data());
    problem.SetParameterBlockConstant(rotations_[0].coeffs().data());
  }
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options_.max_iterations;
  // Tight: a graph of a few thousand keyframes still solves in well under a
  // second, and the result does not depend on where the solver gave up.
  solver.function_tolerance = 1e-12;
  solver.gradient_tolerance = 1e-12;
  solver.parameter_tolerance = 1e-12;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  out.iterations = static_cast<int>(summary.iterations.size());
  out.initial_cost = summary.initial_cost;
  out.final_cost = summary.final_cost;
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.report = summary.BriefReport();
  for (Eigen::Quaterniond& q : rotations_) q.normalize();
  return out;
}

}  // namespace pose_graph
}  // namespace bowg
