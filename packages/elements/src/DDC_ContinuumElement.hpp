// Continuum elements, total Lagrangian, for every element cell type:
//   2-D, plane strain, per unit thickness: "Quad4" (bilinear, 2x2 Gauss),
//       "Quad9" (biquadratic Lagrange, 3x3 Gauss);
//   3-D: "Hex8" (trilinear, 2x2x2 Gauss), "Hex20" (serendipity, 3x3x3),
//       "Hex27" (triquadratic Lagrange, 3x3x3), "Tet4" (linear, 1 point),
//       "Tet10" (quadratic, 4 points).
// Shape functions, node order (Gmsh's, DDC_ReferenceCell.hpp) and the
// choice of each quadrature rule: DDC_ShapeFunctions.hpp. DOFs node-major.
//
// Kinematics (Bonet & Wood, Nonlinear Continuum Mechanics for FEA, ch. 9;
// Wriggers, Nonlinear Finite Element Methods, ch. 4), the same in 2-D and
// 3-D: F = I + sum_a u_a (x) Grad N_a,
//   U_e = sum_q W(F_q) w_q detJ0_q,
//   f_int = sum_q B_q^T S_q w_q detJ0_q        (= dU_e/du),
//   K = sum_q (B_q^T D_q B_q + G_q) w_q detJ0_q,
// with the nonlinear B-matrix B (Voigt rows E11, E22, [E33, 2 E23, 2 E13,]
// 2 E12 by nodal DOF; DDC_Material.hpp) and the geometric stiffness
// G_ab = (Grad N_a . S Grad N_b) I. With a geometrically linear material
// ("Linear Elastic") B is the small-strain B-matrix (F replaced by I in B)
// and G = 0, so U_e = 1/2 u^T K u exactly.
//
// Admissibility: compute()/postprocess() throw InadmissibleDeformation when
// det(dX/dxi) <= 0 (inverted reference element) or, for the finite-strain
// laws, det F <= 0 at a quadrature point. The small-strain law has no such
// restriction and is evaluated for any u.
//
// postprocess(): Cauchy stress sigma = J^-1 F S F^T (plane strain: sigma_zz =
// J^-1 S33), or sigma(eps) for the small-strain law, averaged over the
// quadrature points weighted by their reference volume w_q detJ0_q (i.e. the
// reference-volume mean over the element); energyDensity = U_e / reference
// volume (area in 2-D); minDetJ = smallest det F at the quadrature points.
//
// mass(): M = ∫ ρ N_a N_b dV ⊗ I in the reference configuration (constant in
// the total Lagrangian form), consistent or lumped (MassLumping,
// DDC_Element.hpp); the rule is massQuadratureRule(), not the stiffness
// rule (the 1-point Tet4 rule integrates N_a N_b wrongly).
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <memory>

#include "DDC_Element.hpp"
#include "DDC_Material.hpp"
#include "DDC_ReferenceCell.hpp"

namespace ddc {

/// Common base of the continuum elements. The concrete elements are created
/// by makeContinuumElement or through the ElementFactory.
class ContinuumElement : public Element {
 public:
  /// \param material not null
  /// \param cell the element cell type (its shape functions give the mass)
  ContinuumElement(std::shared_ptr<const Material> material, CellType cell)
      : material_(std::move(material)), cell_(cell) {}

  /// Valid parameters of a continuum element type (without "Type", which
  /// the factory adds): a sublist "Material" with Material::getValidParameters().
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();

  const Material& material() const { return *material_; }
  std::shared_ptr<const Material> materialPtr() const { return material_; }
  /// The small-strain law (Material::isGeometricallyLinear()) gives a
  /// constant tangent.
  bool tangentIsConstant() const override { return material_->isGeometricallyLinear(); }
  /// The material has a density > 0.
  bool hasMass() const override { return material_->density() > 0.0; }
  /// M_ab = ∫ ρ N_a N_b dV over the reference element with
  /// massQuadratureRule() (exact on affine elements), or its row-sum or HRZ
  /// lumped diagonal; ρ = material().density().
  void mass(const NodalArray& X, MassLumping lumping, Eigen::MatrixXd& M) const override;

 protected:
  std::shared_ptr<const Material> material_;
  CellType cell_;
};

/// The continuum element of an element cell type (Quad4, Quad9, Hex8, Hex20,
/// Hex27, Tet4, Tet10).
/// \param material not null
/// \throws std::invalid_argument for a facet cell type
std::shared_ptr<ContinuumElement> makeContinuumElement(CellType cell, std::shared_ptr<const Material> material);

}  // namespace ddc
