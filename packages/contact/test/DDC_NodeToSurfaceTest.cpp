// The conventional node-to-surface element on every facet type
// (DDC_NodeToSurface.hpp; doc/verification.md rung 1): closest-point
// projection, residual = finite-difference gradient of the energy, tangent =
// finite-difference Jacobian of the residual (including the variation of the
// projection and of the normal), symmetry, exact gaps on flat facets, and the
// 2-D Line2 case against the node-to-segment element; the decomposed slave
// and master counterparts on every facet type (DDC_DecomposedNodeToSurface.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "DDC_DecomposedNodeToSurface.hpp"
#include "DDC_NodeToSegment.hpp"
#include "DDC_NodeToSurface.hpp"
#include "DDC_ReferenceCell.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using ddc::CellType;
using ddc::NodeToSurfaceElement;

/// Central differences with step kStep have truncation error ~ kStep² times
/// third derivatives (O(1) here) and round-off ~ 1e-16 / kStep: the
/// comparison tolerance, relative to the largest entry, sits far above both
/// and far below any missing term of the linearisation (O(1) relative).
constexpr double kStep = 1e-6;
constexpr double kFiniteDifference = 1e-6;

const CellType kFacets3d[] = {CellType::Tri3, CellType::Tri6, CellType::Quad4, CellType::Quad8, CellType::Quad9};
const CellType kFacets2d[] = {CellType::Line2, CellType::Line3};

/// A curved, distorted facet of type `facet` (reference nodes mapped by a
/// smooth warp) with a slave node above it at reference facet point `at`
/// (gap `gap` along the facet's normal side), and a small random
/// displacement of every node.
struct Case {
  Eigen::MatrixXd X, u;
};

Case makeCase(CellType facet, std::array<double, 2> at, double gap, unsigned seed) {
  const auto& c = ddc::referenceCell(facet);
  const int dim = ddc::facetSpaceDimension(facet), m = c.numNodes;
  Case k;
  k.X.resize(m + 1, dim);
  auto warp = [&](double s, double t) {
    Eigen::VectorXd p(dim);
    if (dim == 2) {
      p << s + 0.05 * s * s, 0.1 * s * s;
    } else {
      p << s + 0.05 * t * t, t - 0.04 * s * t, 0.15 * s * t + 0.1 * s * s;
    }
    return p;
  };
  for (int i = 0; i < m; ++i) k.X.row(i + 1) = warp(c.nodes[i][0], c.nodes[i][1]).transpose();
  // Slave: above the warped point; "above" = the outward normal side (+z in
  // 3-D for the counter-clockwise facets, −y in 2-D: the body is on the left
  // of the direction of travel).
  Eigen::VectorXd s = warp(at[0], at[1]);
  if (dim == 2)
    s[1] -= gap;
  else
    s[2] += gap;
  k.X.row(0) = s.transpose();
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-0.02, 0.02);
  k.u = Eigen::MatrixXd::NullaryExpr(m + 1, dim, [&]() { return d(gen); });
  return k;
}

ddc::ElementResult evaluate(const NodeToSurfaceElement& e, const Case& k, const Eigen::MatrixXd& u, double lambda,
                            unsigned what = ddc::kAll) {
  ddc::ContactPairState st;
  st.active = true;
  st.multiplier = lambda;
  ddc::ElementResult r;
  e.computeContact(k.X, u, st, what, r);
  return r;
}

/// The finite-difference checks for one facet type and slave position.
void checkDerivatives(CellType facet, std::array<double, 2> at, unsigned seed) {
  NodeToSurfaceElement e(facet);
  const Case k = makeCase(facet, at, 0.05, seed);
  const double lambda = -2.3;
  const auto r = evaluate(e, k, k.u, lambda);
  const int nd = e.dim() * e.numNodes();
  ASSERT_EQ(r.residual.size(), nd + 1);
  const auto proj = e.project(k.X, k.u);
  ASSERT_TRUE(proj.converged);
  EXPECT_TRUE(proj.inside);
  EXPECT_NEAR(r.residual[nd], proj.gap, ddc::test::kRoundoff) << "the multiplier row is the gap";
  EXPECT_NEAR(r.energy, lambda * proj.gap, ddc::test::kRoundoff);
  // Residual vs the energy, tangent vs the residual, by central differences.
  Eigen::VectorXd fdRes(nd);
  Eigen::MatrixXd fdTan(nd, nd);
  for (int b = 0; b < nd; ++b) {
    Eigen::MatrixXd up = k.u, um = k.u;
    up(b / e.dim(), b % e.dim()) += kStep;
    um(b / e.dim(), b % e.dim()) -= kStep;
    const auto rp = evaluate(e, k, up, lambda), rm = evaluate(e, k, um, lambda);
    fdRes[b] = (rp.energy - rm.energy) / (2 * kStep);
    fdTan.col(b) = (rp.residual.head(nd) - rm.residual.head(nd)) / (2 * kStep);
  }
  const double resScale = r.residual.head(nd).cwiseAbs().maxCoeff();
  const double tanScale = r.tangent.topLeftCorner(nd, nd).cwiseAbs().maxCoeff();
  EXPECT_LE((r.residual.head(nd) - fdRes).cwiseAbs().maxCoeff(), kFiniteDifference * resScale)
      << ddc::cellTypeName(facet) << ": residual vs d(energy)/du";
  EXPECT_LE((r.tangent.topLeftCorner(nd, nd) - fdTan).cwiseAbs().maxCoeff(), kFiniteDifference * tanScale)
      << ddc::cellTypeName(facet) << ": tangent vs d(residual)/du (variation of the projection and the normal)";
  EXPECT_LE((r.tangent - r.tangent.transpose()).cwiseAbs().maxCoeff(), 1e-12 * tanScale) << "symmetric";
  // The λ column is the gap's gradient (the residual divided by λ).
  EXPECT_LE((r.tangent.col(nd).head(nd) * lambda - r.residual.head(nd)).cwiseAbs().maxCoeff(), 1e-14 * resScale);
  EXPECT_GT(tanScale, 0.0) << "a curved / moving facet has a geometric stiffness";
}

TEST(NodeToSurface, ResidualAndTangentMatchFiniteDifferencesOnEveryFacet) {
  unsigned seed = 1;
  for (CellType f : kFacets3d) {
    const bool tri = f == CellType::Tri3 || f == CellType::Tri6;
    // The middle and near an edge / a corner, still inside.
    for (auto at : tri ? std::vector<std::array<double, 2>>{{0.3, 0.3}, {0.9, 0.05}}
                       : std::vector<std::array<double, 2>>{{0.1, -0.2}, {0.95, 0.9}}) {
      SCOPED_TRACE(ddc::cellTypeName(f));
      checkDerivatives(f, at, seed++);
    }
  }
  for (CellType f : kFacets2d)
    for (double at : {0.2, -0.97}) {
      SCOPED_TRACE(ddc::cellTypeName(f));
      checkDerivatives(f, {at, 0.0}, seed++);
    }
}

TEST(NodeToSurface, FlatFacetGivesTheDistanceAndTheOutwardNormal) {
  // Flat Quad4 in z = 0 (counter-clockwise seen from +z: outward +z), slave
  // at height 0.3 above (0.2, -0.4): ξ̄ = (0.2, -0.4), g = 0.3, n = +z; and
  // below: g = -0.3 (penetration).
  Eigen::MatrixXd x(4, 3);
  x << -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0;
  for (double h : {0.3, -0.3}) {
    Eigen::VectorXd xs(3);
    xs << 0.2, -0.4, h;
    const auto p = ddc::projectOntoFacet(CellType::Quad4, x, xs);
    ASSERT_TRUE(p.converged);
    EXPECT_NEAR(p.xi[0], 0.2, ddc::test::kRoundoff);
    EXPECT_NEAR(p.xi[1], -0.4, ddc::test::kRoundoff);
    EXPECT_NEAR(p.gap, h, ddc::test::kRoundoff);
    EXPECT_NEAR(p.normal[2], 1.0, ddc::test::kRoundoff);
    EXPECT_TRUE(p.inside);
  }
  Eigen::VectorXd out(3);
  out << 1.5, 0.0, 0.1;
  EXPECT_FALSE(ddc::projectOntoFacet(CellType::Quad4, x, out).inside) << "beyond the edge x = 1";
}

TEST(NodeToSurface, Line2EqualsTheNodeToSegmentElement) {
  // The 2-D element on a Line2 facet is the node-to-segment element of
  // DDC_NodeToSegment.hpp (same node order, same normal, ξ ∈ [-1, 1] instead
  // of [0, 1]): residual and tangent agree to round-off.
  const Case k = makeCase(CellType::Line2, {0.3, 0.0}, 0.04, 7);
  NodeToSurfaceElement e(CellType::Line2);
  ddc::NodeToSegmentElement nts;
  ddc::ContactPairState st;
  st.active = true;
  st.multiplier = -1.7;
  ddc::ElementResult a, b;
  e.computeContact(k.X, k.u, st, ddc::kAll, a);
  nts.computeContact(k.X, k.u, st, ddc::kAll, b);
  EXPECT_NEAR(a.energy, b.energy, ddc::test::kRoundoff);
  EXPECT_LE((a.residual - b.residual).cwiseAbs().maxCoeff(), ddc::test::kRoundoff);
  EXPECT_LE((a.tangent - b.tangent).cwiseAbs().maxCoeff(), ddc::test::kRoundoff * b.tangent.cwiseAbs().maxCoeff());
}

TEST(NodeToSurface, ReleasedPairRestrainsTheMultiplier) {
  NodeToSurfaceElement e(CellType::Quad9);
  const Case k = makeCase(CellType::Quad9, {0.0, 0.0}, 0.1, 3);
  ddc::ContactPairState st;
  st.active = false;
  st.multiplier = 0.4;
  ddc::ElementResult r;
  e.computeContact(k.X, k.u, st, ddc::kAll, r);
  const int nd = e.dim() * e.numNodes();
  EXPECT_EQ(r.residual[nd], 0.4);
  EXPECT_EQ(r.tangent(nd, nd), 1.0);
  EXPECT_EQ(r.residual.head(nd).cwiseAbs().maxCoeff(), 0.0);
}

/// Frozen at the converged projection, the two decomposed counterparts add up
/// to the frozen-gap element, whose gap and gradient there are the
/// conventional element's (paper eq. 1 and 2); residuals are the exact
/// gradients of the energies (the gap is linear: checked at two states).
TEST(DecomposedNodeToSurface, CounterpartsAddUpToTheFrozenPairOnEveryFacet) {
  unsigned seed = 40;
  std::vector<CellType> facets(std::begin(kFacets3d), std::end(kFacets3d));
  facets.insert(facets.end(), std::begin(kFacets2d), std::end(kFacets2d));
  for (CellType f : facets) {
    SCOPED_TRACE(ddc::cellTypeName(f));
    const Case k = makeCase(f, {0.2, 0.1}, 0.03, seed++);
    NodeToSurfaceElement nts(f);
    ddc::DecomposedSurfaceCounterpart slave(f, false), master(f, true);
    const auto proj = nts.project(k.X, k.u);
    ASSERT_TRUE(proj.converged);
    ddc::FrozenFacetProjection frozen{proj.xi, proj.normal};
    const int d = nts.dim(), m = master.numNodes(), nd = d * (m + 1);
    ddc::ContactPairState st;
    st.active = true;
    st.multiplier = -0.8;
    ddc::ElementResult rs, rm, rc;
    const Eigen::MatrixXd Xs = k.X.topRows(1), us = k.u.topRows(1), Xm = k.X.bottomRows(m), um = k.u.bottomRows(m);
    slave.computeContact(Xs, us, frozen, st, ddc::kAll, rs);
    master.computeContact(Xm, um, frozen, st, ddc::kAll, rm);
    nts.computeContact(k.X, k.u, st, ddc::kAll, rc);
    // The multiplier rows add up to the gap, the displacement rows to λ G.
    EXPECT_NEAR(rs.residual[d] + rm.residual[d * m], proj.gap, ddc::test::kRoundoff);
    Eigen::VectorXd sum(nd);
    sum << rs.residual.head(d), rm.residual.head(d * m);
    EXPECT_LE((sum - rc.residual.head(nd)).cwiseAbs().maxCoeff(), ddc::test::kRoundoff)
        << "frozen at the projection, the decomposed gradient is the conventional one";
    EXPECT_NEAR(rs.energy + rm.energy, rc.energy, ddc::test::kRoundoff);
    // Constraint rows are the multiplier rows of the tangents.
    EXPECT_LE((slave.constraintRow(frozen) - rs.tangent.row(d).head(d).transpose()).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_LE((master.constraintRow(frozen) - rm.tangent.row(d * m).head(d * m).transpose()).cwiseAbs().maxCoeff(),
              0.0);
    // Frozen: moving the nodes changes the gap linearly by the row.
    Eigen::MatrixXd um2 = um;
    um2(0, d - 1) += 0.01;
    EXPECT_NEAR(master.gapPart(Xm, um2, frozen) - master.gapPart(Xm, um, frozen),
                0.01 * master.constraintRow(frozen)[d - 1], ddc::test::kRoundoff);
    // Released: ½λ² in the slave counterpart only.
    st.active = false;
    slave.computeContact(Xs, us, frozen, st, ddc::kAll, rs);
    master.computeContact(Xm, um, frozen, st, ddc::kAll, rm);
    EXPECT_EQ(rs.energy, 0.5 * 0.8 * 0.8);
    EXPECT_EQ(rm.energy, 0.0);
    EXPECT_EQ(rm.tangent.cwiseAbs().maxCoeff(), 0.0);
  }
}

TEST(DecomposedNodeToSurface, AFrozenNormalThatIsNotUnitIsRejected) {
  ddc::DecomposedSurfaceCounterpart slave(CellType::Quad8, false);
  ddc::FrozenFacetProjection unset;  // normal (0, 0, 0): nobody froze it
  EXPECT_THROW(slave.constraintRow(unset), std::invalid_argument);
}

TEST(NodeToSurface, NonFacetCellTypesAreRejected) {
  EXPECT_THROW(NodeToSurfaceElement(CellType::Hex8), std::invalid_argument);
  EXPECT_THROW(NodeToSurfaceElement(CellType::Tet4), std::invalid_argument);
}

}  // namespace
