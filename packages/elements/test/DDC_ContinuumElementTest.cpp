// Continuum elements Quad4 / Quad9 with each material: derivative checks
// against central finite differences, symmetry, rigid-body invariance,
// homogeneous deformations against the closed-form laws, inverted elements.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>

#include "DDC_ContinuumElement.hpp"
#include "DDC_ElementTestSupport.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using ddc::test::flatten;
using ddc::test::homogeneousDisplacement;
using ddc::test::kDisplacementScale;
using ddc::test::kFdStep;
using ddc::test::kFiniteDifference;
using ddc::test::kRoundoff;
using ddc::test::makeTestElement;
using ddc::test::relDiff;
using ddc::test::unflatten;

constexpr double kE = ddc::test::kTestE;
constexpr double kNu = ddc::test::kTestNu;

Eigen::MatrixX2d randomDisplacement(int n, unsigned seed) {
  return ddc::test::randomNodal(n, 2, kDisplacementScale, seed);
}

/// A distorted, non-parallelogram quadrilateral (counter-clockwise corners).
Eigen::MatrixX2d distortedCorners() {
  Eigen::MatrixX2d X(4, 2);
  X << 0.0, 0.0,  //
      2.1, 0.3,   //
      2.4, 1.9,   //
      -0.3, 1.6;
  return X;
}

/// Quad9 on the distorted corners with curved edges (mid-side nodes off the
/// chords) and an off-centre centre node.
Eigen::MatrixX2d distortedQuad9() {
  const Eigen::MatrixX2d c = distortedCorners();
  Eigen::MatrixX2d X(9, 2);
  X.topRows(4) = c;
  X.row(4) = 0.5 * (c.row(0) + c.row(1)) + Eigen::RowVector2d(0.05, -0.08);
  X.row(5) = 0.5 * (c.row(1) + c.row(2)) + Eigen::RowVector2d(0.07, 0.03);
  X.row(6) = 0.5 * (c.row(2) + c.row(3)) + Eigen::RowVector2d(-0.04, 0.06);
  X.row(7) = 0.5 * (c.row(3) + c.row(0)) + Eigen::RowVector2d(-0.06, -0.02);
  X.row(8) = 0.25 * (c.row(0) + c.row(1) + c.row(2) + c.row(3)) + Eigen::RowVector2d(0.07, 0.04);
  return X;
}

/// Quad9 with straight edges (area = polygon area of the corners): mid-side
/// nodes slid along the edges, centre node moved.
Eigen::MatrixX2d straightEdgedQuad9() {
  const Eigen::MatrixX2d c = distortedCorners();
  Eigen::MatrixX2d X(9, 2);
  X.topRows(4) = c;
  X.row(4) = 0.45 * c.row(0) + 0.55 * c.row(1);
  X.row(5) = 0.52 * c.row(1) + 0.48 * c.row(2);
  X.row(6) = 0.5 * c.row(2) + 0.5 * c.row(3);
  X.row(7) = 0.47 * c.row(3) + 0.53 * c.row(0);
  X.row(8) = 0.25 * (c.row(0) + c.row(1) + c.row(2) + c.row(3)) + Eigen::RowVector2d(0.05, -0.03);
  return X;
}

double shoelaceArea(const Eigen::MatrixX2d& c) {
  double a = 0;
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    a += c(i, 0) * c(j, 1) - c(j, 0) * c(i, 1);
  }
  return 0.5 * a;
}

Eigen::MatrixX2d referenceFor(const std::string& elem) {
  return elem == "Quad4" ? distortedCorners() : distortedQuad9();
}

// --------------------------------------------------- element x material grid

class ElementMaterial : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {
 protected:
  std::string elem() const { return std::get<0>(GetParam()); }
  std::string mat() const { return std::get<1>(GetParam()); }
};

TEST_P(ElementMaterial, ResidualMatchesEnergyFiniteDifferences) {
  auto el = makeTestElement(elem(), mat());
  const Eigen::MatrixX2d X = referenceFor(elem());
  const Eigen::MatrixX2d u = randomDisplacement(el->numNodes(), 17);
  ddc::ElementPostResult post;
  el->postprocess(X, u, post);
  ASSERT_GT(post.minDetJ, 0.5) << "test state should be a moderate deformation";

  ddc::ElementResult r;
  el->compute(X, u, ddc::kAll, r);
  const Eigen::VectorXd v = flatten(u);
  Eigen::VectorXd fd(v.size());
  for (int i = 0; i < v.size(); ++i) {
    Eigen::VectorXd vp = v, vm = v;
    vp(i) += kFdStep;
    vm(i) -= kFdStep;
    ddc::ElementResult rp, rm;
    el->compute(X, unflatten(vp, 2), ddc::kEnergy, rp);
    el->compute(X, unflatten(vm, 2), ddc::kEnergy, rm);
    fd(i) = (rp.energy - rm.energy) / (2 * kFdStep);
  }
  ASSERT_EQ(r.residual.size(), v.size());
  EXPECT_GT(r.residual.norm(), 1.0) << "a non-trivial state is needed for a meaningful check";
  EXPECT_LT((r.residual - fd).norm(), kFiniteDifference * r.residual.norm())
      << "analytic:\n" << r.residual.transpose() << "\nFD:\n" << fd.transpose();
}

TEST_P(ElementMaterial, TangentMatchesResidualFiniteDifferencesAndIsSymmetric) {
  auto el = makeTestElement(elem(), mat());
  const Eigen::MatrixX2d X = referenceFor(elem());
  const Eigen::MatrixX2d u = randomDisplacement(el->numNodes(), 23);
  ddc::ElementResult r;
  el->compute(X, u, ddc::kAll, r);
  const Eigen::VectorXd v = flatten(u);
  Eigen::MatrixXd fd(v.size(), v.size());
  for (int i = 0; i < v.size(); ++i) {
    Eigen::VectorXd vp = v, vm = v;
    vp(i) += kFdStep;
    vm(i) -= kFdStep;
    ddc::ElementResult rp, rm;
    el->compute(X, unflatten(vp, 2), ddc::kResidual, rp);
    el->compute(X, unflatten(vm, 2), ddc::kResidual, rm);
    fd.col(i) = (rp.residual - rm.residual) / (2 * kFdStep);
  }
  ASSERT_EQ(r.tangent.rows(), v.size());
  ASSERT_EQ(r.tangent.cols(), v.size());
  EXPECT_LT((r.tangent - fd).norm(), kFiniteDifference * r.tangent.norm());
  // Hyperelastic: K is a Hessian, symmetric up to round-off.
  EXPECT_LT((r.tangent - r.tangent.transpose()).norm(), kRoundoff * r.tangent.norm());
}

TEST_P(ElementMaterial, HomogeneousDeformationGivesClosedFormStress) {
  auto el = makeTestElement(elem(), mat());
  const Eigen::MatrixX2d X = elem() == "Quad4" ? distortedCorners() : straightEdgedQuad9();
  const double area = shoelaceArea(distortedCorners());
  Eigen::Matrix2d F;
  F << 1.2, 0.15,  //
      -0.1, 0.9;
  const Eigen::MatrixX2d u = homogeneousDisplacement(X, F);

  // Closed-form laws, written in a form independent of the element code.
  const double mu = kE / (2 * (1 + kNu)), la = kE * kNu / ((1 + kNu) * (1 - 2 * kNu));
  const double J = F.determinant();
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  double W = 0;
  Eigen::Matrix2d sigma;
  double sigmaZZ = 0;
  if (mat() == "Neo-Hookean") {
    // Spatial form: sigma = mu/J (b - I) + lambda ln J / J I, b = F F^T,
    // b33 = 1 so sigma_zz = lambda ln J / J.
    const Eigen::Matrix2d b = F * F.transpose();
    W = 0.5 * mu * (b.trace() + 1 - 3) - mu * std::log(J) + 0.5 * la * std::log(J) * std::log(J);
    sigma = mu / J * (b - I) + la * std::log(J) / J * I;
    sigmaZZ = la * std::log(J) / J;
  } else if (mat() == "St. Venant-Kirchhoff") {
    const Eigen::Matrix2d E = 0.5 * (F.transpose() * F - I);
    const Eigen::Matrix2d S = la * E.trace() * I + 2 * mu * E;
    W = 0.5 * la * E.trace() * E.trace() + mu * (E.array() * E.array()).sum();
    sigma = F * S * F.transpose() / J;
    sigmaZZ = la * E.trace() / J;
  } else {
    const Eigen::Matrix2d eps = 0.5 * (F + F.transpose()) - I;
    W = 0.5 * la * eps.trace() * eps.trace() + mu * (eps.array() * eps.array()).sum();
    sigma = la * eps.trace() * I + 2 * mu * eps;
    sigmaZZ = la * eps.trace();
  }

  ddc::ElementResult r;
  el->compute(X, u, ddc::kEnergy, r);
  EXPECT_LT(relDiff(r.energy, W * area), kRoundoff);
  ddc::ElementPostResult post;
  el->postprocess(X, u, post);
  EXPECT_LT(relDiff(post.energyDensity, W), kRoundoff);
  const double scale = sigma.norm();
  EXPECT_NEAR(post.cauchy[0], sigma(0, 0), kRoundoff * scale);
  EXPECT_NEAR(post.cauchy[1], sigma(1, 1), kRoundoff * scale);
  EXPECT_NEAR(post.cauchy[5], sigma(0, 1), kRoundoff * scale);
  EXPECT_NEAR(post.cauchy[2], sigmaZZ, kRoundoff * scale);
  EXPECT_LT(relDiff(post.minDetJ, J), kRoundoff);
}

TEST_P(ElementMaterial, NodeForcesAreSelfEquilibrated) {
  // Translation invariance of U_e: the element's nodal forces sum to zero.
  // Rotation invariance (not for the small-strain law): zero net moment
  // about the origin, sum_a x_a x f_a = 0 with x_a the current positions.
  auto el = makeTestElement(elem(), mat());
  const Eigen::MatrixX2d X = referenceFor(elem());
  const Eigen::MatrixX2d u = randomDisplacement(el->numNodes(), 5);
  ddc::ElementResult r;
  el->compute(X, u, ddc::kResidual, r);
  const Eigen::MatrixX2d f = unflatten(r.residual, 2);
  EXPECT_LT(f.colwise().sum().norm(), kRoundoff * f.norm());
  if (mat() != "Linear Elastic") {
    const Eigen::MatrixX2d x = X + u;
    double m = 0;
    for (int a = 0; a < x.rows(); ++a) m += x(a, 0) * f(a, 1) - x(a, 1) * f(a, 0);
    EXPECT_LT(std::abs(m), kRoundoff * f.norm() * x.norm());
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllElementsAndMaterials, ElementMaterial,
    ::testing::Combine(::testing::Values("Quad4", "Quad9"),
                       ::testing::Values("Neo-Hookean", "St. Venant-Kirchhoff", "Linear Elastic")),
    [](const ::testing::TestParamInfo<ElementMaterial::ParamType>& info) {
      std::string m = std::get<1>(info.param);
      std::string clean;
      for (char c : m)
        if (std::isalnum(static_cast<unsigned char>(c))) clean += c;
      return std::get<0>(info.param) + "_" + clean;
    });

// ----------------------------------------------------------- finite strain

class FiniteStrainElement : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(FiniteStrainElement, RigidRotationIsStressFree) {
  const auto& [elem, mat] = GetParam();
  auto el = makeTestElement(elem, mat);
  const Eigen::MatrixX2d X = referenceFor(elem);
  Eigen::Matrix2d R;
  R << 0, -1, 1, 0;  // 90 degrees
  const Eigen::MatrixX2d u = homogeneousDisplacement(X, R);
  ddc::ElementResult r;
  el->compute(X, u, ddc::kAll, r);
  // Reference magnitudes: E * area for the energy, E * size for forces.
  EXPECT_LT(std::abs(r.energy), kRoundoff * kE * 4.0);
  EXPECT_LT(r.residual.norm(), kRoundoff * kE * 2.0);
  ddc::ElementPostResult post;
  el->postprocess(X, u, post);
  for (double s : post.cauchy) EXPECT_LT(std::abs(s), kRoundoff * kE);
  EXPECT_LT(relDiff(post.minDetJ, 1.0), kRoundoff);
  // The same displacement is a large strain for the small-strain law, which
  // shows this test can fail.
  auto lin = makeTestElement(elem, "Linear Elastic");
  lin->compute(X, u, ddc::kEnergy, r);
  EXPECT_GT(r.energy, 0.1 * kE);
}

TEST_P(FiniteStrainElement, RejectsNonPositiveDetF) {
  const auto& [elem, mat] = GetParam();
  auto el = makeTestElement(elem, mat);
  const Eigen::MatrixX2d X = referenceFor(elem);
  Eigen::Matrix2d F;
  F << -1, 0, 0, 1;  // reflection, det F = -1
  ddc::test::expectDetFRejected(*el, X, F);
}

INSTANTIATE_TEST_SUITE_P(NeoHookeanAndSVK, FiniteStrainElement,
                         ::testing::Combine(::testing::Values("Quad4", "Quad9"),
                                            ::testing::Values("Neo-Hookean", "St. Venant-Kirchhoff")),
                         [](const ::testing::TestParamInfo<FiniteStrainElement::ParamType>& info) {
                           return std::get<0>(info.param) +
                                  (std::get<1>(info.param) == "Neo-Hookean" ? "_NeoHookean" : "_SVK");
                         });

// ------------------------------------------------------------ small strain

class SmallStrainElement : public ::testing::TestWithParam<std::string> {};

TEST_P(SmallStrainElement, EnergyIsQuadraticAndInfinitesimalRotationIsFree) {
  auto el = makeTestElement(GetParam(), "Linear Elastic");
  const Eigen::MatrixX2d X = referenceFor(GetParam());
  const Eigen::MatrixX2d u = randomDisplacement(el->numNodes(), 99);
  ddc::ElementResult r;
  el->compute(X, u, ddc::kAll, r);
  const Eigen::VectorXd v = flatten(u);
  // Geometrically linear: f = K u and U = u.K.u / 2 exactly.
  EXPECT_LT((r.residual - r.tangent * v).norm(), kRoundoff * r.residual.norm());
  EXPECT_LT(relDiff(r.energy, 0.5 * v.dot(r.tangent * v)), kRoundoff);
  // Infinitesimal rotation u = theta (-Y, X) has eps = 0.
  Eigen::MatrixX2d rot(X.rows(), 2);
  rot.col(0) = -0.3 * X.col(1);
  rot.col(1) = 0.3 * X.col(0);
  el->compute(X, rot, ddc::kAll, r);
  EXPECT_LT(std::abs(r.energy), kRoundoff * kE);
  EXPECT_LT(r.residual.norm(), kRoundoff * kE);
}

INSTANTIATE_TEST_SUITE_P(Quads, SmallStrainElement, ::testing::Values("Quad4", "Quad9"));

// --------------------------------------------------- reference geometry

TEST(ContinuumElement, ReferenceJacobian) {
  auto q4 = makeTestElement("Quad4", "Neo-Hookean");
  auto q9 = makeTestElement("Quad9", "Neo-Hookean");
  // Rectangle [0,2] x [0,1]: dX/dxi = diag(1, 0.5), det = 0.5 everywhere.
  Eigen::MatrixX2d rect(9, 2);
  rect << 0, 0, 2, 0, 2, 1, 0, 1, 1, 0, 2, 0.5, 1, 1, 0, 0.5, 1, 0.5;
  EXPECT_LT(relDiff(q4->minReferenceJacobian(rect.topRows(4)), 0.5), kRoundoff);
  EXPECT_LT(relDiff(q9->minReferenceJacobian(rect), 0.5), kRoundoff);
  EXPECT_GT(q4->minReferenceJacobian(distortedCorners()), 0.0);
  EXPECT_GT(q9->minReferenceJacobian(distortedQuad9()), 0.0);

  // Clockwise node order (corners reversed; Quad9 mid-sides follow).
  Eigen::MatrixX2d cw4(4, 2);
  cw4 << rect.row(0), rect.row(3), rect.row(2), rect.row(1);
  EXPECT_LT(q4->minReferenceJacobian(cw4), 0.0);
  Eigen::MatrixX2d cw9(9, 2);
  cw9 << rect.row(0), rect.row(3), rect.row(2), rect.row(1), rect.row(7), rect.row(6), rect.row(5),
      rect.row(4), rect.row(8);
  EXPECT_LT(q9->minReferenceJacobian(cw9), 0.0);
  // Evaluating an inverted element is refused.
  ddc::ElementResult r;
  EXPECT_THROW(q4->compute(cw4, Eigen::MatrixX2d::Zero(4, 2), ddc::kAll, r), ddc::InadmissibleDeformation);
  EXPECT_THROW(q9->compute(cw9, Eigen::MatrixX2d::Zero(9, 2), ddc::kAll, r), ddc::InadmissibleDeformation);

  // A mid-side node pulled across the element folds the Quad9 map at a
  // corner while its corners alone look fine.
  Eigen::MatrixX2d bad = rect;
  bad.row(4) << 1.9, 0.0;
  EXPECT_LT(q9->minReferenceJacobian(bad), 0.0);
}

TEST(ContinuumElement, Sizes) {
  auto q4 = makeTestElement("Quad4", "St. Venant-Kirchhoff");
  auto q9 = makeTestElement("Quad9", "St. Venant-Kirchhoff");
  EXPECT_EQ(q4->numNodes(), 4);
  EXPECT_EQ(q9->numNodes(), 9);
  ddc::ElementResult r;
  q9->compute(distortedQuad9(), Eigen::MatrixX2d::Zero(9, 2), ddc::kAll, r);
  EXPECT_EQ(r.residual.size(), 18);
  EXPECT_EQ(r.tangent.rows(), 18);
  EXPECT_EQ(r.energy, 0.0);
  EXPECT_THROW(q9->compute(distortedCorners(), Eigen::MatrixX2d::Zero(4, 2), ddc::kAll, r),
               std::invalid_argument);
}

}  // namespace
