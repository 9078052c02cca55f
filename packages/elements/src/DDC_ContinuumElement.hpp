// Plane-strain continuum elements, total Lagrangian, per unit thickness:
// "Quad4" (bilinear, 2x2 Gauss) and "Quad9" (biquadratic Lagrange, 3x3 Gauss).
//
// Node order is Gmsh's: corners counter-clockwise 0..3; Quad9 mid-sides
// 4:(0-1) 5:(1-2) 6:(2-3) 7:(3-0) and centre 8. DOFs node-major.
//
// Kinematics (Bonet & Wood, Nonlinear Continuum Mechanics for FEA, ch. 9;
// Wriggers, Nonlinear FEM, ch. 4): F = I + sum_a u_a (x) Grad N_a,
//   U_e = sum_q W(F_q) w_q detJ0_q,
//   f_int = sum_q B_q^T S_q w_q detJ0_q        (= dU_e/du),
//   K = sum_q (B_q^T D_q B_q + G_q) w_q detJ0_q,
// with the nonlinear B-matrix B (3 x 2n, rows E11, E22, 2 E12) and the
// geometric stiffness G_ab = (Grad N_a . S Grad N_b) I_2. With a
// geometrically linear material ("Linear Elastic") B is the small-strain
// B-matrix (F replaced by I in B) and G = 0, so U_e = 1/2 u^T K u exactly.
//
// Admissibility: compute()/postprocess() throw InadmissibleDeformation when
// det(dX/dxi) <= 0 (inverted reference element) or, for the finite-strain
// laws, det F <= 0 at a quadrature point. The small-strain law has no such
// restriction and is evaluated for any u.
//
// postprocess(): Cauchy stress sigma = J^-1 F S F^T (sigma_zz = J^-1 S33),
// or sigma(eps) for the small-strain law, averaged over the quadrature points
// weighted by their reference volume w_q detJ0_q (i.e. the reference-volume
// mean over the element); energyDensity = U_e / reference area; minDetJ =
// smallest det F at the quadrature points.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <memory>

#include "DDC_Element.hpp"
#include "DDC_Material.hpp"

namespace ddc {

/// Common base of the plane-strain continuum elements. The concrete
/// elements (Quad4, Quad9) are created by makeQuad4 / makeQuad9 or through
/// the ElementFactory.
class ContinuumElement : public Element {
 public:
  explicit ContinuumElement(std::shared_ptr<const Material> material) : material_(std::move(material)) {}

  /// Valid parameters of a continuum element type (without "Type", which
  /// the factory adds): a sublist "Material" with Material::getValidParameters().
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();

  const Material& material() const { return *material_; }
  std::shared_ptr<const Material> materialPtr() const { return material_; }

 protected:
  std::shared_ptr<const Material> material_;
};

/// Bilinear 4-node quadrilateral, 2x2 Gauss quadrature.
/// \param material not null
std::shared_ptr<ContinuumElement> makeQuad4(std::shared_ptr<const Material> material);

/// Biquadratic 9-node Lagrange quadrilateral, 3x3 Gauss quadrature.
/// \param material not null
std::shared_ptr<ContinuumElement> makeQuad9(std::shared_ptr<const Material> material);

}  // namespace ddc
