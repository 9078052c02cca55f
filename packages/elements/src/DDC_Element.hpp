// Element interface: every element type (continuum, contact, host-defined)
// returns its strain energy, residual and tangent from nodal data, in 2-D or
// 3-D (dim()).
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace ddc {

/// What Element::compute should evaluate (bit flags).
enum ComputeFlags : unsigned {
  kEnergy = 1u,
  kResidual = 2u,
  kTangent = 4u,
  kAll = 7u,
};

/// Nodal values of one element: numNodes() rows (the element's nodes in its
/// node order) by dim() columns (x, y[, z] components). A reference, so a
/// caller's MatrixX2d, MatrixX3d or MatrixXd binds to it without a copy.
using NodalArray = Eigen::Ref<const Eigen::MatrixXd>;

/// How Element::mass() forms the element's mass matrix.
enum class MassLumping {
  Consistent,  ///< M_ab = ∫ ρ N_a N_b dV, times the identity over the components
  /// Diagonal, m_a = Σ_b M_ab. Positive for the linear elements (Quad4, Hex8,
  /// Tet4) and Quad9/Hex27; zero or negative at the corners of Hex20 and Tet10.
  RowSum,
  /// Diagonal, m_a = M_aa · m / Σ_c M_cc with m = ∫ ρ dV (Hinton, Rock &
  /// Zienkiewicz 1976): positive for every element type.
  HRZ
};

/// Results of one element evaluation. Sizes: residual n, tangent n x n with
/// n = numNodes * dim DOFs ordered node-major (u0x, u0y, [u0z,] u1x, ...).
struct ElementResult {
  double energy = 0.0;        ///< strain energy U_e = ∫ W(F) dV (per unit thickness in 2-D)
  Eigen::VectorXd residual;   ///< internal force f_int = ∂U_e/∂u
  Eigen::MatrixXd tangent;    ///< K = ∂f_int/∂u (symmetric for hyperelasticity)
};

/// Post-processing values of one element, averaged over its quadrature points.
struct ElementPostResult {
  /// Cauchy stress in the Voigt order of the materials (DDC_Material.hpp):
  /// σxx, σyy, σzz, σyz, σxz, σxy. Plane strain: σzz from S33, σyz = σxz = 0.
  double cauchy[6] = {0, 0, 0, 0, 0, 0};
  double energyDensity = 0.0;  ///< W per unit reference volume (U_e / V_e; 2-D: U_e / area_e)
  double minDetJ = 0.0;        ///< smallest det F over quadrature points

  /// Von Mises equivalent stress of `cauchy`,
  /// sqrt(((σxx-σyy)² + (σyy-σzz)² + (σzz-σxx)²)/2 + 3 (σyz² + σxz² + σxy²)).
  double vonMises() const {
    const double* s = cauchy;
    const double d01 = s[0] - s[1], d12 = s[1] - s[2], d20 = s[2] - s[0];
    return std::sqrt(0.5 * (d01 * d01 + d12 * d12 + d20 * d20) + 3 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
  }
};

/// Thrown by elements when the deformation is not admissible (det F <= 0 or
/// an inverted reference element); the analysis answers with a bisection.
class InadmissibleDeformation : public std::runtime_error {
 public:
  /// \param w what is inadmissible and where (element, quadrature point)
  explicit InadmissibleDeformation(const std::string& w) : std::runtime_error(w) {}
};

/// A stateless element evaluator: one instance serves every element of a
/// body (it holds the material and options, not nodal data).
class Element {
 public:
  virtual ~Element() = default;
  /// Number of nodes this element expects (4 for Quad4, 9 for Quad9, ...).
  virtual int numNodes() const = 0;
  /// Space dimension of the element's nodal arrays and DOFs (2 or 3).
  virtual int dim() const = 0;
  /// Evaluate energy / residual / tangent.
  /// \param X reference coordinates, numNodes() x dim()
  /// \param u nodal displacements, numNodes() x dim()
  /// \param what bitwise or of ComputeFlags
  /// \param out resized by the element as needed
  /// \throws InadmissibleDeformation when det F <= 0 at a quadrature point
  virtual void compute(const NodalArray& X, const NodalArray& u, unsigned what, ElementResult& out) const = 0;
  /// Stress and energy density for output.
  virtual void postprocess(const NodalArray& X, const NodalArray& u, ElementPostResult& out) const = 0;
  /// Smallest det J of the reference map over the quadrature points and
  /// corners (<= 0 means an inverted or degenerate element).
  virtual double minReferenceJacobian(const NodalArray& X) const = 0;
  /// True if the tangent does not depend on u (a geometrically and
  /// materially linear element): a solver may then keep its factorisation
  /// across Newton iterations and load steps. Default false.
  virtual bool tangentIsConstant() const { return false; }
  /// True if mass() gives a mass matrix (a density > 0). Default false: the
  /// element has no inertia and a dynamic analysis refuses it.
  virtual bool hasMass() const { return false; }
  /// The mass matrix in the reference configuration (total Lagrangian: it
  /// does not change with the deformation), DOFs node-major as for compute()
  /// (per unit thickness in 2-D). Not collective.
  /// \param X reference coordinates, numNodes() x dim()
  /// \param lumping consistent or one of the diagonal (lumped) forms
  /// \param M resized to (numNodes() dim()) square
  /// \throws std::logic_error unless hasMass()
  virtual void mass(const NodalArray& X, MassLumping lumping, Eigen::MatrixXd& M) const {
    (void)X, (void)lumping, (void)M;
    throw std::logic_error("Element::mass: this element type has no mass (hasMass() is false)");
  }
};

/// The mass matrix M (node-major, `dim` components per node) with the mass
/// of the nodes flagged in `massless` moved to the element's other nodes: the
/// rows and columns of those nodes are zeroed and the rest is scaled so the
/// element keeps its mass (the sum of M over one component). This is the
/// mass redistribution of Khenous, Laborde & Renard (2008) for elastodynamic
/// contact: contact-surface nodes without inertia cannot carry the velocity
/// jumps of an impact from step to step (doc/user-guide.md, "Dynamics").
/// A principal submatrix of a positive definite M stays positive definite;
/// a diagonal (lumped) M stays diagonal.
/// \returns false, leaving M unchanged, if every node is flagged (there is
///          nowhere to move the mass)
inline bool redistributeNodalMass(Eigen::MatrixXd& M, const std::vector<char>& massless, int dim) {
  const Eigen::Index n = M.rows();
  bool any = false, all = true;
  for (Eigen::Index a = 0; a < n; ++a) {
    const bool off = massless[static_cast<size_t>(a / dim)] != 0;
    any = any || off;
    all = all && off;
  }
  if (!any) return true;
  if (all) return false;
  const double total = M.sum();
  for (Eigen::Index a = 0; a < n; ++a)
    if (massless[static_cast<size_t>(a / dim)]) {
      M.row(a).setZero();
      M.col(a).setZero();
    }
  const double kept = M.sum();
  if (!(kept > 0.0)) return false;
  M *= total / kept;
  return true;
}

}  // namespace ddc
