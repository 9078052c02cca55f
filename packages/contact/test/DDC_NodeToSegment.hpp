// The conventional nonlinear node-to-segment (NTS) contact element with a
// Lagrange multiplier in closed form (doc/contact.md), and its registration
// in the element factory. The contact component evaluates every facet type,
// Line2 included, with the node-to-surface elements of
// DDC_SurfaceContactElement.hpp; on Line2 they equal this element to
// round-off (ctest contact_node_to_surface), which is its role now: the
// closed-form reference of the generic element.
//
// Geometry (2-D, straight 2-node master segment):
//   x = X + u,  t = x2 − x1,  L = |t|,  τ = t / L,
//   n = (t_y, −t_x) / L        unit outward master normal: the master body
//                              lies on the LEFT of 1 → 2, n points to the right,
//   ξ̄ = (x_s − x1)·t / L²     closest-point projection (0 at node 1, 1 at node 2),
//   g_N = n·(x_s − x̄(ξ̄)) = n·(x_s − x1) = cross(x_s − x1, t) / L.
// g_N > 0: separated, g_N < 0: penetration. The formula is smooth for every ξ̄
// (also slightly outside [0, 1], e.g. just after a segment switch); only a
// zero-length segment is singular.
//
// Potential (Fang & Izzuddin 2022, eq. 2): active Π_c = λ g_N, inactive
// (released) Π_c = ½ λ², which restrains λ to zero.
//
// SIGN CONVENTION. The element returns residual = ∂Π_c/∂(u, λ), the same
// "internal force" convention as the continuum elements (f_int = ∂U/∂u,
// equilibrium f_int = f_ext). The residual on the slave is therefore λ n and
// the contact force the slave FEELS is −λ n; on master node i the residual is
// −λ N_i(ξ̄) n and the force felt is +λ N_i n. A compressive contact has
// λ < 0 (paper's convention): the slave is pushed along +n, away from the
// master body, and the master nodes are pushed along −n, into their body.
#pragma once

#include <Eigen/Dense>
#include <Teuchos_ParameterList.hpp>

#include "DDC_ContactElement.hpp"
#include "DDC_ElementFactory.hpp"

namespace ddc {

/// Closest-point projection of a point onto the straight line through a
/// master segment (current configuration). For the NTS element, the contact
/// search and for freezing ξ^p, n^p at the end of a converged step.
struct SegmentProjection {
  double xi = 0.0;                               ///< ξ̄ = (x_s − x1)·t/|t|²; in [0,1] iff inside the segment
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();   ///< unit outward normal n = (t_y, −t_x)/|t|
  Eigen::Vector2d tangent = Eigen::Vector2d::Zero();  ///< unit tangent τ = t/|t|
  double length = 0.0;                           ///< |t| = |x2 − x1|
  double gap = 0.0;                              ///< g_N = n·(x_s − x̄(ξ̄)), > 0 separated
};

/// Project `xs` onto the segment x1 → x2 (current coordinates).
/// \throws InadmissibleDeformation if the segment has (numerically) zero length.
SegmentProjection projectOntoSegment(const Eigen::Vector2d& xs, const Eigen::Vector2d& x1,
                                     const Eigen::Vector2d& x2);

/// Conventional nonlinear node-to-segment element ("Node-To-Segment").
///
/// Nodes [slave s, master 1, master 2]; DOFs [u_s, u_1, u_2, λ] (7).
/// Residual and tangent are the exact first and second derivatives of Π_c,
/// including the variation of the projection ξ̄ and of the normal n
/// (consistent linearisation of the 2-D node-to-segment gap on a straight
/// segment, Wriggers, Computational Contact Mechanics, ch. 9; derivation in
/// DDC_NodeToSegment.cpp):
///
///   δg_N = Nᵀ δu,        N  = [ n; −(1−ξ̄) n; −ξ̄ n ]
///   Δδg_N = δuᵀ H Δu,    H  = −(N₁ T₀ᵀ + T₀ N₁ᵀ)/L − g_N N₁ N₁ᵀ / L²
///   with T₀ = [ τ; −(1−ξ̄) τ; −ξ̄ τ ],  N₁ = [ 0; −n; n ]  (N₁ᵀ δu = n·δt).
///
/// Active:   residual [λ N; g_N],  tangent [[λ H, N], [Nᵀ, 0]],  energy λ g_N.
/// Inactive: residual [0; λ],      tangent diag(0, …, 0, 1),     energy ½ λ².
/// No parameters. `state.frozenXi/frozenNormal` are ignored.
class NodeToSegmentElement : public ContactElement {
 public:
  /// Empty: the element has no parameters.
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();

  int numNodes() const override { return 3; }
  void computeContact(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u, const ContactPairState& state,
                      unsigned what, ElementResult& out) const override;
  /// g_N of the current configuration (independent of the state).
  double gap(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u, const ContactPairState& state) const override;
};

/// Register the contact element types in `f`:
///   "Node-To-Segment"        (3 nodes: slave, master 1, master 2),
///   "Decomposed NTS Slave"   (1 node: slave),
///   "Decomposed NTS Master"  (2 nodes: master 1, master 2).
/// None of them has parameters. The created objects are ContactElement's
/// (dynamic_pointer_cast to use computeContact / gap).
void registerContactElements(ElementFactory& f);

}  // namespace ddc
