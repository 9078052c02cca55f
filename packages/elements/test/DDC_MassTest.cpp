// Mass matrices of the continuum elements (ContinuumElement::mass, the
// Material's Density): for every element type, consistent and lumped,
//  - the total mass is ρV and a rigid translation's kinetic energy is exact;
//  - the consistent matrix gives the exact kinetic energy of any linear
//    velocity field on an affine element (closed-form second moments of the
//    reference cell, independent of the quadrature);
//  - it is the Hessian of the kinetic energy T(v) = ½ ∫ ρ |v_h|² dV computed
//    point by point here (central differences), symmetric and positive
//    definite;
//  - RowSum is the consistent matrix's row sums, HRZ its diagonal scaled to
//    the total mass (positive for every type), and RowSum is not positive at
//    the corners of Hex20 and Tet10 (the reason HRZ exists).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>

#include "DDC_ElementTestSupport.hpp"
#include "DDC_Error.hpp"
#include "DDC_ReferenceCell.hpp"
#include "DDC_ShapeFunctions.hpp"

namespace {

using ddc::CellType;
using ddc::MassLumping;

/// Mass density of the test material.
constexpr double kRho = 2.7;
/// Round-off of sums over ~1000 quadrature products relative to ρV.
constexpr double kRoundoff = 1e-12;
/// Central second differences of a quadratic form: exact up to the
/// cancellation eps |T| / h², with h = 1e-3 and |T| ~ 1.
constexpr double kFiniteDifference = 1e-6;

const CellType kTypes[] = {CellType::Quad4, CellType::Quad9, CellType::Hex8, CellType::Hex20,
                           CellType::Hex27, CellType::Tet4,  CellType::Tet10};

std::shared_ptr<ddc::Element> massElement(CellType type) {
  Teuchos::ParameterList p;
  p.set("Type", std::string(ddc::cellTypeName(type)));
  p.sublist("Material").set("Type", std::string("Neo-Hookean"));
  p.sublist("Material").set("Density", kRho);
  return ddc::ElementFactory::withBuiltins().create(p, "Element");
}

/// An affine, non-orthogonal map x = A ξ + b of the reference cell.
struct Affine {
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
  explicit Affine(int d) {
    A = Eigen::MatrixXd::Identity(d, d);
    A(0, 1) = 0.3;
    A(1, 0) = -0.2;
    A(0, 0) = 1.7;
    A(1, 1) = 0.9;
    if (d == 3) A(2, 0) = 0.25, A(1, 2) = 0.1, A(2, 2) = 1.3;
    b = Eigen::VectorXd::LinSpaced(d, 0.5, 1.5);
  }
};

/// Node coordinates of the reference cell under the map (numNodes x d).
Eigen::MatrixXd mappedNodes(CellType type, const Affine& m) {
  const ddc::ReferenceCell& ref = ddc::referenceCell(type);
  Eigen::MatrixXd X(ref.numNodes, ref.dim);
  for (int a = 0; a < ref.numNodes; ++a) {
    Eigen::VectorXd xi(ref.dim);
    for (int k = 0; k < ref.dim; ++k) xi[k] = ref.nodes[a][k];
    X.row(a) = (m.A * xi + m.b).transpose();
  }
  return X;
}

/// Volume, first and second moments of the reference cell: V_ref, ∫ξ, ∫ξξᵀ.
void referenceMoments(CellType type, double& V, Eigen::VectorXd& first, Eigen::MatrixXd& second) {
  const ddc::ReferenceCell& ref = ddc::referenceCell(type);
  const int d = ref.dim;
  if (ref.simplex) {  // the unit tetrahedron
    V = 1.0 / 6.0;
    first = Eigen::VectorXd::Constant(d, 1.0 / 24.0);
    second = Eigen::MatrixXd::Constant(d, d, 1.0 / 120.0);
    second.diagonal().setConstant(1.0 / 60.0);
  } else {  // [-1, 1]^d
    V = std::pow(2.0, d);
    first = Eigen::VectorXd::Zero(d);
    second = Eigen::MatrixXd::Identity(d, d) * (V / 3.0);
  }
}

/// The element's volume and ∫ x dV, ∫ x xᵀ dV under the affine map.
void physicalMoments(CellType type, const Affine& m, double& V, Eigen::VectorXd& first, Eigen::MatrixXd& second) {
  double Vr;
  Eigen::VectorXd fr;
  Eigen::MatrixXd sr;
  referenceMoments(type, Vr, fr, sr);
  const double J = m.A.determinant();
  V = J * Vr;
  first = J * (m.A * fr + Vr * m.b);
  second = J * (m.A * sr * m.A.transpose() + m.A * fr * m.b.transpose() + m.b * fr.transpose() * m.A.transpose() +
                Vr * m.b * m.b.transpose());
}

/// T(v) = ½ ∫ ρ |Σ_a N_a v_a|² dV, point by point (not through mass()).
double kineticEnergy(CellType type, const Eigen::MatrixXd& X, const Eigen::VectorXd& v) {
  const int n = X.rows(), d = X.cols();
  const ddc::QuadratureRule& rule = ddc::massQuadratureRule(type);
  double T = 0.0;
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (size_t q = 0; q < rule.points.size(); ++q) {
    ddc::shapeFunctions(type, rule.points[q], &N, &dN);
    Eigen::VectorXd vq = Eigen::VectorXd::Zero(d);
    for (int a = 0; a < n; ++a) vq += N[a] * v.segment(d * a, d);
    T += 0.5 * kRho * rule.weights[q] * (X.transpose() * dN).determinant() * vq.squaredNorm();
  }
  return T;
}

/// The element of a type with density kRho on the affine map, and the exact
/// volume and moments of that element.
struct AffineCase {
  std::shared_ptr<ddc::Element> el;
  Eigen::MatrixXd X;
  double V = 0.0;
  Eigen::VectorXd first;
  Eigen::MatrixXd second;
  int d = 0, n = 0;
  explicit AffineCase(CellType type) : el(massElement(type)) {
    const Affine map(el->dim());
    X = mappedNodes(type, map);
    physicalMoments(type, map, V, first, second);
    d = el->dim();
    n = el->numNodes();
  }
};

class Mass : public testing::TestWithParam<CellType> {};

TEST_P(Mass, TotalMassAndRigidTranslation) {
  const CellType type = GetParam();
  const AffineCase k(type);
  const auto& [el, X, V, first, second, d, n] = k;
  ASSERT_TRUE(el->hasMass());
  Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(d, 0.4, -0.7);
  Eigen::VectorXd v(n * d);
  for (int a = 0; a < n; ++a) v.segment(d * a, d) = c;
  double worst = 0.0;
  for (MassLumping l : {MassLumping::Consistent, MassLumping::RowSum, MassLumping::HRZ}) {
    Eigen::MatrixXd M;
    el->mass(X, l, M);
    ASSERT_EQ(M.rows(), n * d);
    double total = 0.0;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) total += M(d * a, d * b);
    EXPECT_NEAR(total / (kRho * V), 1.0, kRoundoff) << ddc::cellTypeName(type) << " lumping " << int(l);
    const double T = 0.5 * v.dot(M * v) / (0.5 * kRho * V * c.squaredNorm());
    EXPECT_NEAR(T, 1.0, kRoundoff) << ddc::cellTypeName(type) << " lumping " << int(l)
                                   << ": kinetic energy of a rigid translation";
    worst = std::max({worst, std::abs(total / (kRho * V) - 1.0), std::abs(T - 1.0)});
  }
  std::cout << "[mass] " << ddc::cellTypeName(type) << " total mass and rigid translation, worst relative error "
            << worst << "\n";
}

TEST_P(Mass, ConsistentMassIsExactForLinearVelocityFields) {
  const CellType type = GetParam();
  const AffineCase k(type);
  const auto& [el, X, V, first, second, d, n] = k;
  Eigen::MatrixXd M;
  el->mass(X, MassLumping::Consistent, M);
  double worst = 0.0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    // v(x) = B x + c: every element interpolates it exactly.
    const Eigen::MatrixXd B = ddc::test::randomNodal(d, d, 1.0, seed);
    const Eigen::VectorXd c = ddc::test::randomNodal(d, 1, 1.0, seed + 100);
    Eigen::VectorXd v(n * d);
    for (int a = 0; a < n; ++a) v.segment(d * a, d) = B * X.row(a).transpose() + c;
    // ½ ρ ∫ |Bx + c|² dV = ½ ρ (tr(Bᵀ B ∫xxᵀ) + 2 cᵀ B ∫x + |c|² V).
    const double exact = 0.5 * kRho * ((B.transpose() * B * second).trace() + 2 * c.dot(B * first) + c.squaredNorm() * V);
    EXPECT_NEAR(0.5 * v.dot(M * v) / exact, 1.0, kRoundoff) << ddc::cellTypeName(type) << " seed " << seed;
    worst = std::max(worst, std::abs(0.5 * v.dot(M * v) / exact - 1.0));
  }
  std::cout << "[mass] " << ddc::cellTypeName(type) << " linear velocity fields, worst relative error " << worst
            << "\n";
}

TEST_P(Mass, ConsistentMassIsTheHessianOfTheKineticEnergy) {
  const CellType type = GetParam();
  const auto el = massElement(type);
  const Affine map(el->dim());
  // A curved element too: the reference nodes perturbed (mid-side nodes off
  // their sides), which the check does not need to be affine.
  Eigen::MatrixXd X = mappedNodes(type, map) + ddc::test::randomNodal(el->numNodes(), el->dim(), 0.05, 7);
  const int m = el->numNodes() * el->dim();
  Eigen::MatrixXd M;
  el->mass(X, MassLumping::Consistent, M);
  const Eigen::VectorXd v0 = ddc::test::flatten(ddc::test::randomNodal(el->numNodes(), el->dim(), 1.0, 3));
  const double h = 1e-3;
  double worst = 0.0;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      auto T = [&](double si, double sj) {
        Eigen::VectorXd v = v0;
        v[i] += si * h;
        v[j] += sj * h;
        return kineticEnergy(type, X, v);
      };
      const double fd = (T(1, 1) - T(1, -1) - T(-1, 1) + T(-1, -1)) / (4 * h * h);
      worst = std::max(worst, std::abs(fd - M(i, j)));
    }
  EXPECT_LT(worst / M.cwiseAbs().maxCoeff(), kFiniteDifference) << ddc::cellTypeName(type);
  std::cout << "[mass] " << ddc::cellTypeName(type) << " Hessian of the kinetic energy, worst relative FD error "
            << worst / M.cwiseAbs().maxCoeff() << "\n";
  EXPECT_LT((M - M.transpose()).cwiseAbs().maxCoeff(), kRoundoff * M.cwiseAbs().maxCoeff());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues().minCoeff(), 0.0)
      << ddc::cellTypeName(type) << ": the consistent mass is positive definite";
}

TEST_P(Mass, LumpedMatrices) {
  const CellType type = GetParam();
  const auto el = massElement(type);
  const Eigen::MatrixXd X = mappedNodes(type, Affine(el->dim()));
  Eigen::MatrixXd Mc, Mr, Mh;
  el->mass(X, MassLumping::Consistent, Mc);
  el->mass(X, MassLumping::RowSum, Mr);
  el->mass(X, MassLumping::HRZ, Mh);
  const double scale = Mc.cwiseAbs().maxCoeff();
  EXPECT_LT((Mr - Eigen::MatrixXd(Mc.rowwise().sum().asDiagonal())).cwiseAbs().maxCoeff(), kRoundoff * scale);
  const Eigen::VectorXd hrz = Mc.diagonal() * (Mc.sum() / Mc.diagonal().sum());
  EXPECT_LT((Mh - Eigen::MatrixXd(hrz.asDiagonal())).cwiseAbs().maxCoeff(), kRoundoff * scale);
  EXPECT_GT(Mh.diagonal().minCoeff(), 0.0) << ddc::cellTypeName(type) << ": HRZ masses are positive";
  const bool serendipityOrQuadraticTet = type == CellType::Hex20 || type == CellType::Tet10;
  EXPECT_EQ(Mr.diagonal().minCoeff() > 0.0, !serendipityOrQuadraticTet)
      << ddc::cellTypeName(type) << ": row-sum masses " << Mr.diagonal().transpose();
}

TEST_P(Mass, RedistributionMovesTheMassOfFlaggedNodesAndKeepsTheTotal) {
  // Contact-surface mass redistribution (Khenous, Laborde & Renard 2008):
  // the flagged nodes' rows and columns vanish, the element keeps its mass
  // and a rigid translation its kinetic energy, the rest stays positive
  // definite, and a lumped matrix stays diagonal.
  const CellType type = GetParam();
  const AffineCase k(type);
  const auto& [el, X, V, first, second, d, n] = k;
  std::vector<char> flagged(n, 0);
  flagged[0] = flagged[1] = 1;  // two corners: on one edge of every type
  for (MassLumping l : {MassLumping::Consistent, MassLumping::HRZ}) {
    Eigen::MatrixXd M;
    el->mass(X, l, M);
    const Eigen::MatrixXd before = M;
    ASSERT_TRUE(ddc::redistributeNodalMass(M, flagged, d));
    EXPECT_NEAR(M.sum() / before.sum(), 1.0, kRoundoff) << ddc::cellTypeName(type);
    const double scale = before.cwiseAbs().maxCoeff();
    for (int a = 0; a < n * d; ++a)
      if (flagged[a / d]) {
        EXPECT_EQ(M.row(a).cwiseAbs().maxCoeff(), 0.0);
        EXPECT_EQ(M.col(a).cwiseAbs().maxCoeff(), 0.0);
      }
    std::vector<int> kept;
    for (int a = 0; a < n * d; ++a)
      if (!flagged[a / d]) kept.push_back(a);
    Eigen::MatrixXd Mk(kept.size(), kept.size());
    for (size_t i = 0; i < kept.size(); ++i)
      for (size_t j = 0; j < kept.size(); ++j) Mk(i, j) = M(kept[i], kept[j]);
    EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(Mk).info(), Eigen::Success) << ddc::cellTypeName(type);
    if (l == MassLumping::HRZ) {
      EXPECT_LT((M - Eigen::MatrixXd(M.diagonal().asDiagonal())).cwiseAbs().maxCoeff(), kRoundoff * scale);
    }
    Eigen::VectorXd v(n * d);
    for (int a = 0; a < n; ++a) v.segment(d * a, d) = Eigen::VectorXd::Constant(d, 0.3);
    EXPECT_NEAR(v.dot(M * v) / v.dot(before * v), 1.0, kRoundoff);
  }
  // Nowhere to move the mass: refused, M unchanged.
  Eigen::MatrixXd M;
  el->mass(X, MassLumping::Consistent, M);
  const Eigen::MatrixXd before = M;
  EXPECT_FALSE(ddc::redistributeNodalMass(M, std::vector<char>(n, 1), d));
  EXPECT_EQ((M - before).cwiseAbs().maxCoeff(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(EveryElementType, Mass, testing::ValuesIn(kTypes),
                         [](const testing::TestParamInfo<CellType>& i) { return ddc::cellTypeName(i.param); });

TEST(MassDensity, NoDensityNoMass) {
  // Density defaults to 0: the element has no mass, and asking for it is a
  // programming error (a dynamic analysis checks hasMass() first).
  const auto el = ddc::test::makeTestElement("Quad4", "Neo-Hookean");
  EXPECT_FALSE(el->hasMass());
  Eigen::MatrixXd M;
  EXPECT_THROW(el->mass(mappedNodes(CellType::Quad4, Affine(2)), MassLumping::Consistent, M), std::logic_error);
}

TEST(MassDensity, NegativeOrNonFiniteDensityIsAnInputError) {
  for (double rho : {-1.0, std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()}) {
    Teuchos::ParameterList p;
    p.set("Type", std::string("Hex8"));
    p.sublist("Material").set("Density", rho);
    try {
      ddc::ElementFactory::withBuiltins().create(p, "Mesh/Bodies/Ball/Element");
      ADD_FAILURE() << "density " << rho << " accepted";
    } catch (const ddc::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("Mesh/Bodies/Ball/Element/Material/Density"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
