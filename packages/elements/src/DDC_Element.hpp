// Element interface: every element type (continuum, contact, host-defined)
// returns its strain energy, residual and tangent from nodal data.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <stdexcept>
#include <string>

namespace ddc {

/// What Element::compute should evaluate (bit flags).
enum ComputeFlags : unsigned {
  kEnergy = 1u,
  kResidual = 2u,
  kTangent = 4u,
  kAll = 7u,
};

/// Results of one element evaluation. Sizes: residual n, tangent n x n with
/// n = numNodes * 2 DOFs ordered node-major (u0x, u0y, u1x, u1y, ...).
struct ElementResult {
  double energy = 0.0;        ///< strain energy U_e = ∫ W(F) dV (per unit thickness)
  Eigen::VectorXd residual;   ///< internal force f_int = ∂U_e/∂u
  Eigen::MatrixXd tangent;    ///< K = ∂f_int/∂u (symmetric for hyperelasticity)
};

/// Post-processing values of one element, averaged over its quadrature points.
struct ElementPostResult {
  double cauchy[4] = {0, 0, 0, 0};  ///< Cauchy stress σxx, σyy, σxy, σzz (plane strain)
  double energyDensity = 0.0;       ///< W per unit reference volume (U_e / area_e)
  double minDetJ = 0.0;             ///< smallest det F over quadrature points
};

/// Thrown by elements when the deformation is not admissible (det F <= 0 or
/// an inverted reference element); the analysis answers with a bisection.
class InadmissibleDeformation : public std::runtime_error {
 public:
  explicit InadmissibleDeformation(const std::string& w) : std::runtime_error(w) {}
};

/// A stateless element evaluator: one instance serves every element of a
/// body (it holds the material and options, not nodal data).
class Element {
 public:
  virtual ~Element() = default;
  /// Number of nodes this element expects (4 for Quad4, 9 for Quad9, ...).
  virtual int numNodes() const = 0;
  /// Evaluate energy / residual / tangent.
  /// \param X reference coordinates, numNodes() x 2
  /// \param u nodal displacements, numNodes() x 2
  /// \param what bitwise or of ComputeFlags
  /// \param out resized by the element as needed
  /// \throws InadmissibleDeformation when det F <= 0 at a quadrature point
  virtual void compute(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u, unsigned what,
                       ElementResult& out) const = 0;
  /// Stress and energy density for output.
  virtual void postprocess(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u,
                           ElementPostResult& out) const = 0;
  /// Smallest det J of the reference map over the quadrature points and
  /// corners (<= 0 means an inverted or degenerate element).
  virtual double minReferenceJacobian(const Eigen::MatrixX2d& X) const = 0;
};

}  // namespace ddc
