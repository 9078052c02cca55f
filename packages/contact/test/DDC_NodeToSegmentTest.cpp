// Node-to-segment contact elements: the conventional nonlinear element and the
// decomposed slave/master counterparts (Fang & Izzuddin 2022, eqs. 1 and 2).
// Derivative checks over all DOFs including λ (central FD of energy and
// residual, plus nested forward AD for the exact NTS Hessian), symmetry, the
// physical sign convention, force/moment balance, the relation between the
// decomposed and the conventional element, and factory registration.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Sacado.hpp>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "DDC_DecomposedNodeToSegment.hpp"
#include "DDC_Error.hpp"
#include "DDC_NodeToSegment.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using ddc::ContactElement;
using ddc::ContactPairState;
using ddc::ElementResult;
using ddc::test::kFiniteDifference;
using ddc::test::kRoundoff;

// ----------------------------------------------------------------------------
// Helpers
// ----------------------------------------------------------------------------

/// Rows of a MatrixX2d from a list of points.
Eigen::MatrixX2d rows(std::initializer_list<Eigen::Vector2d> pts) {
  Eigen::MatrixX2d m(static_cast<Eigen::Index>(pts.size()), 2);
  int i = 0;
  for (const auto& p : pts) m.row(i++) = p.transpose();
  return m;
}

/// One evaluation point of a contact element: nodal data + state. The DOF
/// vector is [u (node-major), λ].
struct Config {
  Eigen::MatrixX2d X, u;
  ContactPairState state;

  Eigen::VectorXd dofs() const {
    Eigen::VectorXd v(2 * X.rows() + 1);
    for (int i = 0; i < X.rows(); ++i) v.segment<2>(2 * i) = u.row(i).transpose();
    v(v.size() - 1) = state.multiplier;
    return v;
  }
  Config with(const Eigen::VectorXd& v) const {
    Config c = *this;
    for (int i = 0; i < X.rows(); ++i) c.u.row(i) = v.segment<2>(2 * i).transpose();
    c.state.multiplier = v(v.size() - 1);
    return c;
  }
};

ElementResult evaluate(const ContactElement& el, const Config& c, unsigned what = ddc::kAll) {
  ElementResult r;
  el.computeContact(c.X, c.u, c.state, what, r);
  return r;
}

/// Central FD step: 1e-6 relative to the coordinate scale O(1) of the tests
/// (see kFiniteDifference for why this pairs with a 1e-6 relative tolerance).
constexpr double kStep = 1e-6;

/// max |a − b| / max(‖b‖∞, 1): FD errors relative to the size of the quantity
/// (floor 1 because coordinates, λ and the derivatives are all O(1) here).
double relErr(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(b.cwiseAbs().maxCoeff(), 1.0);
}

struct FdErrors {
  double residual = 0, tangent = 0, asymmetry = 0;
};

/// Residual vs central FD of the energy and tangent vs central FD of the
/// residual, over all DOFs (displacements and λ); asymmetry of the tangent.
FdErrors derivativeErrors(const ContactElement& el, const Config& c) {
  const ElementResult r0 = evaluate(el, c);
  const Eigen::VectorXd v0 = c.dofs();
  const int n = static_cast<int>(v0.size());
  EXPECT_EQ(r0.residual.size(), n);
  EXPECT_EQ(r0.tangent.rows(), n);
  EXPECT_EQ(r0.tangent.cols(), n);
  Eigen::VectorXd fdRes(n);
  Eigen::MatrixXd fdTan(n, n);
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd vp = v0, vm = v0;
    vp(j) += kStep;
    vm(j) -= kStep;
    const ElementResult rp = evaluate(el, c.with(vp)), rm = evaluate(el, c.with(vm));
    fdRes(j) = (rp.energy - rm.energy) / (2 * kStep);
    fdTan.col(j) = (rp.residual - rm.residual) / (2 * kStep);
  }
  FdErrors e;
  e.residual = relErr(r0.residual, fdRes);
  e.tangent = relErr(r0.tangent, fdTan);
  e.asymmetry = (r0.tangent - r0.tangent.transpose()).cwiseAbs().maxCoeff();
  return e;
}

void expectDerivativesMatch(const ContactElement& el, const Config& c, const std::string& what) {
  const FdErrors e = derivativeErrors(el, c);
  EXPECT_LT(e.residual, kFiniteDifference) << what << ": residual vs FD of energy";
  EXPECT_LT(e.tangent, kFiniteDifference) << what << ": tangent vs FD of residual";
  EXPECT_LT(e.asymmetry, kRoundoff) << what << ": tangent asymmetry";
  std::printf("[ FD       ] %-48s residual %.2e  tangent %.2e  asym %.1e\n", what.c_str(), e.residual, e.tangent,
              e.asymmetry);
}

/// Slave + segment configuration for the NTS element with X chosen and u a
/// fixed non-trivial displacement, so that both X and u enter.
Config ntsConfig(const Eigen::Vector2d& xs, const Eigen::Vector2d& x1, const Eigen::Vector2d& x2, bool active,
                 double lambda) {
  Config c;
  c.u = rows({{0.013, -0.021}, {-0.017, 0.008}, {0.011, 0.019}});
  c.X = rows({xs, x1, x2}) - c.u;  // current positions are exactly xs, x1, x2
  c.state.active = active;
  c.state.multiplier = lambda;
  return c;
}

Eigen::Vector2d pointAt(const Eigen::Vector2d& x1, const Eigen::Vector2d& x2, double xi, double gap) {
  const Eigen::Vector2d t = x2 - x1;
  const Eigen::Vector2d n = Eigen::Vector2d(t.y(), -t.x()) / t.norm();
  return x1 + xi * t + gap * n;
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// ----------------------------------------------------------------------------
// Projection
// ----------------------------------------------------------------------------

TEST(SegmentProjection, HorizontalSegmentNormalAndGap) {
  // 1 → 2 runs in −x: the master body is on the left, i.e. below; n = +y.
  const auto p = ddc::projectOntoSegment({0.5, 0.25}, {2.0, 0.0}, {0.0, 0.0});
  EXPECT_NEAR(p.normal.x(), 0.0, kRoundoff);
  EXPECT_NEAR(p.normal.y(), 1.0, kRoundoff);
  EXPECT_NEAR(p.xi, 0.75, kRoundoff);
  EXPECT_NEAR(p.gap, 0.25, kRoundoff);
  EXPECT_NEAR(p.length, 2.0, kRoundoff);
  // g = cross(x_s − x1, t)/|t| and x_s − x̄(ξ̄) = g n for a straight segment.
  const Eigen::Vector2d xs(0.5, 0.25), x1(2.0, 0.0), x2(0.0, 0.0);
  EXPECT_NEAR(p.gap, cross(xs - x1, x2 - x1) / 2.0, kRoundoff);
  const Eigen::Vector2d xbar = x1 + p.xi * (x2 - x1);
  EXPECT_LT((xs - xbar - p.gap * p.normal).norm(), kRoundoff);
}

TEST(SegmentProjection, ZeroLengthSegmentIsInadmissible) {
  EXPECT_THROW(ddc::projectOntoSegment({0.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}), ddc::InadmissibleDeformation);
  const ddc::NodeToSegmentElement el;
  Config c = ntsConfig({0, 1}, {1, 1}, {1, 1}, true, -1.0);
  ElementResult r;
  EXPECT_THROW(el.computeContact(c.X, c.u, c.state, ddc::kAll, r), ddc::InadmissibleDeformation);
  // Released: the geometry is not needed, no throw.
  c.state.active = false;
  EXPECT_NO_THROW(el.computeContact(c.X, c.u, c.state, ddc::kAll, r));
}

// ----------------------------------------------------------------------------
// Conventional NTS: derivatives
// ----------------------------------------------------------------------------

struct NtsCase {
  std::string name;
  Eigen::Vector2d x1, x2;
  double xi, gap;
};

std::vector<NtsCase> ntsCases() {
  const Eigen::Vector2d a(0.3, -0.2), b(1.4, 0.1);        // generic segment
  const Eigen::Vector2d c(-0.5, 0.8), d(-0.2, -1.7);      // rotated (steep) and stretched (|t| ≈ 2.5)
  const Eigen::Vector2d e(1.0, 1.0), f(1.0 + 0.31, 0.95);  // short segment, |t| ≈ 0.31
  return {
      {"inside, g = 0", a, b, 0.4, 0.0},
      {"inside, penetrating g = -0.05", a, b, 0.4, -0.05},
      {"inside, separated g = +0.2", a, b, 0.6, 0.2},
      {"near end 1 (xi = 0.01)", a, b, 0.01, -0.02},
      {"near end 2 (xi = 0.99)", a, b, 0.99, -0.02},
      {"rotated+stretched segment", c, d, 0.37, -0.08},
      {"short segment", e, f, 0.55, -0.03},
      {"xi slightly below 0 (-0.03)", a, b, -0.03, -0.01},
      {"xi slightly above 1 (1.04)", c, d, 1.04, -0.01},
  };
}

TEST(NodeToSegment, DerivativesActiveMatchFiniteDifferences) {
  const ddc::NodeToSegmentElement el;
  for (const auto& k : ntsCases()) {
    for (double lambda : {-0.7, 0.3}) {
      const Config c = ntsConfig(pointAt(k.x1, k.x2, k.xi, k.gap), k.x1, k.x2, true, lambda);
      expectDerivativesMatch(el, c, "NTS active " + k.name + (lambda < 0 ? " l<0" : " l>0"));
    }
  }
}

TEST(NodeToSegment, DerivativesInactiveMatchFiniteDifferences) {
  const ddc::NodeToSegmentElement el;
  for (const auto& k : ntsCases()) {
    const Config c = ntsConfig(pointAt(k.x1, k.x2, k.xi, k.gap), k.x1, k.x2, false, 0.45);
    expectDerivativesMatch(el, c, "NTS inactive " + k.name);
    const ElementResult r = evaluate(el, c);
    EXPECT_DOUBLE_EQ(r.energy, 0.5 * 0.45 * 0.45);
    EXPECT_EQ(r.residual.head<6>().cwiseAbs().maxCoeff(), 0.0);
    EXPECT_DOUBLE_EQ(r.residual(6), 0.45);
    EXPECT_DOUBLE_EQ(r.tangent(6, 6), 1.0);
    EXPECT_EQ(r.tangent.cwiseAbs().sum(), 1.0);
  }
}

TEST(NodeToSegment, GapProjectionAndResidualAgree) {
  const ddc::NodeToSegmentElement el;
  for (const auto& k : ntsCases()) {
    const Config c = ntsConfig(pointAt(k.x1, k.x2, k.xi, k.gap), k.x1, k.x2, true, -0.5);
    EXPECT_NEAR(el.gap(c.X, c.u, c.state), k.gap, kRoundoff) << k.name;
    const ElementResult r = evaluate(el, c);
    EXPECT_NEAR(r.residual(6), k.gap, kRoundoff) << k.name;
    EXPECT_NEAR(r.energy, -0.5 * k.gap, kRoundoff) << k.name;
    const auto p = ddc::projectOntoSegment(pointAt(k.x1, k.x2, k.xi, k.gap), k.x1, k.x2);
    EXPECT_NEAR(p.xi, k.xi, kRoundoff) << k.name;
  }
}

/// g_N as a template of the 6 current coordinates, for nested forward AD.
template <class T>
T gapOf(const T* x) {
  // x = [xs_x, xs_y, x1_x, x1_y, x2_x, x2_y]
  const T tx = x[4] - x[2], ty = x[5] - x[3];
  const T ax = x[0] - x[2], ay = x[1] - x[3];
  return (ax * ty - ay * tx) / std::sqrt(tx * tx + ty * ty);
}

TEST(NodeToSegment, TangentEqualsExactHessianFromAutomaticDifferentiation) {
  // Independent exact check (no truncation error): second derivatives of g_N
  // by nested forward AD, SFad<SFad<double,6>,6>.
  using Inner = Sacado::Fad::SFad<double, 6>;
  using Outer = Sacado::Fad::SFad<Inner, 6>;
  const ddc::NodeToSegmentElement el;
  for (const auto& k : ntsCases()) {
    const double lambda = -1.3;
    const Config c = ntsConfig(pointAt(k.x1, k.x2, k.xi, k.gap), k.x1, k.x2, true, lambda);
    const Eigen::MatrixX2d x = c.X + c.u;
    Outer v[6];
    for (int i = 0; i < 6; ++i) {
      const double xi = x(i / 2, i % 2);
      v[i] = Outer(6, i, Inner(6, i, xi));
    }
    const Outer g = gapOf(v);
    const ElementResult r = evaluate(el, c);
    for (int i = 0; i < 6; ++i) {
      EXPECT_NEAR(r.residual(i), lambda * g.dx(i).val(), kRoundoff) << k.name << " dof " << i;
      EXPECT_NEAR(r.tangent(i, 6), g.dx(i).val(), kRoundoff) << k.name << " dof " << i;
      for (int j = 0; j < 6; ++j)
        EXPECT_NEAR(r.tangent(i, j), lambda * g.dx(i).dx(j), 10 * kRoundoff)  // |λ H| ≤ ~10
            << k.name << " (" << i << "," << j << ")";
    }
    EXPECT_NEAR(r.residual(6), g.val().val(), kRoundoff);
  }
}

TEST(NodeToSegment, OnlyRequestedQuantitiesAreComputed) {
  const ddc::NodeToSegmentElement el;
  const Config c = ntsConfig({0.5, 0.0}, {2, 0}, {0, 0}, true, -1.0);
  ElementResult r;
  r.energy = 42.0;
  el.computeContact(c.X, c.u, c.state, ddc::kResidual, r);
  EXPECT_EQ(r.energy, 42.0);
  EXPECT_EQ(r.residual.size(), 7);
  EXPECT_EQ(r.tangent.size(), 0);
}

TEST(NodeToSegment, WrongNumberOfNodesThrows) {
  const ddc::NodeToSegmentElement el;
  ContactPairState s;
  ElementResult r;
  const Eigen::MatrixX2d two = Eigen::MatrixX2d::Zero(2, 2);
  EXPECT_THROW(el.computeContact(two, two, s, ddc::kAll, r), std::invalid_argument);
  EXPECT_THROW(el.gap(two, two, s), std::invalid_argument);
}

// ----------------------------------------------------------------------------
// Conventional NTS: physics
// ----------------------------------------------------------------------------

TEST(NodeToSegment, CompressionPushesSlaveOutwardAlongNormal) {
  // Master: horizontal segment 1 = (2, 0) → 2 = (0, 0), master body below
  // (left of 1 → 2), outward normal n = +y. Slave on the surface above ξ = 3/4.
  // Compression λ = −3. Residual = ∂Π/∂u = λ N (internal-force convention):
  // slave residual λ n = (0, −3); the force the slave FEELS is −λ n = (0, +3),
  // i.e. along +n, away from the master body. The master nodes feel
  // +λ N_i n = −3 N_i (0, 1): pushed into their body, shared 1/4 : 3/4.
  const ddc::NodeToSegmentElement el;
  const Config c = ntsConfig({0.5, 0.0}, {2.0, 0.0}, {0.0, 0.0}, true, -3.0);
  const ElementResult r = evaluate(el, c);
  EXPECT_NEAR(r.residual(0), 0.0, kRoundoff);
  EXPECT_NEAR(r.residual(1), -3.0, kRoundoff);
  const Eigen::Vector2d feltBySlave = -r.residual.segment<2>(0);
  EXPECT_GT(feltBySlave.y(), 0.0) << "compression must push the slave along +n";
  EXPECT_NEAR(-r.residual(3), -3.0 * 0.25, kRoundoff);  // master 1, N_1 = 1 − ξ = 1/4
  EXPECT_NEAR(-r.residual(5), -3.0 * 0.75, kRoundoff);  // master 2, N_2 = ξ = 3/4
  EXPECT_NEAR(r.residual(2), 0.0, kRoundoff);
  EXPECT_NEAR(r.residual(4), 0.0, kRoundoff);
  EXPECT_NEAR(r.residual(6), 0.0, kRoundoff);  // g = 0
  EXPECT_NEAR(r.energy, 0.0, kRoundoff);
}

/// Σ forces and Σ moments (about p) of the nodal residuals of the NTS element.
std::pair<Eigen::Vector2d, double> resultant(const Config& c, const ElementResult& r, const Eigen::Vector2d& p) {
  const Eigen::MatrixX2d x = c.X + c.u;
  Eigen::Vector2d f = Eigen::Vector2d::Zero();
  double m = 0.0;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d fi = r.residual.segment<2>(2 * i);
    f += fi;
    m += cross(x.row(i).transpose() - p, fi);
  }
  return {f, m};
}

TEST(NodeToSegment, ForcesAndMomentsBalance) {
  // Normal-only contact forces: Σ f = λ(n − (1−ξ)n − ξ n) = 0 and
  // Σ (x_i − p) × f_i = λ (x_s − x̄) × n = λ g (n × n) = 0, so the element is
  // in self-equilibrium at g = 0 (as required) and in fact for any g.
  const ddc::NodeToSegmentElement el;
  const std::vector<Eigen::Vector2d> points = {{0, 0}, {10.0, -3.0}, {-7.5, 4.2}};
  for (const auto& k : ntsCases()) {
    const Config c = ntsConfig(pointAt(k.x1, k.x2, k.xi, k.gap), k.x1, k.x2, true, -2.2);
    const ElementResult r = evaluate(el, c);
    for (const auto& p : points) {
      const auto [f, m] = resultant(c, r, p);
      EXPECT_LT(f.norm(), kRoundoff) << k.name;
      EXPECT_LT(std::abs(m), 20 * kRoundoff) << k.name;  // lever arms up to ~10
    }
  }
}

TEST(NodeToSegment, GapIsInvariantUnderRigidMotion) {
  // Objectivity: a rigid rotation + translation of all three nodes leaves g_N
  // unchanged, so the u–u tangent annihilates infinitesimal rigid modes at
  // g = 0 … here checked on the finite motion.
  const ddc::NodeToSegmentElement el;
  const double a = 0.83;
  Eigen::Matrix2d Q;
  Q << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  const Eigen::Vector2d shift(1.7, -0.4);
  for (const auto& k : ntsCases()) {
    const Config c = ntsConfig(pointAt(k.x1, k.x2, k.xi, k.gap), k.x1, k.x2, true, -1.0);
    Config moved = c;
    const Eigen::MatrixX2d x = c.X + c.u;
    for (int i = 0; i < 3; ++i) moved.u.row(i) = (Q * x.row(i).transpose() + shift).transpose() - c.X.row(i);
    EXPECT_NEAR(el.gap(moved.X, moved.u, moved.state), el.gap(c.X, c.u, c.state), kRoundoff) << k.name;
  }
}

// ----------------------------------------------------------------------------
// Decomposed counterparts
// ----------------------------------------------------------------------------

ContactPairState frozen(bool active, double lambda, double xi, const Eigen::Vector2d& n) {
  ContactPairState s;
  s.active = active;
  s.multiplier = lambda;
  s.frozenXi = xi;
  s.frozenNormal = n.normalized();
  return s;
}

TEST(DecomposedNts, SlaveDerivativesMatchFiniteDifferences) {
  const ddc::DecomposedNtsSlaveElement el;
  for (bool active : {true, false}) {
    for (double lambda : {-0.8, 0.35}) {
      Config c;
      c.X = rows({{0.7, 1.1}});
      c.u = rows({{0.02, -0.05}});
      c.state = frozen(active, lambda, 0.3, {0.6, 0.8});
      expectDerivativesMatch(el, c,
                             std::string("slave ") + (active ? "active" : "inactive") + (lambda < 0 ? " l<0" : " l>0"));
      const ElementResult r = evaluate(el, c);
      const Eigen::Vector2d xs(0.72, 1.05), n(0.6, 0.8);
      if (active) {
        EXPECT_NEAR(r.energy, lambda * n.dot(xs), kRoundoff);
        EXPECT_LT((r.residual.head<2>() - lambda * n).norm(), kRoundoff);
        EXPECT_NEAR(r.residual(2), n.dot(xs), kRoundoff);
        EXPECT_NEAR(r.tangent(2, 2), 0.0, 0.0);
      } else {
        EXPECT_NEAR(r.energy, 0.5 * lambda * lambda, kRoundoff);
        EXPECT_EQ(r.residual.head<2>().norm(), 0.0);
        EXPECT_DOUBLE_EQ(r.residual(2), lambda);
        EXPECT_DOUBLE_EQ(r.tangent(2, 2), 1.0);
      }
    }
  }
}

TEST(DecomposedNts, MasterDerivativesMatchFiniteDifferences) {
  const ddc::DecomposedNtsMasterElement el;
  for (bool active : {true, false}) {
    for (double xi : {0.3, -0.02, 1.03}) {
      Config c;
      c.X = rows({{0.0, 0.0}, {1.5, -0.4}});
      c.u = rows({{0.01, 0.03}, {-0.02, 0.04}});
      c.state = frozen(active, -0.9, xi, {-0.26, 0.97});
      expectDerivativesMatch(el, c,
                             std::string("master ") + (active ? "active" : "inactive") + " xi=" + std::to_string(xi));
      const ElementResult r = evaluate(el, c);
      if (!active) {
        EXPECT_EQ(r.energy, 0.0);
        EXPECT_EQ(r.residual.size(), 5);
        EXPECT_EQ(r.residual.norm(), 0.0);
        EXPECT_EQ(r.tangent.norm(), 0.0);
      } else {
        const Eigen::Vector2d n = c.state.frozenNormal;
        EXPECT_LT((r.residual.segment<2>(0) + 0.9 * (-(1 - xi)) * n).norm(), kRoundoff);  // −λ N_1 n
        EXPECT_LT((r.residual.segment<2>(2) + 0.9 * (-xi) * n).norm(), kRoundoff);        // −λ N_2 n
        EXPECT_EQ((r.tangent.topLeftCorner<4, 4>().norm()), 0.0);
      }
    }
  }
}

TEST(DecomposedNts, MissingFrozenNormalThrows) {
  ContactPairState s;  // frozenNormal = 0: nobody filled it in
  s.active = true;
  ElementResult r;
  const ddc::DecomposedNtsSlaveElement slave;
  const ddc::DecomposedNtsMasterElement master;
  const Eigen::MatrixX2d one = Eigen::MatrixX2d::Zero(1, 2), two = Eigen::MatrixX2d::Zero(2, 2);
  EXPECT_THROW(slave.computeContact(one, one, s, ddc::kAll, r), std::invalid_argument);
  EXPECT_THROW(master.computeContact(two, two, s, ddc::kAll, r), std::invalid_argument);
  EXPECT_THROW(slave.gap(one, one, s), std::invalid_argument);
  EXPECT_THROW(master.gap(two, two, s), std::invalid_argument);
  s.frozenNormal = Eigen::Vector2d(0.0, 2.0);  // not normalised
  EXPECT_THROW(ddc::decomposedGap({0, 0}, {0, 0}, {1, 0}, s), std::invalid_argument);
  // Wrong node counts.
  s.frozenNormal = Eigen::Vector2d(0.0, 1.0);
  EXPECT_THROW(slave.computeContact(two, two, s, ddc::kAll, r), std::invalid_argument);
  EXPECT_THROW(master.computeContact(one, one, s, ddc::kAll, r), std::invalid_argument);
}

/// The pair of decomposed counterparts on the NTS node set [s, 1, 2],
/// assembled into the NTS DOF layout [u_s, u_1, u_2, λ] (λ rows summed).
ElementResult assembleDecomposed(const Config& nts) {
  const ddc::DecomposedNtsSlaveElement slave;
  const ddc::DecomposedNtsMasterElement master;
  ElementResult rs, rm, sum;
  slave.computeContact(nts.X.topRows(1), nts.u.topRows(1), nts.state, ddc::kAll, rs);
  master.computeContact(nts.X.bottomRows(2), nts.u.bottomRows(2), nts.state, ddc::kAll, rm);
  const int ms[3] = {0, 1, 6}, mm[5] = {2, 3, 4, 5, 6};  // local → NTS DOF
  sum.energy = rs.energy + rm.energy;
  sum.residual.setZero(7);
  sum.tangent.setZero(7, 7);
  for (int i = 0; i < 3; ++i) {
    sum.residual(ms[i]) += rs.residual(i);
    for (int j = 0; j < 3; ++j) sum.tangent(ms[i], ms[j]) += rs.tangent(i, j);
  }
  for (int i = 0; i < 5; ++i) {
    sum.residual(mm[i]) += rm.residual(i);
    for (int j = 0; j < 5; ++j) sum.tangent(mm[i], mm[j]) += rm.tangent(i, j);
  }
  return sum;
}

/// NTS configuration with ξ^p, n^p frozen on the configuration itself.
Config frozenOnSelf(const NtsCase& k, bool active, double lambda) {
  Config c = ntsConfig(pointAt(k.x1, k.x2, k.xi, k.gap), k.x1, k.x2, active, lambda);
  const Eigen::MatrixX2d x = c.X + c.u;
  const auto p = ddc::projectOntoSegment(x.row(0).transpose(), x.row(1).transpose(), x.row(2).transpose());
  c.state.frozenXi = p.xi;
  c.state.frozenNormal = p.normal;
  return c;
}

TEST(DecomposedNts, SumEqualsConventionalElementOnTheFrozenConfiguration) {
  // With ξ^p, n^p taken from the current configuration, slave + master give
  // exactly the NTS energy, residual (gradient) and gap, and the NTS coupling
  // column N; only the NTS geometric block λ ∂²g/∂u² is absent (the
  // decomposed gap is linear in u).
  const ddc::NodeToSegmentElement nts;
  const ddc::DecomposedNtsSlaveElement slave;
  const ddc::DecomposedNtsMasterElement master;
  for (const auto& k : ntsCases()) {
    const Config c = frozenOnSelf(k, true, -1.7);
    const ElementResult rn = evaluate(nts, c), rd = assembleDecomposed(c);
    EXPECT_NEAR(rd.energy, rn.energy, kRoundoff) << k.name;
    EXPECT_LT((rd.residual - rn.residual).cwiseAbs().maxCoeff(), kRoundoff) << k.name;
    EXPECT_LT((rd.tangent.col(6) - rn.tangent.col(6)).cwiseAbs().maxCoeff(), kRoundoff) << k.name;
    EXPECT_EQ((rd.tangent.topLeftCorner<6, 6>().norm()), 0.0) << k.name;
    const double gs = slave.gap(c.X.topRows(1), c.u.topRows(1), c.state);
    const double gm = master.gap(c.X.bottomRows(2), c.u.bottomRows(2), c.state);
    const Eigen::MatrixX2d x = c.X + c.u;
    EXPECT_NEAR(gs + gm, nts.gap(c.X, c.u, c.state), kRoundoff) << k.name;
    EXPECT_NEAR(ddc::decomposedGap(x.row(0).transpose(), x.row(1).transpose(), x.row(2).transpose(), c.state),
                gs + gm, kRoundoff)
        << k.name;
    // Constraint-row coefficients = the λ row of the tangents = ∂g/∂u.
    EXPECT_LT((ddc::DecomposedNtsSlaveElement::constraintCoefficients(c.state) - rn.tangent.block<2, 1>(0, 6)).norm(),
              kRoundoff);
    EXPECT_LT((ddc::DecomposedNtsMasterElement::constraintCoefficients(c.state) - rn.tangent.block<4, 1>(2, 6)).norm(),
              kRoundoff);
  }
  // Released: the sum is ½ λ² on λ alone, as for the NTS element.
  for (const auto& k : ntsCases()) {
    const Config c = frozenOnSelf(k, false, 0.6);
    const ElementResult rn = evaluate(nts, c), rd = assembleDecomposed(c);
    EXPECT_NEAR(rd.energy, rn.energy, kRoundoff);
    EXPECT_LT((rd.residual - rn.residual).norm(), kRoundoff);
    EXPECT_LT((rd.tangent - rn.tangent).norm(), kRoundoff);
  }
}

TEST(DecomposedNts, FrozenGapAgreesToFirstOrderAfterAnIncrement) {
  // Freeze ξ^p, n^p on x⁰ and move the nodes by ε d. The decomposed gap is
  // the linearisation of g_N at x⁰ (its gradient is the NTS gradient there),
  // so |g_dec − g_NTS| = O(ε²) and the residuals differ by O(ε): halving ε
  // divides the gap error by ~4 and the residual error by ~2.
  const ddc::NodeToSegmentElement nts;
  Eigen::MatrixX2d d(3, 2);
  d << 0.3, -0.8, -0.5, 0.2, 0.7, 0.9;
  for (const auto& k : ntsCases()) {
    const Config c0 = frozenOnSelf(k, true, -1.1);
    double gapErr[2], resErr[2];
    const double eps[2] = {1e-2, 5e-3};
    for (int m = 0; m < 2; ++m) {
      Config c = c0;
      c.u += eps[m] * d;
      const Eigen::MatrixX2d x = c.X + c.u;
      const double gd =
          ddc::decomposedGap(x.row(0).transpose(), x.row(1).transpose(), x.row(2).transpose(), c.state);
      gapErr[m] = std::abs(gd - nts.gap(c.X, c.u, c.state));
      resErr[m] = (assembleDecomposed(c).residual - evaluate(nts, c).residual).cwiseAbs().maxCoeff();
    }
    EXPECT_LT(gapErr[0], 10 * eps[0] * eps[0]) << k.name;
    EXPECT_NEAR(gapErr[0] / gapErr[1], 4.0, 0.4) << k.name << ": gap error not O(eps^2)";
    EXPECT_NEAR(resErr[0] / resErr[1], 2.0, 0.2) << k.name << ": residual error not O(eps)";
  }
}

// ----------------------------------------------------------------------------
// Factory registration
// ----------------------------------------------------------------------------

TEST(ContactElementRegistration, NamesNodesAndCreation) {
  auto f = ddc::ElementFactory::withBuiltins();
  ddc::registerContactElements(f);
  EXPECT_THAT(f.names(), ::testing::IsSupersetOf({std::string("Node-To-Segment"), std::string("Decomposed NTS Slave"),
                                                  std::string("Decomposed NTS Master"), std::string("Quad4")}));
  const std::vector<std::pair<std::string, int>> expected = {
      {"Node-To-Segment", 3}, {"Decomposed NTS Slave", 1}, {"Decomposed NTS Master", 2}};
  for (const auto& [name, nodes] : expected) {
    EXPECT_EQ(f.entry(name).numNodes, nodes) << name;
    EXPECT_FALSE(f.entry(name).description.empty()) << name;
    Teuchos::ParameterList p;
    p.set("Type", name);
    const auto el = f.create(p, "Contact/Element");
    ASSERT_TRUE(el) << name;
    EXPECT_EQ(el->numNodes(), nodes) << name;
    const auto ce = std::dynamic_pointer_cast<ddc::ContactElement>(el);
    ASSERT_TRUE(ce) << name << " is not a ContactElement";
    // No parameters: a misspelt one is an input error naming it.
    Teuchos::ParameterList bad;
    bad.set("Type", name);
    bad.set("Penalty", 1.0);
    try {
      f.create(bad, "Contact/Element");
      ADD_FAILURE() << name << ": unknown parameter accepted";
    } catch (const ddc::InputError& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr("Penalty")) << name;
    }
  }
  EXPECT_TRUE(std::dynamic_pointer_cast<ddc::NodeToSegmentElement>(
      f.entry("Node-To-Segment").create(Teuchos::ParameterList())));
  EXPECT_TRUE(std::dynamic_pointer_cast<ddc::DecomposedNtsSlaveElement>(
      f.entry("Decomposed NTS Slave").create(Teuchos::ParameterList())));
  EXPECT_TRUE(std::dynamic_pointer_cast<ddc::DecomposedNtsMasterElement>(
      f.entry("Decomposed NTS Master").create(Teuchos::ParameterList())));
}

}  // namespace
