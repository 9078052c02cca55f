// Materials: parameter validation, Lamé constants, closed-form values of the
// energy and stress at simple deformations.
#include <gtest/gtest.h>

#include <cmath>

#include "DDC_Element.hpp"
#include "DDC_Error.hpp"
#include "DDC_Material.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

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

}  // namespace
