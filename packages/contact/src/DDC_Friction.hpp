// Coulomb friction of one contact pair, shared by the node-to-surface
// elements (DDC_NodeToSurface.hpp, DDC_DecomposedNodeToSurface.hpp) and the
// contact component's state update (doc/contact.md, "Friction").
//
// Unknowns of a frictional pair: the normal multiplier λ_n (λ_n < 0 in
// compression, p = −λ_n the normal force) and the tangential multipliers
// λ_t,α along a unit tangent basis τ_α (α = 1 in 2-D, 1..2 in 3-D); the
// tangential force on the slave node is −Σ λ_t,α τ_α. The slip of a step is
//
//   u_t,α = τ_α·[(x_s − x_s⁰) − Σ N_i(ξ)(x_i − x_i⁰)],
//
// x⁰ the positions at the step start (the slave's motion relative to the
// master material point it is paired with). Coulomb's law as a
// nonlinear complementarity function (Alart & Curnier 1991; Hüeber, Stadler
// & Wohlmuth 2008; Popp et al. 2010), with z = λ_t + c_t u_t and c_t > 0:
//
//   stick  |z| <  μ p   row  u_t = 0
//   slip   |z| >= μ p   row  (λ_t − μ p⁺ t̂)/c_t = 0,  t̂ = z/|z|, p⁺ = max(p, 0)
//
// in an active pair (open pairs restrain every multiplier to zero). The
// stick row is the tangential twin of the gap row; the slip row puts the
// tangential force on the cone in the direction of the current slip
// predictor. Both rows have length units, like the gap row. The slip row's
// exact derivatives (semismooth Newton): with P⊥ = I − t̂ t̂ᵀ,
//
//   ∂/∂λ_t = (I − (μ p⁺/|z|) P⊥)/c_t,  ∂/∂λ_n = μ t̂/c_t (p > 0),
//   ∂/∂u_t = −(μ p⁺/|z|) P⊥
//
// (in 2-D P⊥ = 0: the slip row is λ_t = μ p⁺ sign(z), linear).
#pragma once

#include <Eigen/Dense>
#include <array>
#include <vector>

namespace ddc {

/// The friction part of a pair's state handed to a contact element.
struct FrictionPairState {
  /// μ ≥ 0; 0: frictionless, the element has one multiplier (λ_n).
  double coefficient = 0.0;
  /// c_t > 0 of the complementarity function (force per length): decides
  /// stick or slip and scales the slip row.
  double stiffness = 1.0;
  /// An active pair sticks (true) or slips (false).
  bool stick = true;
  /// λ_t,α (entries past dim − 1 unused).
  std::array<double, 2> tangential{{0.0, 0.0}};
  /// Decomposed counterparts: the pair's whole slip u_t,α at the current
  /// iterate (both counterparts' parts; the slip row needs the whole of it).
  std::array<double, 2> slip{{0.0, 0.0}};
  /// Displacements of the element's nodes at the step start (numNodes x
  /// dim), the x⁰ of the slip; empty: no slip yet (u⁰ = u).
  Eigen::MatrixXd stepStart;
  /// Whether the pair has friction (tangential multipliers).
  bool frictional() const { return coefficient > 0.0; }
};

/// The tangential rows of an active frictional pair, linearised: row α is
/// residual_α + Σ_β slipDerivative(α,β) δu_t,β + lambdaNDerivative_α δλ_n
/// + Σ_β lambdaTDerivative(α,β) δλ_t,β (sizes: the number of tangent
/// directions).
struct FrictionRows {
  Eigen::VectorXd residual;
  Eigen::MatrixXd slipDerivative;
  Eigen::VectorXd lambdaNDerivative;
  Eigen::MatrixXd lambdaTDerivative;
};

/// The rows of the file comment for `nt` tangent directions.
/// \param slip u_t (nt entries); \param lambdaN λ_n; \param lambdaT λ_t (nt)
FrictionRows frictionRows(int nt, const double* slip, double lambdaN, const double* lambdaT,
                          const FrictionPairState& friction);

/// Whether an active pair sticks: |λ_t + c_t u_t| < μ p⁺ (file comment).
/// A slipping pair returns to stick only below (1 − kStickHysteresis) μ p⁺,
/// so a pair exactly on the cone does not flip with round-off.
bool sticks(int nt, const double* slip, double lambdaN, const double* lambdaT, const FrictionPairState& friction);

/// Whether a slipping pair's predictor z = λ_t + c_t u_t turns against the
/// force its slip row imposed (z·λ_t < 0, λ_t = μ p⁺ t̂ of the last
/// iterate): the solve with the force one way slid the node the other way.
/// When neither direction is consistent with the load the pair sticks, but
/// |z| stays above μ p⁺ and Newton cycles between the two directions with
/// no change of the stick/slip set (the Hertz octant's symmetry-plane
/// nodes in 3-D, doc/contact.md "Friction"). ContactPairing sticks a pair
/// whose slip reverses at two consecutive iterations (Coulomb's law sticks
/// a node whose slip reverses); if the stick iterate's force leaves the
/// cone it slips again, in that force's direction. A single reversal is
/// left alone: Newton's first iterates, or a sliding body's vibration
/// (the incline under FETI-DP), reverse a node's slip once and go on.
bool slipReverses(int nt, const double* slip, const double* lambdaT, const FrictionPairState& friction);

/// Relative margin of sticks() for a pair that slips.
constexpr double kStickHysteresis = 1e-8;

/// The unit tangent basis of the decomposed element, orthogonal to the unit
/// normal n: in 2-D τ = (−n_y, n_x) (the facet's direction of travel,
/// DDC_NodeToSurface.hpp); in 3-D τ_1 = the previous τ_1 made orthogonal to
/// n (a minimal rotation from step to step), or, when there is none or it
/// is nearly along n, the normalised projection of the coordinate axis
/// least aligned with n; τ_2 = n × τ_1.
std::array<Eigen::Vector3d, 2> tangentBasis(int dim, const Eigen::Vector3d& normal,
                                            const Eigen::Vector3d& previous = Eigen::Vector3d::Zero());

/// A slip row is held by the supports when what is left of its free
/// coefficients outside the span of the earlier rows' is at most this
/// fraction of the whole row (slipRowRedundant()). Only a slave node on a
/// support (a symmetry plane) has such a row, and there the deformed master
/// surface tilts the basis across the plane by about h times the surface's
/// curvature: measured up to 1.3e-7 on the Hertz octant and 1.1e-4 on the
/// Mindlin half model (doc/contact.md, "Mindlin"), each a nearly singular
/// system (multipliers of 1/tilt) when counted. A row that carries force
/// has a free part of order one (its slave node free along it).
constexpr double kHeldSlipRow = 1e-2;

/// Whether tangential row `alpha` of a pair holds nothing that the supports
/// and the rows before it do not: `rows` are the displacement coefficients
/// of the gap row and of the tangential rows on the free DOFs (prescribed
/// ones zeroed), `sizes` the norms of the same rows with the prescribed
/// DOFs; row 1 + alpha is redundant when what is left of it outside the
/// span of rows 0..alpha is at most `tolerance` times its size (a row with
/// no free coefficient at all, too). A slave node and its master point on
/// a symmetry plane have two free relative directions; once the master
/// surface tilts across the plane the gap row and both tangential rows
/// each have free coefficients, but they span only those two directions:
/// the last row is redundant, and the system singular unless its
/// multiplier is restrained (ContactPairing::restrainHeldSlip()). The
/// tolerance is relative to the whole row, not to its free part: a row
/// that the deformed master surface tilts off the plane (a free part of
/// 1e-7 to 1e-4 of the row, kHeldSlipRow) would otherwise count, and its
/// multiplier grow as the inverse of the tilt.
bool slipRowRedundant(const std::vector<Eigen::VectorXd>& rows, const std::vector<double>& sizes, int alpha,
                      double tolerance);

}  // namespace ddc
