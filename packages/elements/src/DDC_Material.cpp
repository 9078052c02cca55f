#include "DDC_Material.hpp"

#include <cmath>
#include <sstream>
#include <vector>

#include "DDC_Element.hpp"
#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

/// The names accepted by "Type", in the order of the enumeration; the first
/// is the default.
const std::vector<std::string>& materialTypeNames() {
  static const std::vector<std::string> names = {"Neo-Hookean", "St. Venant-Kirchhoff",
                                                 "Linear Elastic"};
  return names;
}

/// Voigt index a -> tensor indices (i, j): 0 -> 11, 1 -> 22, 2 -> 12.
constexpr int kVoigtI[3] = {0, 1, 0};
constexpr int kVoigtJ[3] = {0, 1, 1};

/// The constant plane-strain elasticity matrix in Voigt form (stress
/// [11,22,12], strain [11,22,2*12]); also the SVK tangent dS/dE.
Eigen::Matrix3d isotropicVoigt(double lambda, double mu) {
  Eigen::Matrix3d D;
  D << lambda + 2 * mu, lambda, 0,  //
      lambda, lambda + 2 * mu, 0,   //
      0, 0, mu;
  return D;
}

/// W, S and D of the quadratic law W = lambda/2 (tr E)^2 + mu E:E for a
/// symmetric in-plane strain E (E33 = 0); shared by SVK (Green-Lagrange E)
/// and linear elasticity (eps).
double quadraticLaw(const Eigen::Matrix2d& E, double lambda, double mu, Eigen::Vector3d* S,
                    Eigen::Matrix3d* D) {
  const double trE = E(0, 0) + E(1, 1);
  const double EE = E(0, 0) * E(0, 0) + E(1, 1) * E(1, 1) + 2 * E(0, 1) * E(0, 1);
  if (S) *S << lambda * trE + 2 * mu * E(0, 0), lambda * trE + 2 * mu * E(1, 1), 2 * mu * E(0, 1);
  if (D) *D = isotropicVoigt(lambda, mu);
  return 0.5 * lambda * trE * trE + mu * EE;
}

double requirePositiveJ(const Eigen::Matrix2d& F, const char* law) {
  const double J = F.determinant();
  if (!(J > 0)) DDC_THROW(InadmissibleDeformation, law << ": det F = " << J << " <= 0");
  return J;
}

}  // namespace

Material::Material(double youngsModulus, double poissonsRatio)
    : youngsModulus_(youngsModulus),
      poissonsRatio_(poissonsRatio),
      lambda_(youngsModulus * poissonsRatio / ((1 + poissonsRatio) * (1 - 2 * poissonsRatio))),
      mu_(youngsModulus / (2 * (1 + poissonsRatio))) {}

Teuchos::RCP<const Teuchos::ParameterList> Material::getValidParameters() {
  // Built once (thread-safe static initialisation); callers get a const view.
  static const Teuchos::RCP<const Teuchos::ParameterList> valid = [] {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Material"));
    const auto& names = materialTypeNames();
    pl->set("Type", names.front(),
            "Hyperelastic law in plane strain (F33 = 1). 'Neo-Hookean': compressible, "
            "W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2. 'St. Venant-Kirchhoff': "
            "W = lambda/2 (tr E)^2 + mu E:E. 'Linear Elastic': small strain, geometrically "
            "linear elements (for verification).",
            enumValidator(names, "Type"));
    pl->set("Young's Modulus", 1000.0, "Young's modulus E.", greaterThan(0.0));
    pl->set("Poisson's Ratio", 0.3,
            "Poisson's ratio nu; the Lame constants are the 3-D ones (plane strain), so nu = 0.5 "
            "(incompressible) and nu = -1 make them infinite.",
            between(-1.0, 0.5, Interval::Open));
    return Teuchos::RCP<const Teuchos::ParameterList>(pl);
  }();
  return valid;
}

std::shared_ptr<Material> createMaterial(Teuchos::ParameterList& params, const std::string& path) {
  validateLevel(params, *Material::getValidParameters(), path);
  const std::string type = params.get<std::string>("Type");
  const double E = params.get<double>("Young's Modulus");
  const double nu = params.get<double>("Poisson's Ratio");
  if (type == "Neo-Hookean") return std::make_shared<NeoHookean>(E, nu);
  if (type == "St. Venant-Kirchhoff") return std::make_shared<StVenantKirchhoff>(E, nu);
  if (type == "Linear Elastic") return std::make_shared<LinearElastic>(E, nu);
  // Unreachable after validateLevel (the enumeration validator rejects
  // other names), kept so a new name in the list cannot fall through.
  DDC_THROW(InputError, "parameter '" << joinPath(path, "Type") << "': material type '" << type
                                      << "' is not implemented");
}

// ---------------------------------------------------------------- Neo-Hookean

double NeoHookean::evaluate(const Eigen::Matrix2d& F, Eigen::Vector3d* S, Eigen::Matrix3d* D) const {
  const double J = requirePositiveJ(F, "Neo-Hookean");
  const double lnJ = std::log(J);
  const Eigen::Matrix2d C = F.transpose() * F;
  // I1 = tr C with C33 = 1 (plane strain).
  const double W = 0.5 * mu_ * (C.trace() + 1.0 - 3.0) - mu_ * lnJ + 0.5 * lambda_ * lnJ * lnJ;
  if (!S && !D) return W;
  // C^-1 in-plane block: C is block diagonal with C33 = 1, so the in-plane
  // block of C^-1 is the inverse of the 2x2 block, det C = J^2.
  Eigen::Matrix2d Ci;
  const double invDetC = 1.0 / (J * J);
  Ci << C(1, 1) * invDetC, -C(0, 1) * invDetC, -C(1, 0) * invDetC, C(0, 0) * invDetC;
  if (S) {
    // S = mu (I - C^-1) + lambda ln J C^-1
    *S << mu_ * (1.0 - Ci(0, 0)) + lambda_ * lnJ * Ci(0, 0),
        mu_ * (1.0 - Ci(1, 1)) + lambda_ * lnJ * Ci(1, 1), (lambda_ * lnJ - mu_) * Ci(0, 1);
  }
  if (D) {
    // CC_ijkl = lambda Ci_ij Ci_kl + (mu - lambda ln J)(Ci_ik Ci_jl + Ci_il Ci_jk);
    // with engineering shear in the strain vector, D_ab = CC_{ij(a) kl(b)}
    // by the minor symmetry CC_ij12 = CC_ij21.
    const double c = mu_ - lambda_ * lnJ;
    for (int a = 0; a < 3; ++a) {
      const int i = kVoigtI[a], j = kVoigtJ[a];
      for (int b = a; b < 3; ++b) {
        const int k = kVoigtI[b], l = kVoigtJ[b];
        (*D)(a, b) = lambda_ * Ci(i, j) * Ci(k, l) + c * (Ci(i, k) * Ci(j, l) + Ci(i, l) * Ci(j, k));
        (*D)(b, a) = (*D)(a, b);
      }
    }
  }
  return W;
}

double NeoHookean::stressZZ(const Eigen::Matrix2d& F) const {
  const double J = requirePositiveJ(F, "Neo-Hookean");
  // S33 = mu (1 - C33^-1) + lambda ln J C33^-1 with C33 = 1.
  return lambda_ * std::log(J);
}

// -------------------------------------------------------------------- SVK

double StVenantKirchhoff::evaluate(const Eigen::Matrix2d& F, Eigen::Vector3d* S,
                                   Eigen::Matrix3d* D) const {
  const Eigen::Matrix2d E = 0.5 * (F.transpose() * F - Eigen::Matrix2d::Identity());
  return quadraticLaw(E, lambda_, mu_, S, D);
}

double StVenantKirchhoff::stressZZ(const Eigen::Matrix2d& F) const {
  const Eigen::Matrix2d E = 0.5 * (F.transpose() * F - Eigen::Matrix2d::Identity());
  // S33 = lambda tr E + 2 mu E33, E33 = 0.
  return lambda_ * E.trace();
}

// ----------------------------------------------------------- Linear elastic

double LinearElastic::evaluate(const Eigen::Matrix2d& F, Eigen::Vector3d* S, Eigen::Matrix3d* D) const {
  const Eigen::Matrix2d H = F - Eigen::Matrix2d::Identity();
  const Eigen::Matrix2d eps = 0.5 * (H + H.transpose());
  return quadraticLaw(eps, lambda_, mu_, S, D);
}

double LinearElastic::stressZZ(const Eigen::Matrix2d& F) const {
  // sigma_zz = lambda tr eps (eps_zz = 0).
  return lambda_ * (F(0, 0) - 1.0 + F(1, 1) - 1.0);
}

}  // namespace ddc
