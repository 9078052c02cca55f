// Materials: parameter validation, Lamé constants, closed-form values of the
// energy and stress at simple deformations; in 3-D also derivative checks
// (S against W, D against S), objectivity and agreement of the 3-D laws with
// plane strain.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "DDC_Element.hpp"
#include "DDC_Error.hpp"
#include "DDC_Material.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using ddc::test::kFiniteDifference;
using ddc::test::kRoundoff;
using ddc::test::relDiff;

/// Expect `f` to throw ddc::InputError whose message contains every string
/// of `needles`.
template <class Fn>
void expectInputError(Fn f, std::initializer_list<std::string> needles) {
  try {
    f();
    ADD_FAILURE() << "no InputError thrown";
  } catch (const ddc::InputError& e) {
    const std::string msg = e.what();
    for (const auto& n : needles) EXPECT_NE(msg.find(n), std::string::npos) << "'" << n << "' not in: " << msg;
  }
}

TEST(Material, DefaultsAndLameConstants) {
  Teuchos::ParameterList p;
  auto m = ddc::createMaterial(p, "Element/Material");
  EXPECT_EQ(m->typeName(), "Neo-Hookean");
  EXPECT_EQ(p.get<std::string>("Type"), "Neo-Hookean");
  EXPECT_EQ(p.get<double>("Young's Modulus"), 1000.0);
  EXPECT_EQ(p.get<double>("Poisson's Ratio"), 0.3);
  // E = 1000, nu = 0.3: mu = 1000 / 2.6, lambda = 300 / (1.3 * 0.4).
  EXPECT_LT(relDiff(m->mu(), 1000.0 / 2.6), kRoundoff);
  EXPECT_LT(relDiff(m->lambda(), 300.0 / 0.52), kRoundoff);
}

TEST(Material, SelectsType) {
  for (const std::string t : {"Neo-Hookean", "St. Venant-Kirchhoff", "Linear Elastic"}) {
    Teuchos::ParameterList p;
    p.set("Type", t);
    auto m = ddc::createMaterial(p, "M");
    EXPECT_EQ(m->typeName(), t);
    EXPECT_EQ(m->isGeometricallyLinear(), t == "Linear Elastic");
  }
}

TEST(Material, RejectsBadInput) {
  expectInputError(
      [] {
        Teuchos::ParameterList p;
        p.set("Youngs Modulus", 10.0);
        ddc::createMaterial(p, "Body/Element/Material");
      },
      {"Body/Element/Material/Youngs Modulus", "Young's Modulus"});
  expectInputError(
      [] {
        Teuchos::ParameterList p;
        p.set("Type", std::string("Mooney-Rivlin"));
        ddc::createMaterial(p, "Body/Element/Material");
      },
      {"Body/Element/Material/Type", "Mooney-Rivlin", "Neo-Hookean", "St. Venant-Kirchhoff", "Linear Elastic"});
  expectInputError(
      [] {
        Teuchos::ParameterList p;
        p.set("Young's Modulus", -5.0);
        ddc::createMaterial(p, "Body/Element/Material");
      },
      {"Body/Element/Material/Young's Modulus", "> 0"});
  for (double nu : {0.5, -1.0, 0.7}) {
    expectInputError(
        [nu] {
          Teuchos::ParameterList p;
          p.set("Poisson's Ratio", nu);
          ddc::createMaterial(p, "Body/Element/Material");
        },
        {"Body/Element/Material/Poisson's Ratio"});
  }
  // Wrong value type (int instead of double).
  expectInputError(
      [] {
        Teuchos::ParameterList p;
        p.set("Young's Modulus", 5);
        ddc::createMaterial(p, "M");
      },
      {"M/Young's Modulus"});
}

TEST(Material, NeoHookeanUniaxialClosedForm) {
  // F = diag(s, 1): J = s, I1 = s^2 + 2, so
  // W = mu/2 (s^2 - 1) - mu ln s + lambda/2 (ln s)^2,
  // S11 = mu (1 - 1/s^2) + lambda ln s / s^2, S22 = S33 = lambda ln s.
  ddc::NeoHookean m(1000.0, 0.3);
  const double mu = m.mu(), la = m.lambda();
  for (double s : {0.7, 1.0, 1.3}) {
    Eigen::Matrix2d F;
    F << s, 0, 0, 1;
    Eigen::Vector3d S;
    Eigen::Matrix3d D;
    const double W = m.evaluate(F, &S, &D);
    const double Wref = 0.5 * mu * (s * s - 1) - mu * std::log(s) + 0.5 * la * std::log(s) * std::log(s);
    EXPECT_NEAR(W, Wref, kRoundoff * mu);
    EXPECT_NEAR(S(0), mu * (1 - 1 / (s * s)) + la * std::log(s) / (s * s), kRoundoff * mu);
    EXPECT_NEAR(S(1), la * std::log(s), kRoundoff * mu);
    EXPECT_NEAR(S(2), 0.0, kRoundoff * mu);
    EXPECT_NEAR(m.stressZZ(F), la * std::log(s), kRoundoff * mu);
    // D11 = dS11/dE11 = (lambda + 2 (mu - lambda ln s)) / s^4 (C^-1_11 = 1/s^2).
    EXPECT_NEAR(D(0, 0), (la + 2 * (mu - la * std::log(s))) / std::pow(s, 4), kRoundoff * mu);
  }
  // At F = I the tangent is the small-strain elasticity matrix.
  Eigen::Matrix3d D, Dlin;
  m.evaluate(Eigen::Matrix2d::Identity(), nullptr, &D);
  ddc::LinearElastic(1000.0, 0.3).evaluate(Eigen::Matrix2d::Identity(), nullptr, &Dlin);
  EXPECT_LT((D - Dlin).norm(), kRoundoff * Dlin.norm());
}

TEST(Material, NeoHookeanRejectsNonPositiveJ) {
  ddc::NeoHookean m(1000.0, 0.3);
  Eigen::Matrix2d F;
  F << -1, 0, 0, 1;
  EXPECT_THROW(m.evaluate(F, nullptr, nullptr), ddc::InadmissibleDeformation);
  EXPECT_THROW(m.stressZZ(F), ddc::InadmissibleDeformation);
}

TEST(Material, StVenantKirchhoffClosedForm) {
  // F = diag(s, 1): E11 = (s^2 - 1)/2, W = (lambda/2 + mu) E11^2.
  ddc::StVenantKirchhoff m(200.0, 0.25);
  const double s = 1.4, E11 = 0.5 * (s * s - 1);
  Eigen::Matrix2d F;
  F << s, 0, 0, 1;
  Eigen::Vector3d S;
  const double W = m.evaluate(F, &S, nullptr);
  EXPECT_NEAR(W, (0.5 * m.lambda() + m.mu()) * E11 * E11, kRoundoff * m.mu());
  EXPECT_NEAR(S(0), (m.lambda() + 2 * m.mu()) * E11, kRoundoff * m.mu());
  EXPECT_NEAR(S(1), m.lambda() * E11, kRoundoff * m.mu());
  EXPECT_NEAR(m.stressZZ(F), m.lambda() * E11, kRoundoff * m.mu());
}

// ------------------------------------------------------------------- 3-D

/// The three laws with E = 1000, nu = 0.3.
std::vector<std::shared_ptr<ddc::Material>> allMaterials() {
  return {std::make_shared<ddc::NeoHookean>(1000.0, 0.3), std::make_shared<ddc::StVenantKirchhoff>(1000.0, 0.3),
          std::make_shared<ddc::LinearElastic>(1000.0, 0.3)};
}

/// A random deformation gradient near I (entries of F - I up to 0.15).
Eigen::Matrix3d randomF(unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-0.15, 0.15);
  Eigen::Matrix3d F;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) F(i, j) = (i == j ? 1.0 : 0.0) + d(gen);
  return F;
}

/// The symmetric tensor of a 3-D Voigt vector whose shears are engineering
/// (strain) or tensorial (stress) components.
Eigen::Matrix3d fromVoigt(const ddc::Vector6d& v, double shearFactor) {
  Eigen::Matrix3d m;
  m << v(0), shearFactor * v(5), shearFactor * v(4),  //
      shearFactor * v(5), v(1), shearFactor * v(3),   //
      shearFactor * v(4), shearFactor * v(3), v(2);
  return m;
}

constexpr double kFdStep = 1e-6;  // strains are O(0.1); see kFiniteDifference

TEST(Material3d, StressIsTheEnergyDerivative) {
  // First Piola-Kirchhoff P = dW/dF = F S (for the small-strain law dW/dF =
  // sigma, the stress it returns).
  for (const auto& m : allMaterials()) {
    const Eigen::Matrix3d F = randomF(3);
    ddc::Vector6d S;
    m->evaluate(F, &S, nullptr);
    const Eigen::Matrix3d Sm = fromVoigt(S, 1.0);
    const Eigen::Matrix3d P = m->isGeometricallyLinear() ? Sm : Eigen::Matrix3d(F * Sm);
    Eigen::Matrix3d fd;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Eigen::Matrix3d Fp = F, Fm = F;
        Fp(i, j) += kFdStep;
        Fm(i, j) -= kFdStep;
        fd(i, j) = (m->evaluate(Fp, nullptr, nullptr) - m->evaluate(Fm, nullptr, nullptr)) / (2 * kFdStep);
      }
    EXPECT_LT((fd - P).norm(), kFiniteDifference * P.norm()) << m->typeName();
  }
}

TEST(Material3d, TangentIsTheStressDerivative) {
  // D(:, b) = dS/dE_b with the engineering shear strain as variable: E is
  // perturbed by h in Voigt component b and F = sqrt(I + 2E) (the laws
  // depend on C = I + 2E only); the small-strain law is perturbed in eps.
  for (const auto& m : allMaterials()) {
    const Eigen::Matrix3d F0 = randomF(4);
    const bool linear = m->isGeometricallyLinear();
    const Eigen::Matrix3d E0 = linear ? Eigen::Matrix3d(0.5 * (F0 + F0.transpose()) - Eigen::Matrix3d::Identity())
                                      : Eigen::Matrix3d(0.5 * (F0.transpose() * F0 - Eigen::Matrix3d::Identity()));
    auto stressAt = [&](const Eigen::Matrix3d& E) {
      const Eigen::Matrix3d F = linear ? Eigen::Matrix3d(Eigen::Matrix3d::Identity() + E)
                                       : Eigen::Matrix3d(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(
                                                             Eigen::Matrix3d::Identity() + 2 * E)
                                                             .operatorSqrt());
      ddc::Vector6d S;
      m->evaluate(F, &S, nullptr);
      return S;
    };
    ddc::Matrix6d D, fd;
    m->evaluate(linear ? Eigen::Matrix3d(Eigen::Matrix3d::Identity() + E0) : F0, nullptr, &D);
    for (int b = 0; b < 6; ++b) {
      ddc::Vector6d e = ddc::Vector6d::Zero();
      e(b) = kFdStep;
      const Eigen::Matrix3d dE = fromVoigt(e, 0.5);
      fd.col(b) = (stressAt(E0 + dE) - stressAt(E0 - dE)) / (2 * kFdStep);
    }
    EXPECT_LT((fd - D).norm(), kFiniteDifference * D.norm()) << m->typeName();
    EXPECT_LT((D - D.transpose()).norm(), kRoundoff * D.norm()) << m->typeName();
  }
}

TEST(Material3d, ReferenceTangentIsIsotropicElasticity) {
  // At F = I every law has W = 0, S = 0 and D = the small-strain matrix.
  const double la = 300.0 / 0.52, mu = 1000.0 / 2.6;
  ddc::Matrix6d Dlin = ddc::Matrix6d::Zero();
  Dlin.topLeftCorner<3, 3>().setConstant(la);
  Dlin.diagonal() << la + 2 * mu, la + 2 * mu, la + 2 * mu, mu, mu, mu;
  for (const auto& m : allMaterials()) {
    ddc::Vector6d S;
    ddc::Matrix6d D;
    EXPECT_EQ(m->evaluate(Eigen::Matrix3d::Identity(), &S, &D), 0.0) << m->typeName();
    EXPECT_LT(S.norm(), kRoundoff * mu) << m->typeName();
    EXPECT_LT((D - Dlin).norm(), kRoundoff * Dlin.norm()) << m->typeName();
  }
}

TEST(Material3d, RigidRotationIsStressFree) {
  // 90 degrees about an axis along no coordinate direction.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(std::acos(0.0), Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const auto& m : allMaterials()) {
    if (m->isGeometricallyLinear()) continue;
    ddc::Vector6d S;
    EXPECT_LT(std::abs(m->evaluate(R, &S, nullptr)), kRoundoff * m->mu()) << m->typeName();
    EXPECT_LT(S.norm(), kRoundoff * m->mu()) << m->typeName();
  }
}

TEST(Material3d, NeoHookeanTriaxialStretchClosedForm) {
  // F = diag(l1, l2, l3): W = mu/2 (sum l_i^2 - 3) - mu ln J + lambda/2 (ln J)^2,
  // S_ii = mu (1 - 1/l_i^2) + lambda ln J / l_i^2, no shear.
  ddc::NeoHookean m(1000.0, 0.3);
  const Eigen::Vector3d l(1.3, 0.8, 1.1);
  const double J = l.prod(), mu = m.mu(), la = m.lambda();
  ddc::Vector6d S;
  const double W = m.evaluate(Eigen::Matrix3d(l.asDiagonal()), &S, nullptr);
  EXPECT_NEAR(W, 0.5 * mu * (l.squaredNorm() - 3) - mu * std::log(J) + 0.5 * la * std::log(J) * std::log(J),
              kRoundoff * mu);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(S(i), mu * (1 - 1 / (l(i) * l(i))) + la * std::log(J) / (l(i) * l(i)), kRoundoff * mu);
  EXPECT_LT(S.tail<3>().norm(), kRoundoff * mu);
  EXPECT_THROW(m.evaluate(Eigen::Matrix3d(Eigen::Vector3d(-1, 1, 1).asDiagonal()), nullptr, nullptr),
               ddc::InadmissibleDeformation);
}

TEST(Material3d, PlaneStrainIsThe3dLawWithF33EqualOne) {
  // The 2-D evaluation equals the 3-D one at F = [[F2, 0], [0, 1]]: W, the
  // in-plane stress and tangent (Voigt slots 11, 22, 12 = 0, 1, 5), S33 =
  // stressZZ and no out-of-plane shear.
  const int slot[3] = {0, 1, 5};
  for (const auto& m : allMaterials()) {
    const Eigen::Matrix3d F3 = randomF(9);
    Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
    F.topLeftCorner<2, 2>() = F3.topLeftCorner<2, 2>();
    Eigen::Vector3d S2;
    Eigen::Matrix3d D2;
    ddc::Vector6d S;
    ddc::Matrix6d D;
    const double W2 = m->evaluate(Eigen::Matrix2d(F.topLeftCorner<2, 2>()), &S2, &D2);
    EXPECT_LT(relDiff(m->evaluate(F, &S, &D), W2), kRoundoff) << m->typeName();
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(S(slot[a]), S2(a), kRoundoff * S2.norm()) << m->typeName();
      for (int b = 0; b < 3; ++b) EXPECT_NEAR(D(slot[a], slot[b]), D2(a, b), kRoundoff * D2.norm()) << m->typeName();
    }
    EXPECT_NEAR(S(2), m->stressZZ(Eigen::Matrix2d(F.topLeftCorner<2, 2>())), kRoundoff * S2.norm()) << m->typeName();
    EXPECT_LT(std::abs(S(3)) + std::abs(S(4)), kRoundoff * S2.norm()) << m->typeName();
  }
}

}  // namespace
