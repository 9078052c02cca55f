// Hyperelastic materials: 3-D laws, evaluated in 3-D or in plane strain.
//
// A material maps the deformation gradient F to the strain energy density
// W, the second Piola-Kirchhoff stress S and the material tangent dS/dE,
// all per unit reference volume. The laws are 3-D; in 2-D they are
// evaluated in plane strain (F33 = 1, F13 = F23 = F31 = F32 = 0) with the
// 3-D Lame constants, so the 2-D stress vector lacks S33 (stressZZ() gives it).
//
// Voigt convention used everywhere in this package (Voigt<dim> below):
//   3-D stress [S11, S22, S33, S23, S13, S12],
//       strain [E11, E22, E33, 2 E23, 2 E13, 2 E12];
//   2-D stress [S11, S22, S12], strain [E11, E22, 2 E12]
// (engineering shear), so that S:dE = S_v . dE_v and the tangent D
// (symmetric, 6x6 or 3x3) satisfies dS_v = D dE_v.
#pragma once

#include <Eigen/Dense>
#include <Teuchos_ParameterList.hpp>
#include <memory>
#include <string>

namespace ddc {

/// Voigt notation of symmetric dim x dim tensors (dim = 2 or 3): component
/// a of a Voigt vector is the tensor entry (kRow[a], kCol[a]); the first dim
/// components are the normal ones, the rest shears.
template <int dim>
struct Voigt;

template <>
struct Voigt<2> {
  static constexpr int kSize = 3;
  static constexpr int kRow[3] = {0, 1, 0};
  static constexpr int kCol[3] = {0, 1, 1};
};

template <>
struct Voigt<3> {
  static constexpr int kSize = 6;
  static constexpr int kRow[6] = {0, 1, 2, 1, 0, 0};
  static constexpr int kCol[6] = {0, 1, 2, 2, 2, 1};
};

/// Stress (or strain) vector and tangent matrix in Voigt form.
template <int dim>
using VoigtVector = Eigen::Matrix<double, Voigt<dim>::kSize, 1>;
template <int dim>
using VoigtMatrix = Eigen::Matrix<double, Voigt<dim>::kSize, Voigt<dim>::kSize>;
using Vector6d = VoigtVector<3>;
using Matrix6d = VoigtMatrix<3>;

/// Abstract hyperelastic material, evaluated in 3-D or in plane strain.
///
/// Created from a "Material" parameter list by createMaterial(). Instances
/// are immutable and thread-safe: one instance serves every quadrature point.
class Material {
 public:
  /// \param youngsModulus E > 0
  /// \param poissonsRatio -1 < nu < 0.5
  /// \pre the ranges are checked by the validators of getValidParameters()
  ///      (in createMaterial()); direct construction
  ///      with values out of range is a programming error.
  /// \param density mass per unit reference volume, >= 0 (0: no inertia)
  Material(double youngsModulus, double poissonsRatio, double density = 0.0);
  virtual ~Material() = default;

  /// Valid parameters of the "Material" sublist (defaults and doc strings):
  /// "Type" (enumeration), "Young's Modulus", "Poisson's Ratio", "Density".
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();

  /// The "Type" name this material was created from, e.g. "Neo-Hookean".
  virtual std::string typeName() const = 0;

  /// True for the small-strain law: elements then use the geometrically
  /// linear formulation (small-strain B-matrix, no geometric stiffness), and
  /// evaluate() reads only eps = sym(F - I).
  virtual bool isGeometricallyLinear() const { return false; }

  /// Strain energy density and its derivatives at one point, plane strain.
  /// \param F in-plane deformation gradient F = I + Grad u (F33 = 1)
  /// \param S if not null: second Piola-Kirchhoff stress, Voigt [S11,S22,S12]
  ///        (for the small-strain law: the Cauchy stress from eps)
  /// \param D if not null: tangent dS/dE in Voigt form (engineering shear)
  /// \return W(F) per unit reference volume
  /// \throws InadmissibleDeformation if the law needs det F > 0 and it is not
  virtual double evaluate(const Eigen::Matrix2d& F, Eigen::Vector3d* S,
                          Eigen::Matrix3d* D) const = 0;

  /// The same in 3-D.
  /// \param F deformation gradient F = I + Grad u (3x3)
  /// \param S if not null: S in Voigt form [S11,S22,S33,S23,S13,S12]
  ///        (for the small-strain law: the Cauchy stress from eps)
  /// \param D if not null: tangent dS/dE, 6x6, engineering shear strains
  /// \return W(F) per unit reference volume
  /// \throws InadmissibleDeformation if the law needs det F > 0 and it is not
  virtual double evaluate(const Eigen::Matrix3d& F, Vector6d* S, Matrix6d* D) const = 0;

  /// Out-of-plane stress component S33 at the in-plane F (plane strain keeps
  /// E33 = 0 but S33 != 0). For the small-strain law this is sigma_zz.
  /// \throws InadmissibleDeformation like evaluate()
  virtual double stressZZ(const Eigen::Matrix2d& F) const = 0;

  double youngsModulus() const { return youngsModulus_; }
  /// Mass density ρ per unit reference volume (0: the material has no
  /// inertia; quasi-static analyses do not read it).
  double density() const { return density_; }
  double poissonsRatio() const { return poissonsRatio_; }
  /// Lamé's first constant lambda = E nu / ((1 + nu)(1 - 2 nu)) (3-D value).
  double lambda() const { return lambda_; }
  /// Shear modulus mu = E / (2 (1 + nu)).
  double mu() const { return mu_; }

 protected:
  double youngsModulus_;
  double poissonsRatio_;
  double density_;
  double lambda_;
  double mu_;
};

/// Compressible neo-Hookean (Bonet & Wood, Nonlinear Continuum Mechanics, ch. 6):
///   W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2,  I1 = tr C (3-D; in
///   plane strain C33 = 1),
///   S = mu (I - C^-1) + lambda ln J C^-1,
///   CC = lambda C^-1 (x) C^-1 + 2 (mu - lambda ln J) II_{C^-1},
/// with II_{C^-1}_ijkl = (C^-1_ik C^-1_jl + C^-1_il C^-1_jk) / 2.
class NeoHookean : public Material {
 public:
  using Material::Material;
  std::string typeName() const override { return "Neo-Hookean"; }
  double evaluate(const Eigen::Matrix2d& F, Eigen::Vector3d* S, Eigen::Matrix3d* D) const override;
  double evaluate(const Eigen::Matrix3d& F, Vector6d* S, Matrix6d* D) const override;
  /// S33 = mu (1 - C33^-1) + lambda ln J C33^-1 = lambda ln J (C33 = 1).
  double stressZZ(const Eigen::Matrix2d& F) const override;
};

/// St. Venant-Kirchhoff: W = lambda/2 (tr E)^2 + mu E:E,
/// S = lambda tr E I + 2 mu E, with E = (C - I)/2 (plane strain: E33 = 0). Accepts any F
/// (it is defined for det F <= 0 too, but elements reject that).
class StVenantKirchhoff : public Material {
 public:
  using Material::Material;
  std::string typeName() const override { return "St. Venant-Kirchhoff"; }
  double evaluate(const Eigen::Matrix2d& F, Eigen::Vector3d* S, Eigen::Matrix3d* D) const override;
  double evaluate(const Eigen::Matrix3d& F, Vector6d* S, Matrix6d* D) const override;
  /// S33 = lambda tr E.
  double stressZZ(const Eigen::Matrix2d& F) const override;
};

/// Small-strain linear elasticity: W = lambda/2 (tr eps)^2 + mu eps:eps with
/// eps = sym(F - I) = sym(Grad u); the stress returned is sigma = lambda tr eps
/// I + 2 mu eps. Elements using it are geometrically linear.
class LinearElastic : public Material {
 public:
  using Material::Material;
  std::string typeName() const override { return "Linear Elastic"; }
  bool isGeometricallyLinear() const override { return true; }
  double evaluate(const Eigen::Matrix2d& F, Eigen::Vector3d* S, Eigen::Matrix3d* D) const override;
  double evaluate(const Eigen::Matrix3d& F, Vector6d* S, Matrix6d* D) const override;
  /// sigma_zz = lambda tr eps.
  double stressZZ(const Eigen::Matrix2d& F) const override;
};

/// Validate a "Material" parameter list (misspelt names, unknown Type, E > 0,
/// -1 < nu < 0.5), fill in defaults and create the material.
/// \param params the "Material" sublist; defaults are added to it
/// \param path its parameter path for messages, e.g.
///        "Mesh/Bodies/Upper Ring/Element/Material"
/// \throws InputError naming the offending parameter path
std::shared_ptr<Material> createMaterial(Teuchos::ParameterList& params, const std::string& path);

}  // namespace ddc
