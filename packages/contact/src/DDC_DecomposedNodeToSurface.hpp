// The decomposed node-to-surface element of Fang & Izzuddin (2022) on a
// facet of any type (paper Figure 1: a slave node and an 8-node facet): the
// slave and master counterparts with the projection ξ^p and normal n^p frozen
// at the last converged configuration (paper eq. 1), meeting only on the
// contact multiplier λ (doc/contact.md), on straight and curved segments
// (Line2, Line3) and on 3-D facets (Tri3, Tri6, Quad4, Quad8, Quad9); on
// Line2 the tests check it against the closed-form decomposed
// node-to-segment counterparts (packages/contact/test):
//
//   g_N = n^p·( x_s − Σ_i N_i(ξ^p) x_i ) = g_s + g_m,
//   slave  active:  Π = λ n^p·x_s               inactive: ½ λ²
//   master active:  Π = −λ n^p·Σ N_i(ξ^p) x_i   inactive: 0
//
// The gap is linear in the displacements, so residuals are λ times fixed
// coefficients and tangents have only the multiplier row and column; one row
// of the FETI-DP constraint operator per active pair (constraintRow()).
// Freeze ξ^p, n^p from projectOntoFacet() (DDC_NodeToSurface.hpp) at the end
// of each converged step: there the frozen gap and its gradient equal the
// conventional element's.
//
// With Coulomb friction (DDC_Friction.hpp) the tangent basis τ^p_α is frozen
// with n^p, so the slip of a step, u_t,α = τ^p_α·(x_s − x_s⁰) −
// τ^p_α·Σ N_i(ξ^p)(x_i − x_i⁰), is linear too and splits into the two
// counterparts like the gap: each adds Σ λ_t,α c_t,α to its residual (c_t,α
// = τ^p_α on the slave, −N_i(ξ^p) τ^p_α on the master). A sticking pair's
// tangential rows are its parts of u_t (they add up to u_t = 0, rows of the
// constraint operator like the gap's); a slipping pair's rows are
// (λ_t − μ p⁺ t̂)/c_t, whose value and multiplier derivatives the slave
// counterpart alone carries, from the pair's whole slip in the state, and
// whose slip derivative each counterpart applies to its own c_t,α.
#pragma once

#include <Eigen/Dense>
#include <array>

#include "DDC_ContactState.hpp"
#include "DDC_ReferenceCell.hpp"

namespace ddc {

/// The frozen geometry of one pair (paper eq. 1).
struct FrozenFacetProjection {
  std::array<double, 2> xi{{0.0, 0.0}};  ///< ξ^p on the master facet (its reference coordinates)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit n^p (z = 0 in 2-D)
  /// The unit tangent basis τ^p_α orthogonal to n^p (tangentBasis(),
  /// DDC_Friction.hpp; τ_2 = 0 in 2-D), read by frictional pairs only.
  std::array<Eigen::Vector3d, 2> tangent{{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}};
};

/// One counterpart of the decomposed element on a facet type.
/// Slave: nodes [slave], DOFs [u_s, λ]. Master: nodes [facet nodes], DOFs
/// [u_1, ..., u_m, λ] (node-major, dim per node, λ last); a frictional pair
/// appends λ_t (dim − 1 of them) after λ.
class DecomposedSurfaceCounterpart {
 public:
  /// \param facet the master facet type (Line2, Line3, Tri3, Tri6, Quad4, Quad8, Quad9)
  /// \param master true: the master counterpart; false: the slave counterpart
  /// \throws std::invalid_argument for a cell type that is not a facet.
  DecomposedSurfaceCounterpart(CellType facet, bool master);
  int dim() const { return dim_; }
  int numNodes() const { return numNodes_; }
  /// DOFs without friction (a frictional pair has dim − 1 more).
  int numDofs() const { return dim_ * numNodes_ + 1; }
  bool isMaster() const { return master_; }
  /// The coefficients c of this counterpart's part of the gap,
  /// g_part = c·(X + u) over its nodal DOFs (slave: n^p; master: −N_i(ξ^p) n^p).
  /// \throws std::invalid_argument if the frozen normal is not a unit vector.
  Eigen::VectorXd constraintRow(const FrozenFacetProjection& frozen) const;
  /// The coefficients of this counterpart's part of the slip u_t,α over its
  /// nodal DOFs (slave: τ^p_α; master: −N_i(ξ^p) τ^p_α).
  /// \throws std::invalid_argument if τ^p_α is not a unit vector orthogonal to n^p.
  Eigen::VectorXd slipRow(const FrozenFacetProjection& frozen, int alpha) const;
  /// This counterpart's part of the frozen gap.
  double gapPart(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u, const FrozenFacetProjection& frozen) const;
  /// Energy, residual, tangent (see the top of this file); `state` gives the
  /// multiplier and the active flag.
  void computeContact(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u, const FrozenFacetProjection& frozen,
                      const ContactPairState& state, unsigned what, ElementResult& out) const;

 private:
  /// The tangential rows and terms of a frictional pair (the file comment).
  void addFriction(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u, const FrozenFacetProjection& frozen,
                   const ContactPairState& state, unsigned what, ElementResult& out) const;

  CellType facet_;
  bool master_;
  int dim_, numNodes_;
};

}  // namespace ddc
