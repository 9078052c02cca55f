// Shape functions of every cell type (Kronecker delta at the nodes,
// partition of unity, gradients summing to zero and matching finite
// differences, reproduction of the polynomials the element should carry)
// and the quadrature rules of the element cells (exact up to their degree).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "DDC_ShapeFunctions.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using ddc::CellType;
using ddc::test::kFiniteDifference;
using ddc::test::kRoundoff;
using Point = std::array<double, 3>;

const std::vector<CellType> kAllCells = {CellType::Quad4, CellType::Quad9, CellType::Hex8,  CellType::Hex20,
                                         CellType::Hex27, CellType::Tet4,  CellType::Tet10, CellType::Line2,
                                         CellType::Line3, CellType::Tri3,  CellType::Tri6,  CellType::Quad8};

/// Random points inside the reference cell (a fixed seed).
std::vector<Point> interiorPoints(CellType t, int count) {
  const auto& c = ddc::referenceCell(t);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> box(-0.95, 0.95), unit(0.02, 0.95);
  std::vector<Point> pts;
  while (static_cast<int>(pts.size()) < count) {
    Point x{0, 0, 0};
    double sum = 0;
    for (int m = 0; m < c.dim; ++m) {
      x[m] = c.simplex && c.dim > 1 ? unit(gen) : box(gen);
      sum += x[m];
    }
    if (c.simplex && c.dim > 1 && sum > 0.98) continue;
    pts.push_back(x);
  }
  return pts;
}

/// Polynomial degree every cell reproduces exactly (complete polynomials).
int completeDegree(CellType t) {
  return t == CellType::Line2 || t == CellType::Quad4 || t == CellType::Hex8 || t == CellType::Tri3 ||
                 t == CellType::Tet4
             ? 1
             : 2;
}

class ShapeFunctions : public ::testing::TestWithParam<CellType> {};

TEST_P(ShapeFunctions, KroneckerDeltaAtNodes) {
  const auto& c = ddc::referenceCell(GetParam());
  Eigen::VectorXd N;
  for (int b = 0; b < c.numNodes; ++b) {
    ddc::shapeFunctions(GetParam(), c.nodes[b], &N, nullptr);
    ASSERT_EQ(N.size(), c.numNodes);
    for (int a = 0; a < c.numNodes; ++a)
      EXPECT_NEAR(N(a), a == b ? 1.0 : 0.0, kRoundoff) << "N_" << a << " at node " << b;
  }
}

TEST_P(ShapeFunctions, PartitionOfUnityAndGradients) {
  const auto& c = ddc::referenceCell(GetParam());
  Eigen::VectorXd N, Np, Nm;
  Eigen::MatrixXd dN;
  constexpr double h = 1e-6;  // FD step on the reference cell (size ~1)
  for (const Point& x : interiorPoints(GetParam(), 10)) {
    ddc::shapeFunctions(GetParam(), x, &N, &dN);
    ASSERT_EQ(dN.rows(), c.numNodes);
    ASSERT_EQ(dN.cols(), c.dim);
    EXPECT_NEAR(N.sum(), 1.0, kRoundoff);
    EXPECT_LT(dN.colwise().sum().norm(), kRoundoff * dN.norm());
    for (int k = 0; k < c.dim; ++k) {
      Point xp = x, xm = x;
      xp[k] += h;
      xm[k] -= h;
      ddc::shapeFunctions(GetParam(), xp, &Np, nullptr);
      ddc::shapeFunctions(GetParam(), xm, &Nm, nullptr);
      EXPECT_LT(((Np - Nm) / (2 * h) - dN.col(k)).norm(), kFiniteDifference * dN.norm()) << "direction " << k;
    }
  }
}

TEST_P(ShapeFunctions, ReproducesCompletePolynomials) {
  // sum_a N_a p(x_a) = p(x) for every monomial of degree <= completeDegree,
  // and the same for the gradients (isoparametric completeness).
  const auto& c = ddc::referenceCell(GetParam());
  const int deg = completeDegree(GetParam());
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (const Point& x : interiorPoints(GetParam(), 5))
    for (int e0 = 0; e0 <= deg; ++e0)
      for (int e1 = 0; e1 <= (c.dim > 1 ? deg - e0 : 0); ++e1)
        for (int e2 = 0; e2 <= (c.dim > 2 ? deg - e0 - e1 : 0); ++e2) {
          const int e[3] = {e0, e1, e2};
          auto p = [&](const Point& y) { return std::pow(y[0], e0) * std::pow(y[1], e1) * std::pow(y[2], e2); };
          ddc::shapeFunctions(GetParam(), x, &N, &dN);
          double value = 0;
          Eigen::Vector3d grad = Eigen::Vector3d::Zero();
          for (int a = 0; a < c.numNodes; ++a) {
            value += N(a) * p(c.nodes[a]);
            for (int k = 0; k < c.dim; ++k) grad(k) += dN(a, k) * p(c.nodes[a]);
          }
          EXPECT_NEAR(value, p(x), kRoundoff) << "monomial " << e0 << e1 << e2;
          for (int k = 0; k < c.dim; ++k) {
            // d/dx_k of the monomial.
            double dp = e[k] == 0 ? 0.0 : e[k];
            for (int m = 0; m < 3; ++m) dp *= std::pow(x[m], m == k ? std::max(e[m] - 1, 0) : e[m]);
            EXPECT_NEAR(grad(k), dp, kRoundoff) << "monomial " << e0 << e1 << e2 << ", d/dx_" << k;
          }
        }
}

INSTANTIATE_TEST_SUITE_P(EveryCell, ShapeFunctions, ::testing::ValuesIn(kAllCells),
                         [](const ::testing::TestParamInfo<CellType>& i) { return ddc::cellTypeName(i.param); });

// ------------------------------------------------------------- quadrature

/// Exact integral of x^e0 y^e1 z^e2 over the reference cell: on [-1,1]^d the
/// product of (1 - (-1)^(e+1))/(e+1); on the unit simplex e0! e1! e2! /
/// (e0 + e1 + e2 + d)!.
double exactMonomialIntegral(CellType t, const int e[3]) {
  const auto& c = ddc::referenceCell(t);
  if (c.simplex) {
    double r = 1;
    for (int m = 0; m < c.dim; ++m) r *= std::tgamma(e[m] + 1);
    return r / std::tgamma(e[0] + e[1] + e[2] + c.dim + 1);
  }
  double r = 1;
  for (int m = 0; m < c.dim; ++m) r *= e[m] % 2 ? 0.0 : 2.0 / (e[m] + 1);
  return r;
}

class Quadrature : public ::testing::TestWithParam<CellType> {};

TEST_P(Quadrature, ExactUpToItsDegreeAndNotBeyond) {
  const auto& c = ddc::referenceCell(GetParam());
  const auto& rule = ddc::quadratureRule(GetParam());
  ASSERT_EQ(rule.points.size(), rule.weights.size());
  for (double w : rule.weights) EXPECT_GT(w, 0.0) << "positive weights";
  double worstBeyond = 0;  // largest error among monomials of degree + 1
  for (int e0 = 0; e0 <= rule.degree + 1; ++e0)
    for (int e1 = 0; e1 <= rule.degree + 1 - e0; ++e1)
      for (int e2 = 0; e2 <= (c.dim > 2 ? rule.degree + 1 - e0 - e1 : 0); ++e2) {
        const int e[3] = {e0, e1, e2};
        double q = 0;
        for (size_t i = 0; i < rule.points.size(); ++i) {
          const auto& x = rule.points[i];
          q += rule.weights[i] * std::pow(x[0], e0) * std::pow(x[1], e1) * std::pow(x[2], e2);
        }
        const double err = std::abs(q - exactMonomialIntegral(GetParam(), e));
        if (e0 + e1 + e2 <= rule.degree)
          EXPECT_LT(err, kRoundoff) << rule.name << ", monomial " << e0 << e1 << e2;
        else
          worstBeyond = std::max(worstBeyond, err);
      }
  // The stated degree is the rule's true degree: some monomial one higher
  // is not integrated exactly.
  EXPECT_GT(worstBeyond, 1e-6) << rule.name;
}

INSTANTIATE_TEST_SUITE_P(EveryElementCell, Quadrature, ::testing::ValuesIn(ddc::elementCellTypes()),
                         [](const ::testing::TestParamInfo<CellType>& i) { return ddc::cellTypeName(i.param); });

TEST(Quadrature, RejectsFacetCells) { EXPECT_THROW(ddc::quadratureRule(CellType::Quad8), std::invalid_argument); }

}  // namespace
