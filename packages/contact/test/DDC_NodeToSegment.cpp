#include "DDC_NodeToSegment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "DDC_DecomposedNodeToSegment.hpp"
#include "DDC_Error.hpp"

namespace ddc {

namespace {

/// Shape checks of the nodal data (programming errors of the caller).
void requireShape(const char* who, int numNodes, const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u) {
  if (X.rows() != numNodes || u.rows() != numNodes)
    DDC_THROW(std::invalid_argument, who << ": expected " << numNodes << " nodes, got X with " << X.rows()
                                         << " and u with " << u.rows() << " rows");
}

}  // namespace

SegmentProjection projectOntoSegment(const Eigen::Vector2d& xs, const Eigen::Vector2d& x1,
                                     const Eigen::Vector2d& x2) {
  const Eigen::Vector2d t = x2 - x1;
  const double L = t.norm();
  // Relative threshold: a segment shorter than round-off of its coordinates
  // has no direction. This is a collapsed (inadmissible) master face.
  const double scale = std::max({x1.norm(), x2.norm(), std::numeric_limits<double>::min()});
  if (!(L > 1e-13 * scale))
    DDC_THROW(InadmissibleDeformation, "node-to-segment: master segment of zero length (|x2 - x1| = "
                                           << L << ") at x1 = (" << x1.x() << ", " << x1.y() << ")");
  SegmentProjection p;
  p.length = L;
  p.tangent = t / L;
  p.normal = Eigen::Vector2d(p.tangent.y(), -p.tangent.x());
  const Eigen::Vector2d a = xs - x1;
  p.xi = a.dot(t) / (L * L);
  // For a straight segment x_s − x̄(ξ̄) = a − ξ̄ t is parallel to n, and
  // n·(a − ξ̄ t) = n·a: the gap needs no explicit projection point.
  p.gap = p.normal.dot(a);
  return p;
}

// ---------------------------------------------------------------------------
// Node-To-Segment
//
// Derivation of the derivatives used below (δ = variation, Δ = linearisation;
// a = x_s − x1, t = x2 − x1, L = |t|, τ = t/L, n = (t_y, −t_x)/L, so that
// a = ξ̄ L τ + g n):
//
// 1. Normal. With R the rotation by +90°, R t = −L n, R n = τ, hence
//    n = −R t / L and δn = −R δt / L − n (τ·δt)/L. Splitting δt along τ and
//    n gives  δn = −τ (n·δt) / L  (n stays a unit vector).
// 2. Projection. ξ̄ = a·t / L²:
//    δξ̄ = [τ·(δa − ξ̄ δt)] / L + g (n·δt) / L²,
//    where δa − ξ̄ δt = δx_s − (1−ξ̄) δx1 − ξ̄ δx2 =: δΔ.
// 3. Gap. g = n·(x_s − x̄(ξ̄)); since ∂x̄/∂ξ = t ⊥ n, the ξ̄ variation drops
//    out and  δg = n·δΔ  (the term δn·(a − ξ̄ t) = δn·(g n) = 0).
//    ⇒ N = ∂g/∂u = [n; −(1−ξ̄) n; −ξ̄ n].
// 4. Second variation: Δδg = Δn·δΔ + n·Δ(δΔ), Δ(δΔ) = −Δξ̄ δt:
//    Δδg = −(n·Δt)(τ·δΔ)/L − (n·δt)(τ·ΔΔ)/L − g (n·δt)(n·Δt)/L²,
//    i.e. H = −(N₁ T₀ᵀ + T₀ N₁ᵀ)/L − g N₁ N₁ᵀ / L² with T₀ = [τ; −(1−ξ̄)τ; −ξ̄τ],
//    N₁ = [0; −n; n]. Symmetric, exact (no terms dropped; the g-term vanishes
//    only at g = 0). The tests check it against finite differences and
//    against nested forward AD (Sacado).
// ---------------------------------------------------------------------------

Teuchos::RCP<const Teuchos::ParameterList> NodeToSegmentElement::getValidParameters() {
  return Teuchos::rcp(new Teuchos::ParameterList("Element"));
}

double NodeToSegmentElement::gap(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u,
                                 const ContactPairState& /*state*/) const {
  requireShape("Node-To-Segment gap", 3, X, u);
  const Eigen::MatrixX2d x = X + u;
  return projectOntoSegment(x.row(0).transpose(), x.row(1).transpose(), x.row(2).transpose()).gap;
}

void NodeToSegmentElement::computeContact(const Eigen::MatrixX2d& X, const Eigen::MatrixX2d& u,
                                          const ContactPairState& state, unsigned what,
                                          ElementResult& out) const {
  requireShape("Node-To-Segment computeContact", 3, X, u);
  constexpr int kN = 7;  // [u_s, u_1, u_2, λ]
  constexpr int kLam = 6;
  const double lam = state.multiplier;

  if (!state.active) {
    // Released: Π = ½ λ², independent of the geometry (no projection needed,
    // so a degenerate segment does not matter here).
    releasedContribution(kN, lam, what, out);
    return;
  }

  const Eigen::MatrixX2d x = X + u;
  const SegmentProjection p = projectOntoSegment(x.row(0).transpose(), x.row(1).transpose(), x.row(2).transpose());
  const double g = p.gap, xi = p.xi, L = p.length;
  const Eigen::Vector2d& n = p.normal;
  const Eigen::Vector2d& tau = p.tangent;

  // N = ∂g/∂u (step 3 above).
  Eigen::Matrix<double, 6, 1> N;
  N << n, -(1.0 - xi) * n, -xi * n;

  if (what & kEnergy) out.energy = lam * g;
  if (what & kResidual) {
    out.residual.resize(kN);
    out.residual.head<6>() = lam * N;
    out.residual(kLam) = g;
  }
  if (what & kTangent) {
    Eigen::Matrix<double, 6, 1> T0, N1;
    T0 << tau, -(1.0 - xi) * tau, -xi * tau;
    N1 << Eigen::Vector2d::Zero(), -n, n;
    // H = ∂²g/∂u² (step 4 above).
    const Eigen::Matrix<double, 6, 6> H =
        -(N1 * T0.transpose() + T0 * N1.transpose()) / L - (g / (L * L)) * (N1 * N1.transpose());
    out.tangent.setZero(kN, kN);
    out.tangent.topLeftCorner<6, 6>() = lam * H;
    out.tangent.block<6, 1>(0, kLam) = N;
    out.tangent.block<1, 6>(kLam, 0) = N.transpose();
  }
}

// ---------------------------------------------------------------------------
// Registration
// ---------------------------------------------------------------------------

void registerContactElements(ElementFactory& f) {
  f.add("Node-To-Segment",
        ElementFactory::Entry{
            [](const Teuchos::ParameterList&) -> std::shared_ptr<Element> {
              return std::make_shared<NodeToSegmentElement>();
            },
            NodeToSegmentElement::getValidParameters(),
            "Conventional nonlinear node-to-segment contact element with a Lagrange multiplier "
            "(nodes: slave, master 1, master 2; Pi = lambda g_N in contact, lambda^2/2 released; "
            "consistent linearisation incl. projection and normal variation).",
            3, 2, /*contact=*/true});
  f.add("Decomposed NTS Slave",
        ElementFactory::Entry{
            [](const Teuchos::ParameterList&) -> std::shared_ptr<Element> {
              return std::make_shared<DecomposedNtsSlaveElement>();
            },
            DecomposedNtsSlaveElement::getValidParameters(),
            "Slave counterpart of the decomposed node-to-segment element (Fang & Izzuddin 2022, eq. 1): "
            "node: slave; frozen projection and normal; Pi = lambda n^p.x_s in contact, lambda^2/2 released.",
            1, 2, /*contact=*/true});
  f.add("Decomposed NTS Master",
        ElementFactory::Entry{
            [](const Teuchos::ParameterList&) -> std::shared_ptr<Element> {
              return std::make_shared<DecomposedNtsMasterElement>();
            },
            DecomposedNtsMasterElement::getValidParameters(),
            "Master counterpart of the decomposed node-to-segment element (Fang & Izzuddin 2022, eq. 1): "
            "nodes: master 1, master 2; frozen projection and normal; Pi = -lambda n^p.sum N_i x_i in "
            "contact, 0 released.",
            2, 2, /*contact=*/true});
}

}  // namespace ddc
