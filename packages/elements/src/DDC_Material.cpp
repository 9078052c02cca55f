#include "DDC_Material.hpp"

#include <cmath>
#include <sstream>
#include <vector>

#include "DDC_Element.hpp"
#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"
#include "DDC_TensorAlgebra.hpp"

namespace ddc {

namespace {

/// The names accepted by "Type", in the order of the enumeration; the first
/// is the default.
const std::vector<std::string>& materialTypeNames() {
  static const std::vector<std::string> names = {"Neo-Hookean", "St. Venant-Kirchhoff",
                                                 "Linear Elastic"};
  return names;
}

template <int dim>
using Tensor = Eigen::Matrix<double, dim, dim>;

/// The constant isotropic elasticity matrix in Voigt form (plane strain for
/// dim = 2); also the SVK tangent dS/dE.
template <int dim>
VoigtMatrix<dim> isotropicVoigt(double lambda, double mu) {
  VoigtMatrix<dim> D = VoigtMatrix<dim>::Zero();
  for (int a = 0; a < dim; ++a) {
    for (int b = 0; b < dim; ++b) D(a, b) = lambda;
    D(a, a) = lambda + 2 * mu;
  }
  for (int a = dim; a < Voigt<dim>::kSize; ++a) D(a, a) = mu;
  return D;
}

/// W, S and D of the quadratic law W = lambda/2 (tr E)^2 + mu E:E for a
/// symmetric strain E (plane strain: E33 = 0); shared by SVK (Green-Lagrange
/// E) and linear elasticity (eps).
template <int dim>
double quadraticLaw(const Tensor<dim>& E, double lambda, double mu, VoigtVector<dim>* S, VoigtMatrix<dim>* D) {
  using V = Voigt<dim>;
  const double trE = E.trace();
  // E:E with each shear entry counted twice (E_ij = E_ji).
  double EE = 0.0;
  for (int a = 0; a < V::kSize; ++a) {
    const double e = E(V::kRow[a], V::kCol[a]);
    EE += (a < dim ? 1.0 : 2.0) * (e * e);
  }
  if (S)
    for (int a = 0; a < V::kSize; ++a) {
      const int i = V::kRow[a], j = V::kCol[a];
      (*S)(a) = a < dim ? lambda * trE + 2 * mu * E(i, i) : 2 * mu * E(i, j);
    }
  if (D) *D = isotropicVoigt<dim>(lambda, mu);
  return 0.5 * lambda * trE * trE + mu * EE;
}

template <int dim>
double requirePositiveJ(const Tensor<dim>& F, const char* law) {
  const double J = F.determinant();
  if (!(J > 0)) DDC_THROW(InadmissibleDeformation, law << ": det F = " << J << " <= 0");
  return J;
}

/// Compressible neo-Hookean law (see NeoHookean) in dim = 3, or in plane
/// strain for dim = 2, where C is block diagonal with C33 = 1: I1 = tr C + 1,
/// det C = J^2 and the in-plane block of C^-1 is the inverse of the 2x2 block.
template <int dim>
double neoHookeanLaw(const Tensor<dim>& F, double lambda, double mu, VoigtVector<dim>* S, VoigtMatrix<dim>* D) {
  using V = Voigt<dim>;
  const double J = requirePositiveJ<dim>(F, "Neo-Hookean");
  const double lnJ = std::log(J);
  const Tensor<dim> C = F.transpose() * F;
  const double I1 = dim == 2 ? C.trace() + 1.0 : C.trace();
  const double W = 0.5 * mu * (I1 - 3.0) - mu * lnJ + 0.5 * lambda * lnJ * lnJ;
  if (!S && !D) return W;
  const Tensor<dim> Ci = adjugate(C) * (1.0 / (J * J));
  if (S) {
    // S = mu (I - C^-1) + lambda ln J C^-1
    for (int a = 0; a < V::kSize; ++a) {
      const int i = V::kRow[a], j = V::kCol[a];
      (*S)(a) = a < dim ? mu * (1.0 - Ci(i, i)) + lambda * lnJ * Ci(i, i) : (lambda * lnJ - mu) * Ci(i, j);
    }
  }
  if (D) {
    // CC_ijkl = lambda Ci_ij Ci_kl + (mu - lambda ln J)(Ci_ik Ci_jl + Ci_il Ci_jk);
    // with engineering shear in the strain vector, D_ab = CC_{ij(a) kl(b)}
    // by the minor symmetry CC_ijkl = CC_ijlk.
    const double c = mu - lambda * lnJ;
    for (int a = 0; a < V::kSize; ++a) {
      const int i = V::kRow[a], j = V::kCol[a];
      for (int b = a; b < V::kSize; ++b) {
        const int k = V::kRow[b], l = V::kCol[b];
        (*D)(a, b) = lambda * Ci(i, j) * Ci(k, l) + c * (Ci(i, k) * Ci(j, l) + Ci(i, l) * Ci(j, k));
        (*D)(b, a) = (*D)(a, b);
      }
    }
  }
  return W;
}

template <int dim>
double stVenantKirchhoffLaw(const Tensor<dim>& F, double lambda, double mu, VoigtVector<dim>* S,
                            VoigtMatrix<dim>* D) {
  const Tensor<dim> E = 0.5 * (F.transpose() * F - Tensor<dim>::Identity());
  return quadraticLaw<dim>(E, lambda, mu, S, D);
}

template <int dim>
double linearElasticLaw(const Tensor<dim>& F, double lambda, double mu, VoigtVector<dim>* S, VoigtMatrix<dim>* D) {
  const Tensor<dim> H = F - Tensor<dim>::Identity();
  const Tensor<dim> eps = 0.5 * (H + H.transpose());
  return quadraticLaw<dim>(eps, lambda, mu, S, D);
}

}  // namespace

Material::Material(double youngsModulus, double poissonsRatio, double density)
    : youngsModulus_(youngsModulus),
      poissonsRatio_(poissonsRatio),
      density_(density),
      lambda_(youngsModulus * poissonsRatio / ((1 + poissonsRatio) * (1 - 2 * poissonsRatio))),
      mu_(youngsModulus / (2 * (1 + poissonsRatio))) {}

Teuchos::RCP<const Teuchos::ParameterList> Material::getValidParameters() {
  // Built once (thread-safe static initialisation); callers get a const view.
  static const Teuchos::RCP<const Teuchos::ParameterList> valid = [] {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Material"));
    const auto& names = materialTypeNames();
    pl->set("Type", names.front(),
            "Hyperelastic law, 3-D (plane strain, F33 = 1, in 2-D). 'Neo-Hookean': compressible, "
            "W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2. 'St. Venant-Kirchhoff': "
            "W = lambda/2 (tr E)^2 + mu E:E. 'Linear Elastic': small strain, geometrically "
            "linear elements (for verification).",
            enumValidator(names, "Type"));
    pl->set("Young's Modulus", 1000.0, "Young's modulus E.", greaterThan(0.0));
    pl->set("Poisson's Ratio", 0.3,
            "Poisson's ratio nu; the Lame constants are the 3-D ones (also in plane strain), so nu = 0.5 "
            "(incompressible) and nu = -1 make them infinite.",
            between(-1.0, 0.5, Interval::Open));
    pl->set("Density", 0.0,
            "Mass density rho per unit reference volume (2-D: per unit area, the thickness being 1), for the "
            "element mass matrices; 0: no inertia. Quasi-static analyses do not read it. At most 1e8, over "
            "4000 times the densest material's (osmium, 22 590 kg/m^3) in kg/m^3, the largest of the consistent "
            "units in use (t/mm^3: 2.3e-8).",
            between(0.0, 1e8));
    return Teuchos::RCP<const Teuchos::ParameterList>(pl);
  }();
  return valid;
}

std::shared_ptr<Material> createMaterial(Teuchos::ParameterList& params, const std::string& path) {
  validateLevel(params, *Material::getValidParameters(), path);
  const std::string type = params.get<std::string>("Type");
  const double E = params.get<double>("Young's Modulus");
  const double nu = params.get<double>("Poisson's Ratio");
  const double rho = params.get<double>("Density");
  if (type == "Neo-Hookean") return std::make_shared<NeoHookean>(E, nu, rho);
  if (type == "St. Venant-Kirchhoff") return std::make_shared<StVenantKirchhoff>(E, nu, rho);
  if (type == "Linear Elastic") return std::make_shared<LinearElastic>(E, nu, rho);
  // Unreachable after validateLevel (the enumeration validator rejects
  // other names), kept so a new name in the list cannot fall through.
  DDC_THROW(InputError, "parameter '" << joinPath(path, "Type") << "': material type '" << type
                                      << "' is not implemented");
}

// ---------------------------------------------------------------- Neo-Hookean

double NeoHookean::evaluate(const Eigen::Matrix2d& F, Eigen::Vector3d* S, Eigen::Matrix3d* D) const {
  return neoHookeanLaw<2>(F, lambda_, mu_, S, D);
}

double NeoHookean::evaluate(const Eigen::Matrix3d& F, Vector6d* S, Matrix6d* D) const {
  return neoHookeanLaw<3>(F, lambda_, mu_, S, D);
}

double NeoHookean::stressZZ(const Eigen::Matrix2d& F) const {
  const double J = requirePositiveJ<2>(F, "Neo-Hookean");
  // S33 = mu (1 - C33^-1) + lambda ln J C33^-1 with C33 = 1.
  return lambda_ * std::log(J);
}

// -------------------------------------------------------------------- SVK

double StVenantKirchhoff::evaluate(const Eigen::Matrix2d& F, Eigen::Vector3d* S, Eigen::Matrix3d* D) const {
  return stVenantKirchhoffLaw<2>(F, lambda_, mu_, S, D);
}

double StVenantKirchhoff::evaluate(const Eigen::Matrix3d& F, Vector6d* S, Matrix6d* D) const {
  return stVenantKirchhoffLaw<3>(F, lambda_, mu_, S, D);
}

double StVenantKirchhoff::stressZZ(const Eigen::Matrix2d& F) const {
  const Eigen::Matrix2d E = 0.5 * (F.transpose() * F - Eigen::Matrix2d::Identity());
  // S33 = lambda tr E + 2 mu E33, E33 = 0.
  return lambda_ * E.trace();
}

// ----------------------------------------------------------- Linear elastic

double LinearElastic::evaluate(const Eigen::Matrix2d& F, Eigen::Vector3d* S, Eigen::Matrix3d* D) const {
  return linearElasticLaw<2>(F, lambda_, mu_, S, D);
}

double LinearElastic::evaluate(const Eigen::Matrix3d& F, Vector6d* S, Matrix6d* D) const {
  return linearElasticLaw<3>(F, lambda_, mu_, S, D);
}

double LinearElastic::stressZZ(const Eigen::Matrix2d& F) const {
  // sigma_zz = lambda tr eps (eps_zz = 0).
  return lambda_ * (F(0, 0) - 1.0 + F(1, 1) - 1.0);
}

}  // namespace ddc
