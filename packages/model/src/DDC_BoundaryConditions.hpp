// Prescribed displacements on node sets and tractions on side sets, both
// scaled by the load factor.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <array>
#include <string>
#include <vector>

#include "DDC_Mesh.hpp"

namespace ddc {

/// A prescribed displacement on a node set:
///   u(X, λ) = s·(v + H (X − c)) + (R(s·θ, a) − I)(X − c),  s = s(λ),
/// with s(λ) = λ, or the piecewise-linear load curve through the points
/// (λ_i, s_i) of "Load Curve" (constant beyond its first and last point):
/// e.g. "0 0, 0.25 1, 1 1" applies the whole value by λ = 0.25 and holds it,
/// "0 0, 0.25 0, 1 1" starts it at λ = 0.25 (a press, then a slide:
/// examples/ironing_3d.xml).
/// on the components selected: v the values, H the displacement gradient
/// (affine fields: patch tests, homogeneous deformations), R(λ·θ, a) a
/// rigid rotation by the angle λ·θ about the axis a through the centre c
/// (Rodrigues' formula; in 2-D a = z). Arrays hold x, y, z; in 2-D the z
/// entries are unused and stay 0.
struct DisplacementCondition {
  std::string name;     ///< sublist name, for messages
  std::string setName;  ///< qualified node set, "Body/set"
  bool fix[3] = {true, true, false};
  double value[3] = {0.0, 0.0, 0.0};
  double gradient[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  double angleRadians = 0.0;
  double axis[3] = {0.0, 0.0, 1.0};  ///< unit rotation axis
  double center[3] = {0.0, 0.0, 0.0};
  /// Load curve points (λ_i strictly increasing, s_i); empty: s(λ) = λ.
  std::vector<std::array<double, 2>> curve;
  /// s(λ): the factor of the values, gradient and angle at load factor λ.
  double scale(double lambda) const;
  /// Prescribed value of component `c` at reference position X and load factor λ.
  double prescribed(int c, const std::array<double, 3>& X, double lambda) const;
};

/// A dead traction (force per unit reference length in 2-D, per unit
/// reference area in 3-D) on a side set, scaled by s(λ): λ, or the load
/// curve as for a DisplacementCondition ("0 0, 0.5 0, 1 1": none until
/// λ = 0.5, then growing to the whole traction; a press, then a push
/// sideways: examples/cattaneo_2d.xml).
struct TractionCondition {
  std::string name;
  std::string setName;  ///< qualified side set
  double traction[3] = {0.0, 0.0, 0.0};
  /// Load curve points (λ_i strictly increasing, s_i); empty: s(λ) = λ.
  std::vector<std::array<double, 2>> curve;
  /// s(λ): the factor of the traction at load factor λ.
  double scale(double lambda) const;
};

/// The piecewise-linear function through `curve` at λ (constant beyond its
/// first and last point); λ itself when `curve` is empty.
double loadCurveValue(const std::vector<std::array<double, 2>>& curve, double lambda);

/// All boundary conditions of a model, parsed from "Boundary Conditions".
struct BoundaryConditions {
  std::vector<DisplacementCondition> displacements;
  std::vector<TractionCondition> tractions;

  /// Valid parameters of one condition ("Boundary Conditions/<Condition Name>").
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  /// Parse and validate every condition; set names are checked against the
  /// mesh (InputError naming the condition and listing the known sets).
  static BoundaryConditions fromParameters(Teuchos::ParameterList& list, const Mesh& mesh,
                                           const std::string& path);
};

}  // namespace ddc
