// The decomposed node-to-segment element of Fang & Izzuddin (2022): the
// slave and master counterparts, which may live in different subdomains and
// share only the contact Lagrange multiplier λ (doc/contact.md), in closed
// form for a straight 2-node segment: the reference of the generic
// counterparts of DDC_DecomposedNodeToSurface.hpp, which the contact
// component evaluates on every facet type.
//
// With ξ^p and n^p frozen on the last converged configuration (paper eq. 1)
// the gap is linear in the displacements:
//
//   g_N = n^p·( x_s − Σ_i N_i(ξ^p) x_i ),   N_1 = 1 − ξ^p,  N_2 = ξ^p,  x = X + u,
//
// and splits into a slave part g_s = n^p·x_s and a master part
// g_m = −n^p·Σ N_i x_i, g_N = g_s + g_m. Each counterpart's potential is λ
// times its part (active); the release term ½λ² lives in the slave
// counterpart only, so the sum of both counterparts is exactly the
// decomposed element (paper eq. 2 with the frozen gap):
//
//   slave  active:  Π = λ n^p·x_s           inactive: ½ λ²
//   master active:  Π = −λ n^p·Σ N_i x_i    inactive: 0
//
// Residual = ∂Π/∂(u, λ) (same sign convention as NodeToSegmentElement: the
// residual on the slave is λ n^p, the force it feels −λ n^p; λ < 0 is
// compression). The LM-row residual of each counterpart is its partial gap;
// the analysis assembles the LM rows of both counterparts on the LM map, and
// their sum is g_N. In FETI terms an active pair is one row of the
// constraint operator B: coefficients n^p on the slave DOFs and −N_i n^p on
// master node i (see constraintCoefficients()).
//
// gap() OF A COUNTERPART RETURNS ITS PART (g_s or g_m), consistent with its
// LM-row residual; the pair's gap is the sum of both, or decomposedGap()
// when both nodes' coordinates are at hand.
//
// state.frozenNormal must be a unit vector whenever it is used (active
// evaluation, gap()): a default (zero) normal throws std::invalid_argument
// instead of silently producing no contact.
#pragma once

#include <Eigen/Dense>
#include <Teuchos_ParameterList.hpp>

#include "DDC_ContactElement.hpp"

namespace ddc {

/// Slave counterpart ("Decomposed NTS Slave"). Nodes [slave]; DOFs [u_s, λ].
/// Active: residual [λ n^p; n^p·x_s], tangent [[0, n^p], [n^pᵀ, 0]].
/// Inactive: residual [0, 0; λ], tangent diag(0, 0, 1). No parameters.
class DecomposedNtsSlaveElement : public ContactElement {
 public:
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  /// Coefficients c of the pair's constraint row on the slave DOFs:
  /// g_s = c·x_s = c·(X_s + u_s), c = n^p.
  /// \throws std::invalid_argument if state.frozenNormal is not a unit vector.
  static Eigen::Vector2d constraintCoefficients(const ContactPairState& state);

  int numNodes() const override { return 1; }
  void computeContact(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u, const ContactPairState& state,
                      unsigned what, ElementResult& out) const override;
  /// The slave part of the frozen gap, g_s = n^p·x_s (not the pair's gap).
  double gap(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u, const ContactPairState& state) const override;
};

/// Master counterpart ("Decomposed NTS Master"). Nodes [master 1, master 2];
/// DOFs [u_1, u_2, λ].
/// Active: residual [−λ N_1 n^p; −λ N_2 n^p; −n^p·Σ N_i x_i], tangent with only
/// the λ row/column [−N_1 n^p; −N_2 n^p] non-zero.
/// Inactive: zero energy, residual and tangent. No parameters.
class DecomposedNtsMasterElement : public ContactElement {
 public:
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  /// Coefficients c of the pair's constraint row on the master DOFs
  /// [u_1x, u_1y, u_2x, u_2y]: g_m = c·(X + u), c = [−N_1 n^p; −N_2 n^p].
  /// \throws std::invalid_argument if state.frozenNormal is not a unit vector.
  static Eigen::Vector4d constraintCoefficients(const ContactPairState& state);

  int numNodes() const override { return 2; }
  void computeContact(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u, const ContactPairState& state,
                      unsigned what, ElementResult& out) const override;
  /// The master part of the frozen gap, g_m = −n^p·Σ N_i(ξ^p) x_i (not the pair's gap).
  double gap(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u, const ContactPairState& state) const override;
};

/// The pair's frozen gap g_N = n^p·(x_s − (1−ξ^p) x_1 − ξ^p x_2) from current
/// coordinates x = X + u (= slave gap() + master gap()).
/// \throws std::invalid_argument if state.frozenNormal is not a unit vector.
double decomposedGap(const Eigen::Vector2d& xs, const Eigen::Vector2d& x1, const Eigen::Vector2d& x2,
                     const ContactPairState& state);

}  // namespace ddc
