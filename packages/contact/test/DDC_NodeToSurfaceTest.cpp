// The conventional node-to-surface element on every facet type
// (DDC_NodeToSurface.hpp; doc/verification.md rung 1): closest-point
// projection, residual = finite-difference gradient of the energy, tangent =
// finite-difference Jacobian of the residual (including the variation of the
// projection and of the normal), symmetry, exact gaps on flat facets, and the
// 2-D Line2 case against the node-to-segment element; the decomposed slave
// and master counterparts on every facet type (DDC_DecomposedNodeToSurface.hpp).
// With Coulomb friction (DDC_Friction.hpp): the frictional element's every
// row against finite differences in stick and in slip, the counterparts
// against it, the stick/slip decision and the tangent basis.
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

// ---- Coulomb friction (DDC_Friction.hpp) ----------------------------------------------

namespace {

/// A frictional state in contact: λ_n, λ_t, μ, c_t and the step-start
/// displacements u0 of the element's nodes.
ddc::ContactPairState frictionalState(const Eigen::MatrixXd& u0, bool stick) {
  ddc::ContactPairState st;
  st.active = true;
  st.multiplier = -2.3;
  st.friction.coefficient = 0.3;
  st.friction.stiffness = 5.0;
  st.friction.stick = stick;
  st.friction.tangential = {0.4, -0.3};
  st.friction.stepStart = u0;
  return st;
}

/// Residual of the element at displacements u and multipliers w = [λ_n, λ_t].
Eigen::VectorXd frictionalResidual(const NodeToSurfaceElement& e, const Case& k, const Eigen::MatrixXd& u,
                                   ddc::ContactPairState st, const Eigen::VectorXd& w, double* energy = nullptr) {
  st.multiplier = w[0];
  for (int a = 1; a < w.size(); ++a) st.friction.tangential[a - 1] = w[a];
  ddc::ElementResult r;
  e.computeContact(k.X, u, st, ddc::kAll, r);
  if (energy) *energy = r.energy;
  return r.residual;
}

/// The frictional element's finite-difference checks on one facet (stick
/// or slip): every residual row against the central-difference Jacobian
/// in u and in the multipliers, and the displacement rows against the
/// gradient of λ_n g_N + λ_t·u_t.
void checkFrictionalDerivatives(CellType facet, std::array<double, 2> at, unsigned seed, bool stick) {
  NodeToSurfaceElement e(facet);
  const Case k = makeCase(facet, at, 0.05, seed);
  const int dim = e.dim(), nd = dim * e.numNodes(), n = nd + dim;
  // The step start: the nodes displaced by a different small amount, so
  // the slip and its derivatives through the projection are not zero.
  Eigen::MatrixXd u0 = 0.5 * k.u.reverse();
  u0(0, 0) -= 0.03;  // the slave slid along x (the facets' first direction)
  const ddc::ContactPairState st = frictionalState(u0, stick);
  Eigen::VectorXd w(dim);
  w << st.multiplier, st.friction.tangential[0], st.friction.tangential[1];
  w.conservativeResize(dim);
  ddc::ElementResult r;
  e.computeContact(k.X, k.u, st, ddc::kAll, r);
  ASSERT_EQ(r.residual.size(), n);
  ASSERT_EQ(r.tangent.rows(), n);
  // The slip rows of the slip state are not the trivial stick rows.
  std::array<Eigen::Vector3d, 2> basis;
  Eigen::MatrixXd x = k.X + k.u, x0 = k.X + u0;
  const auto pr = e.project(k.X, k.u);
  const auto slip = ddc::conventionalSlip(facet, x, x0, pr.xi, &basis);
  if (stick)
    for (int a = 0; a + 1 < dim; ++a) EXPECT_NEAR(r.residual[nd + 1 + a], slip[a], ddc::test::kRoundoff);
  EXPECT_GT(std::abs(slip[0]), 1e-4) << "the case must slip for the check to mean anything";
  Eigen::MatrixXd fd(n, n);
  Eigen::VectorXd fdEnergy(nd);
  for (int b = 0; b < n; ++b) {
    Eigen::MatrixXd up = k.u, um = k.u;
    Eigen::VectorXd wp = w, wm = w;
    if (b < nd) {
      up(b / dim, b % dim) += kStep;
      um(b / dim, b % dim) -= kStep;
    } else {
      wp[b - nd] += kStep;
      wm[b - nd] -= kStep;
    }
    double ep = 0.0, em = 0.0;
    fd.col(b) = (frictionalResidual(e, k, up, st, wp, &ep) - frictionalResidual(e, k, um, st, wm, &em)) / (2 * kStep);
    if (b < nd) fdEnergy[b] = (ep - em) / (2 * kStep);
  }
  const double scale = r.tangent.cwiseAbs().maxCoeff();
  EXPECT_LE((r.tangent - fd).cwiseAbs().maxCoeff(), kFiniteDifference * scale)
      << ddc::cellTypeName(facet) << (stick ? " stick" : " slip") << ": tangent vs d(residual)/d(u, lambda)\n"
      << (r.tangent - fd).cwiseAbs().rowwise().maxCoeff().transpose();
  EXPECT_LE((r.residual.head(nd) - fdEnergy).cwiseAbs().maxCoeff(),
            kFiniteDifference * r.residual.head(nd).cwiseAbs().maxCoeff())
      << ddc::cellTypeName(facet) << ": displacement rows vs d(lambda_n g + lambda_t . u_t)/du";
}

}  // namespace

TEST(NodeToSurface, FrictionalResidualAndTangentMatchFiniteDifferencesOnEveryFacet) {
  unsigned seed = 70;
  for (bool stick : {true, false}) {
    for (CellType f : kFacets3d) {
      SCOPED_TRACE(ddc::cellTypeName(f));
      const bool tri = f == CellType::Tri3 || f == CellType::Tri6;
      checkFrictionalDerivatives(f, tri ? std::array<double, 2>{0.3, 0.3} : std::array<double, 2>{0.1, -0.2}, seed++,
                                 stick);
    }
    for (CellType f : kFacets2d) {
      SCOPED_TRACE(ddc::cellTypeName(f));
      checkFrictionalDerivatives(f, {0.2, 0.0}, seed++, stick);
    }
  }
}

TEST(NodeToSurface, FrictionlessStateGivesTheFrictionlessElementBitForBit) {
  // A zero coefficient is today's element: one multiplier, the same numbers.
  for (CellType f : {CellType::Quad8, CellType::Line3}) {
    NodeToSurfaceElement e(f);
    const Case k = makeCase(f, {0.2, 0.1}, 0.05, 5);
    ddc::ContactPairState plain;
    plain.active = true;
    plain.multiplier = -1.1;
    ddc::ContactPairState withZero = plain;
    withZero.friction.coefficient = 0.0;
    withZero.friction.tangential = {0.5, 0.5};
    withZero.friction.stepStart = k.u;
    ddc::ElementResult a, b;
    e.computeContact(k.X, k.u, plain, ddc::kAll, a);
    e.computeContact(k.X, k.u, withZero, ddc::kAll, b);
    EXPECT_EQ(a.residual, b.residual);
    EXPECT_EQ(a.tangent, b.tangent);
    EXPECT_EQ(a.energy, b.energy);
  }
}

TEST(DecomposedNodeToSurface, FrictionalCounterpartsAddUpToTheConventionalElementAtTheStepStart) {
  // Frozen at the projection of the step start, with the conventional
  // element's tangent basis, the counterparts' residuals and multiplier rows
  // add up to the conventional element's there (stick and slip), and in
  // stick their tangents are the derivatives of their residuals.
  unsigned seed = 90;
  std::vector<CellType> facets(std::begin(kFacets3d), std::end(kFacets3d));
  facets.insert(facets.end(), std::begin(kFacets2d), std::end(kFacets2d));
  for (bool stick : {true, false})
    for (CellType f : facets) {
      SCOPED_TRACE(ddc::cellTypeName(f) + std::string(stick ? " stick" : " slip"));
      const Case k = makeCase(f, {0.2, 0.1}, 0.03, seed++);
      NodeToSurfaceElement nts(f);
      ddc::DecomposedSurfaceCounterpart slave(f, false), master(f, true);
      const int d = nts.dim(), m = master.numNodes(), nd = d * (m + 1), nt = d - 1;
      const auto proj = nts.project(k.X, k.u);
      ddc::FrozenFacetProjection frozen{proj.xi, proj.normal};
      const Eigen::MatrixXd x = k.X + k.u;
      ddc::conventionalSlip(f, x, x, proj.xi, &frozen.tangent);
      ddc::ContactPairState st = frictionalState(k.u, stick);  // u = u0: no slip yet
      ddc::ElementResult rs, rm, rc;
      const Eigen::MatrixXd Xs = k.X.topRows(1), us = k.u.topRows(1), Xm = k.X.bottomRows(m), um = k.u.bottomRows(m);
      ddc::ContactPairState ss = st, sm = st;
      ss.friction.stepStart = us;
      sm.friction.stepStart = um;
      slave.computeContact(Xs, us, frozen, ss, ddc::kAll, rs);
      master.computeContact(Xm, um, frozen, sm, ddc::kAll, rm);
      nts.computeContact(k.X, k.u, st, ddc::kAll, rc);
      Eigen::VectorXd sum(nd);
      sum << rs.residual.head(d), rm.residual.head(d * m);
      EXPECT_LE((sum - rc.residual.head(nd)).cwiseAbs().maxCoeff(), 10 * ddc::test::kRoundoff) << "displacement rows";
      for (int a = 0; a <= nt; ++a)
        EXPECT_NEAR(rs.residual[d + a] + rm.residual[d * m + a], rc.residual[nd + a], 10 * ddc::test::kRoundoff)
            << "multiplier row " << a;
      // The tangential rows' displacement columns: the slave's and the
      // master's parts of the conventional rows.
      for (int a = 1; a <= nt; ++a) {
        Eigen::VectorXd row(nd);
        row << rs.tangent.row(d + a).head(d).transpose(), rm.tangent.row(d * m + a).head(d * m).transpose();
        EXPECT_LE((row - rc.tangent.row(nd + a).head(nd).transpose()).cwiseAbs().maxCoeff(),
                  10 * ddc::test::kRoundoff)
            << "tangential row " << a;
        EXPECT_LE((rs.tangent.row(d + a).tail(d) - rc.tangent.row(nd + a).tail(d)).cwiseAbs().maxCoeff(),
                  10 * ddc::test::kRoundoff)
            << "multiplier columns of tangential row " << a << " (the slave's)";
        EXPECT_EQ(rm.tangent.row(d * m + a).tail(d).cwiseAbs().maxCoeff(), 0.0) << "none in the master's";
      }
    }
}

TEST(Friction, TheStickSlipDecisionAndTheTangentBasis) {
  ddc::FrictionPairState f;
  f.coefficient = 0.5;
  f.stiffness = 10.0;
  const double lambdaN = -2.0;  // p = 2: the cone's radius μ p = 1
  const double lt[2] = {0.3, 0.0};
  const double small[2] = {0.05, 0.0}, large[2] = {0.08, 0.0};  // |z| = 0.8, 1.1
  EXPECT_TRUE(ddc::sticks(1, small, lambdaN, lt, f));
  EXPECT_FALSE(ddc::sticks(1, large, lambdaN, lt, f));
  // On the cone: a sticking pair slips, a slipping pair stays slipping just
  // inside it (hysteresis), and returns to stick below it.
  const double onCone[2] = {0.07, 0.0};
  EXPECT_FALSE(ddc::sticks(1, onCone, lambdaN, lt, f));
  const double inside[2] = {0.07 - 1e-10, 0.0};
  EXPECT_TRUE(ddc::sticks(1, inside, lambdaN, lt, f));
  f.stick = false;
  EXPECT_FALSE(ddc::sticks(1, inside, lambdaN, lt, f));
  EXPECT_TRUE(ddc::sticks(1, small, lambdaN, lt, f));
  // In tension nothing sticks.
  EXPECT_FALSE(ddc::sticks(1, small, 0.5, lt, f));
  // The slip row puts λ_t on the cone along the predictor.
  const auto rows = ddc::frictionRows(1, large, lambdaN, lt, f);
  EXPECT_NEAR(rows.residual[0], (0.3 - 1.0) / 10.0, 1e-15);
  // Tangent bases: unit, orthogonal to n and to each other; 2-D τ = (−n_y, n_x).
  const Eigen::Vector3d n2(0.6, -0.8, 0.0);
  const auto b2 = ddc::tangentBasis(2, n2);
  EXPECT_NEAR((b2[0] - Eigen::Vector3d(0.8, 0.6, 0.0)).norm(), 0.0, 1e-15);
  const Eigen::Vector3d n3 = Eigen::Vector3d(0.2, -0.3, 0.9).normalized();
  for (const Eigen::Vector3d& previous : {Eigen::Vector3d::Zero().eval(), Eigen::Vector3d(1, 0, 0), n3}) {
    const auto b = ddc::tangentBasis(3, n3, previous);
    EXPECT_NEAR(b[0].norm(), 1.0, 1e-14);
    EXPECT_NEAR(b[1].norm(), 1.0, 1e-14);
    EXPECT_NEAR(b[0].dot(n3), 0.0, 1e-14);
    EXPECT_NEAR(b[1].dot(n3), 0.0, 1e-14);
    EXPECT_NEAR(b[0].dot(b[1]), 0.0, 1e-14);
  }
  // A small rotation of n rotates τ_1 little (minimal rotation from the previous τ_1).
  const auto before = ddc::tangentBasis(3, n3, Eigen::Vector3d(1, 0, 0));
  const Eigen::Vector3d n3b = (n3 + Eigen::Vector3d(1e-3, 0, 0)).normalized();
  EXPECT_LT((ddc::tangentBasis(3, n3b, before[0])[0] - before[0]).norm(), 2e-3);
}

// A slipping pair whose predictor turns against the force of its slip row
// (the solve slid the node the other way) reverses; one along it, a
// sticking pair, or a 3-D turn of less than 90 degrees does not.
TEST(Friction, ASlipThatTurnsAgainstItsForceReverses) {
  ddc::FrictionPairState f;
  f.coefficient = 0.5;
  f.stiffness = 10.0;
  f.stick = false;
  const double lt[2] = {1.0, 0.0};  // on the cone μ p = 1, along +τ_1
  const double along[2] = {0.05, 0.0}, against[2] = {-0.2, 0.0};  // z = 1.5, −1
  EXPECT_FALSE(ddc::slipReverses(1, along, lt, f));
  EXPECT_TRUE(ddc::slipReverses(1, against, lt, f));
  const double turned[2] = {-0.05, 0.3}, reversed[2] = {-0.15, 0.3};  // z = (0.5, 3), (−0.5, 3)
  EXPECT_FALSE(ddc::slipReverses(2, turned, lt, f));
  EXPECT_TRUE(ddc::slipReverses(2, reversed, lt, f));
  f.stick = true;
  EXPECT_FALSE(ddc::slipReverses(1, against, lt, f));
}

// A slave node and its master point on a symmetry plane y = 0 (both held in
// y): the free relative motion is (x, z). With the master surface tilted
// across the plane the normal n has a y part and τ_2 = n × τ_1 an x or z
// part, so no row is zero on the free DOFs, yet the gap row and the two
// tangential rows span only (x, z): the second tangential row is redundant
// (ContactPairing::restrainHeldSlip() restrains its multiplier). Off the
// plane every row counts; a row on prescribed DOFs only is redundant too.
TEST(Friction, ASlipRowOnASymmetryPlaneIsRedundant) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.01, 0.05, 1.0).normalized();
  const auto t = ddc::tangentBasis(3, n, Eigen::Vector3d(1, 0, 0));
  // Slave node and one master node (N = 1) with the relative motion
  // x_s − x_m: the rows' coefficients (d, −d) on (slave, master).
  auto rows = [&](bool yHeld) {
    std::vector<Eigen::VectorXd> r;
    for (const Eigen::Vector3d& d : {n, t[0], t[1]}) {
      Eigen::VectorXd v(6);
      v << d, -d;
      if (yHeld) v[1] = v[4] = 0.0;
      r.push_back(v);
    }
    return r;
  };
  const double tol = ddc::kHeldSlipRow;
  const std::vector<double> sizes(3, std::sqrt(2.0));  // |(d, −d)| of a unit d
  EXPECT_FALSE(ddc::slipRowRedundant(rows(false), sizes, 0, tol));
  EXPECT_FALSE(ddc::slipRowRedundant(rows(false), sizes, 1, tol));
  EXPECT_FALSE(ddc::slipRowRedundant(rows(true), sizes, 0, tol));
  EXPECT_TRUE(ddc::slipRowRedundant(rows(true), sizes, 1, tol));
  // Neither row is small on its own (the old zero test missed it).
  EXPECT_GT(rows(true)[2].norm(), 0.05);
  // Every DOF prescribed: both rows hold nothing.
  std::vector<Eigen::VectorXd> none(3, Eigen::VectorXd::Zero(6));
  none[0] = rows(false)[0];
  EXPECT_TRUE(ddc::slipRowRedundant(none, sizes, 0, tol));
  EXPECT_TRUE(ddc::slipRowRedundant(none, sizes, 1, tol));
}

// The same node on the plane x = 0 (held in x) under a flat master whose
// deformed facet tilts τ_1 ≈ x off the plane by 1e-7 (the Hertz octant's
// symmetry-plane nodes in step 2): τ_1's free part is 1e-7 of the row, far
// from zero relative to itself, but nothing beside the tilt of the deformed
// geometry. Judged against its own free part it counted, and its
// multiplier grew as 1/1e-7 (Newton diverged); judged against the whole
// row it is held, as is the 1e-4 tilt of the Mindlin half model. A tilt of
// 0.1 counts.
TEST(Friction, ASlipRowTiltedOffASymmetryPlaneByRoundOffIsRedundant) {
  auto rows = [&](double tilt) {
    const Eigen::Vector3d n(0.0, 0.0, 1.0);
    const Eigen::Vector3d t1 = Eigen::Vector3d(1.0, tilt, 0.0).normalized();
    std::vector<Eigen::VectorXd> r;
    for (const Eigen::Vector3d& d : {n, t1, Eigen::Vector3d(n.cross(t1))}) {
      Eigen::VectorXd v(6);
      v << d, -d;
      v[0] = v[3] = 0.0;  // x held on the slave node and on the master node
      r.push_back(v);
    }
    return r;
  };
  const double tol = ddc::kHeldSlipRow;
  const std::vector<double> sizes(3, std::sqrt(2.0));
  for (double tilt : {1e-7, 1e-4}) {
    EXPECT_TRUE(ddc::slipRowRedundant(rows(tilt), sizes, 0, tol)) << tilt;
    EXPECT_FALSE(ddc::slipRowRedundant(rows(tilt), sizes, 1, tol)) << tilt;
  }
  EXPECT_FALSE(ddc::slipRowRedundant(rows(0.1), sizes, 0, tol));
  EXPECT_TRUE(ddc::slipRowRedundant(rows(0.1), sizes, 1, tol));
}
