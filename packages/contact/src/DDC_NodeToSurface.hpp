// The conventional nonlinear node-to-surface (NTS) contact element on a
// curved facet of any type — the monolithic reference of doc/contact.md in
// 3-D, and on 3-node segments in 2-D. A slave node and a master facet:
//
//   facet types   2-D: Line2, Line3 (sides of Quad4 / Quad9)
//                 3-D: Tri3, Tri6, Quad4, Quad8, Quad9 (faces of Tet4, Tet10,
//                      Hex8, Hex20, Hex27), nodes in the order of
//                      DDC_ReferenceCell.hpp with outward orientation
//   x(ξ)          = Σ N_i(ξ) x_i,  x = X + u,  ξ = ξ (2-D) or (ξ, η) (3-D)
//   a_α           = ∂x/∂ξ_α (tangents)
//   n             3-D: a_1 × a_2 / |a_1 × a_2|, outward for an outward facet;
//                 2-D: (a_y, −a_x) / |a|, the master body on the left of the
//                 direction of travel
//   ξ̄             closest-point projection: (x_s − x(ξ̄))·a_α(ξ̄) = 0, by a
//                 local Newton iteration on ξ (projectOntoFacet())
//   g_N           = n(ξ̄)·(x_s − x(ξ̄)), > 0 separated, < 0 penetration
//
// Potential (Fang & Izzuddin 2022, eq. 2): active Π_c = λ g_N, released
// Π_c = ½ λ². Residual = ∂Π_c/∂(u, λ), the "internal force" convention of
// the continuum elements (f_int = ∂U/∂u): the residual on the slave is λ n and
// the force it feels −λ n; λ < 0 in compression (Fang & Izzuddin), so a
// compressive contact pushes the slave along +n, away from the master body.
//
// Linearisation. At the closest point, δg_N = G·δu with G = [n; −N_i(ξ̄) n]
// (the tangential terms vanish because x_s − x(ξ̄) is normal to the facet, and
// n·δn = 0). The tangent λ ∂G/∂u carries the variation of ξ̄ and of n
// (Wriggers, Computational Contact Mechanics, ch. 9; Laursen, ch. 5). It is
// computed exactly by forward automatic differentiation (Sacado): the
// converged projection ξ̄ is made a function of the nodal positions by one
// Newton step in AD arithmetic from ξ̄, ξ̄(x) = ξ̄ − J⁻¹ f(ξ̄, x) with f_α =
// −(x_s − x(ξ))·a_α and J = ∂f/∂ξ at ξ̄, whose derivative is the implicit
// derivative dξ̄/dx = −J⁻¹ ∂f/∂x exactly (f = 0 there); then G is evaluated
// at ξ̄(x). No second derivatives of the shape functions are written by hand.
//
// Coulomb friction (DDC_Friction.hpp; doc/contact.md, "Friction"): a pair
// with a friction coefficient has the tangential multipliers λ_t after λ and
// the potential λ g_N + λ_t·u_t, u_t the slip of the step along the current
// tangent basis (conventionalSlip()); its Hessian is exact by nested AD
// through the projection (DDC_NodeToSurface.cpp, frictionalContact()).
#pragma once

#include <Eigen/Dense>
#include <array>

#include "DDC_ContactState.hpp"
#include "DDC_ReferenceCell.hpp"

namespace ddc {

/// How far (in reference coordinates) outside a facet a projection still
/// counts as inside: round-off of positions computed by different solvers or
/// rank counts is ~1e-16 relative, and a slave node on the end node of a
/// master surface (a patch whose slave and master surfaces end together)
/// stays inside whatever that round-off.
constexpr double kEndTolerance = 1e-10;

/// Result of projectOntoFacet().
struct FacetProjection {
  std::array<double, 2> xi{{0.0, 0.0}};  ///< facet coordinates of the closest point (reference cell of the facet)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit outward normal there (z = 0 in 2-D)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< x(ξ̄) (z = 0 in 2-D)
  double gap = 0.0;         ///< g_N = n·(x_s − x(ξ̄))
  bool inside = false;      ///< ξ̄ lies in the reference facet (within kEndTolerance)
  bool converged = false;   ///< the local Newton iteration converged
  int iterations = 0;
};

/// The spatial dimension of a facet type's host cells (2 for Line*, 3 for
/// Tri*, Quad*); throws std::invalid_argument for a volume cell type.
int facetSpaceDimension(CellType facet);

/// Closest-point projection of x_s onto a facet in its current position by
/// Newton's method on ξ from `start` (default: the facet's centre), with the
/// full Jacobian J_αβ = a_α·a_β − (x_s − x)·∂a_α/∂ξ_β. Converged when the
/// update is below 1e-13 in ξ; at most 30 iterations.
/// \param x facet node positions, numCellNodes(facet) x dim
/// \param xs slave position (dim entries)
FacetProjection projectOntoFacet(CellType facet, const Eigen::MatrixXd& x, const Eigen::VectorXd& xs,
                                 const std::array<double, 2>* start = nullptr);

/// Position and unit outward normal (z = 0 in 2-D) of a facet at the
/// reference point ξ. \return false if the facet is degenerate there.
/// \param x facet node positions, numCellNodes(facet) x dim
bool facetPointAndNormal(CellType facet, const Eigen::MatrixXd& x, const std::array<double, 2>& xi,
                         Eigen::Vector3d& point, Eigen::Vector3d& normal);

/// The slip u_t,α of the conventional element with friction (DDC_Friction.hpp)
/// at the facet point ξ: τ_α·[(x_s − x_s⁰) − Σ N_i(ξ)(x_i − x_i⁰)], with
/// τ_1 = a_1/|a_1| and, in 3-D, τ_2 = n × τ_1; `basis` gets τ (z = 0 in 2-D).
/// \param x, x0 positions now and at the step start, slave first
///        (1 + numCellNodes(facet) rows, dim columns)
std::array<double, 2> conventionalSlip(CellType facet, const Eigen::MatrixXd& x, const Eigen::MatrixXd& x0,
                                       const std::array<double, 2>& xi,
                                       std::array<Eigen::Vector3d, 2>* basis = nullptr);

/// Conventional node-to-surface element on a facet type. Nodes [slave, facet
/// nodes...]; DOFs [u_s, u_1, ..., u_m, λ] (node-major, dim per node), and
/// λ_t (dim − 1) after λ in a frictional pair. The
/// contact component uses it directly (DDC_SurfaceContactElement.hpp wraps it
/// as an Element for the factory).
class NodeToSurfaceElement {
 public:
  /// \throws std::invalid_argument for a cell type that is not a facet.
  explicit NodeToSurfaceElement(CellType facet);
  CellType facet() const { return facet_; }
  int dim() const { return dim_; }
  int numNodes() const { return numNodes_; }
  /// DOFs without friction (a frictional pair has dim − 1 more).
  int numDofs() const { return dim_ * numNodes_ + 1; }
  /// Energy, residual and tangent (see the top of this file).
  /// \param X, u reference positions and displacements, numNodes() x dim()
  /// \throws InadmissibleDeformation if the facet is degenerate (zero tangent
  ///         area) or the projection does not converge.
  void computeContact(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u, const ContactPairState& state, unsigned what,
                      ElementResult& out) const;
  /// The projection of the slave node at (X, u).
  FacetProjection project(const Eigen::MatrixXd& X, const Eigen::MatrixXd& u) const;

 private:
  CellType facet_;
  int dim_, numNodes_;
};

}  // namespace ddc
