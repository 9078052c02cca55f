// Coulomb friction rows and the decomposed element's tangent basis (see
// DDC_Friction.hpp).
#include "DDC_Friction.hpp"

#include <algorithm>
#include <cmath>

namespace ddc {

namespace {

/// z = λ_t + c_t u_t.
Eigen::VectorXd predictor(int nt, const double* slip, const double* lambdaT, const FrictionPairState& f) {
  Eigen::VectorXd z(nt);
  for (int a = 0; a < nt; ++a) z[a] = lambdaT[a] + f.stiffness * slip[a];
  return z;
}

}  // namespace

FrictionRows frictionRows(int nt, const double* slip, double lambdaN, const double* lambdaT,
                          const FrictionPairState& f) {
  FrictionRows r;
  if (f.stick) {
    r.residual = Eigen::Map<const Eigen::VectorXd>(slip, nt);
    r.slipDerivative = Eigen::MatrixXd::Identity(nt, nt);
    r.lambdaNDerivative = Eigen::VectorXd::Zero(nt);
    r.lambdaTDerivative = Eigen::MatrixXd::Zero(nt, nt);
    return r;
  }
  const Eigen::VectorXd z = predictor(nt, slip, lambdaT, f);
  const double zeta = z.norm();
  const double p = std::max(-lambdaN, 0.0);
  const double ct = f.stiffness, mu = f.coefficient;
  const Eigen::Map<const Eigen::VectorXd> lt(lambdaT, nt);
  // No slip predictor (z = 0, possible only at p = 0): no direction, the
  // row restrains λ_t to μ p⁺ t̂ = 0.
  const Eigen::VectorXd t = zeta > 0.0 ? Eigen::VectorXd(z / zeta) : Eigen::VectorXd::Zero(nt);
  const Eigen::MatrixXd perp = Eigen::MatrixXd::Identity(nt, nt) - t * t.transpose();
  const double ratio = zeta > 0.0 ? mu * p / zeta : 0.0;
  r.residual = (lt - mu * p * t) / ct;
  r.lambdaTDerivative = (Eigen::MatrixXd::Identity(nt, nt) - ratio * perp) / ct;
  r.lambdaNDerivative = -lambdaN > 0.0 ? Eigen::VectorXd(mu * t / ct) : Eigen::VectorXd::Zero(nt);
  r.slipDerivative = -ratio * perp;
  return r;
}

bool sticks(int nt, const double* slip, double lambdaN, const double* lambdaT, const FrictionPairState& f) {
  const double bound = f.coefficient * std::max(-lambdaN, 0.0) * (f.stick ? 1.0 : 1.0 - kStickHysteresis);
  return predictor(nt, slip, lambdaT, f).norm() < bound;
}

bool slipReverses(int nt, const double* slip, const double* lambdaT, const FrictionPairState& f) {
  return !f.stick && predictor(nt, slip, lambdaT, f).dot(Eigen::Map<const Eigen::VectorXd>(lambdaT, nt)) < 0.0;
}

std::array<Eigen::Vector3d, 2> tangentBasis(int dim, const Eigen::Vector3d& n, const Eigen::Vector3d& previous) {
  if (dim == 2) return {Eigen::Vector3d(-n.y(), n.x(), 0.0), Eigen::Vector3d::Zero()};
  Eigen::Vector3d t1 = previous - previous.dot(n) * n;
  // Nearly along n (or none): start from the axis least aligned with n.
  if (!(t1.norm() > 0.1 * previous.norm()) || previous.norm() == 0.0) {
    int axis = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(n[c]) < std::abs(n[axis])) axis = c;
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(axis);
    t1 = e - e.dot(n) * n;
  }
  t1.normalize();
  return {t1, n.cross(t1)};
}

bool slipRowRedundant(const std::vector<Eigen::VectorXd>& rows, const std::vector<double>& sizes, int alpha,
                      double tolerance) {
  // Gram-Schmidt over the rows before it, skipping those already in the
  // span (to the tolerance, of their own size with the prescribed DOFs).
  std::vector<Eigen::VectorXd> basis;
  for (int r = 0; r <= alpha; ++r) {
    Eigen::VectorXd v = rows[r];
    for (const auto& b : basis) v -= b.dot(v) * b;
    if (v.norm() > tolerance * sizes[r] && v.norm() > 0.0) basis.push_back(v / v.norm());
  }
  Eigen::VectorXd v = rows[1 + alpha];
  for (const auto& b : basis) v -= b.dot(v) * b;
  return v.norm() <= tolerance * sizes[1 + alpha];
}

}  // namespace ddc
