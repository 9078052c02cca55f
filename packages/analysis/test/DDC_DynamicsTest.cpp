// Implicit dynamics without contact (Newmark, HHT-alpha, generalised-alpha): a
// linear-elastic bar (E = ρ = 1, ν = 0) clamped at x = 0 and set moving by an
// initial velocity, on 1 and 2 ranks.
//  - the trapezoidal rule (β = ¼, γ = ½) conserves kinetic + strain energy;
//  - γ > ½ damps: the energy never grows and ends lower; so do HHT-α and
//    generalised-α at steps far beyond the periods, more for a more
//    dissipative parameter;
//  - the error in u(T) against the exact solution of the semi-discrete
//    system M ü + K u = 0 (its modes, from the model's own M and K) falls
//    with the time step at order 2, for all three schemes;
//  - FETI-DP (K^s + c M^s per subdomain) = Monolithic per step;
//  - bad dynamics input stops with the parameter named.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_AnalysisTestDecks.hpp"
#include "DDC_Error.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TimeIntegrator.hpp"

namespace {

using PL = Teuchos::ParameterList;
using namespace ddc::test;

/// Energy drift of the trapezoidal rule on a linear problem: only Newton's
/// residual tolerance (1e-8 relative, reached in one iteration to round-off)
/// separates it from exact conservation.
constexpr double kEnergyConservation = 1e-10;
/// FETI-DP = Monolithic per step (doc/verification.md, rung 3).
constexpr double kFetiAgreement = 1e-8;

/// The bar: length 10 (nx x ny Quad4), clamped on the left, initial
/// velocity 0.1 along x on every other node.
PL barDeck(int nx, int ny, double finalTime, double dt) {
  PL deck("DDContact");
  RectangleSpec s;
  s.lengthX = 10.0;
  s.lengthY = 1.0;
  s.nx = nx;
  s.ny = ny;
  s.material = "Linear Elastic";
  s.E = 1.0;
  s.nu = 0.0;
  addRectangle(deck, "Bar", s).sublist("Element").sublist("Material").set("Density", 1.0);
  addDisplacement(deck, "Clamped", "Bar/left", "XY");
  PL& dyn = deck.sublist("Dynamics");
  dyn.set("Integrator", std::string("Newmark"));
  dyn.set("Final Time", finalTime);
  dyn.set("Time Step", dt);
  PL& v = dyn.sublist("Initial Velocity").sublist("Push");
  v.set("Set", std::string("Bar"));
  v.set("Velocity X", 0.1);
  deck.sublist("Output").set("Progress", false);
  deck.sublist("Output").set("VTK", false);
  return deck;
}

double totalEnergy(const ddc::StepRecord& r) { return r.strainEnergy + r.kineticEnergy; }

TEST(Dynamics, TheTrapezoidalRuleConservesTheEnergyOfALinearFreeVibration) {
  PL deck = barDeck(20, 2, 10.0, 0.25);
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  const auto& h = a.history();
  ASSERT_EQ(h.size(), 40u);
  // E0: the kinetic energy of the initial velocity (the clamped nodes at rest).
  const double E0 = totalEnergy(h.front());
  ASSERT_GT(E0, 0.0);
  double worst = 0.0;
  for (const auto& r : h) worst = std::max(worst, std::abs(totalEnergy(r) - E0) / E0);
  EXPECT_LT(worst, kEnergyConservation);
  EXPECT_NEAR(h.back().loadFactor, 10.0, 1e-12) << "in dynamics the load factor is the time";
  // The energy moves between its parts: at least a fifth is strain energy at some step.
  double maxStrain = 0.0;
  for (const auto& r : h) maxStrain = std::max(maxStrain, r.strainEnergy);
  EXPECT_GT(maxStrain, 0.2 * E0);
  if (isRoot()) std::cout << "[dynamics] trapezoidal energy drift over 40 steps: " << worst << "\n";
}

TEST(Dynamics, GammaAboveOneHalfDampsTheEnergy) {
  PL deck = barDeck(20, 2, 10.0, 0.25);
  deck.sublist("Dynamics").set("Newmark Gamma", 0.6);
  deck.sublist("Dynamics").set("Newmark Beta", 0.3025);  // (gamma + 1/2)^2 / 4
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  const auto& h = a.history();
  for (size_t i = 1; i < h.size(); ++i)
    EXPECT_LE(totalEnergy(h[i]), totalEnergy(h[i - 1]) * (1 + kEnergyConservation)) << "step " << i + 1;
  EXPECT_LT(totalEnergy(h.back()), 0.99 * totalEnergy(h.front()));
}

/// An integrator: Integrator and its parameter, for the parameterised tests.
struct Scheme {
  const char* integrator;
  const char* parameter;  ///< "" for none
  double value;
};
const Scheme kSchemes[] = {{"Newmark", "", 0.0}, {"HHT-alpha", "HHT Alpha", -0.1},
                           {"Generalized-alpha", "Spectral Radius", 0.8}};
void setScheme(PL& deck, const Scheme& s) {
  deck.sublist("Dynamics").set("Integrator", std::string(s.integrator));
  if (*s.parameter) deck.sublist("Dynamics").set(s.parameter, s.value);
}

/// The model's K (at u = 0), M and modes on its free DOFs, dense (one
/// rank), and which free DOFs are x components.
struct FreeModes {
  std::vector<int> free;
  Eigen::MatrixXd K, M;
  std::vector<char> isX;  ///< per free DOF
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> modes;  ///< M-orthonormal
  explicit FreeModes(const ddc::Model& m) {
    const int n = static_cast<int>(m.ownedMap()->getGlobalNumElements());
    auto Kg = m.createMatrix();
    auto zero = m.createVector();
    ddc::AssemblyRequest request;
    request.tangent = Kg.get();
    m.assemble(*zero, 0.0, request);
    std::vector<char> x(n, 0);
    for (int node = 0; node < m.mesh().numNodes(); ++node) x[m.dof(node, 0)] = 1;
    for (int g = 0; g < n; ++g)
      if (!m.isConstrained(g)) free.push_back(g), isX.push_back(x[g]);
    const int f = static_cast<int>(free.size());
    K.resize(f, f);
    M.resize(f, f);
    auto e = m.createVector(), Ke = m.createVector(), Me = m.createVector();
    for (int j = 0; j < f; ++j) {
      e->putScalar(0.0);
      e->replaceGlobalValue(free[j], 1.0);
      Kg->apply(*e, *Ke);
      m.applyMass(*e, *Me);
      auto kd = Ke->getData(), md = Me->getData();
      for (int i = 0; i < f; ++i) K(i, j) = kd[free[i]], M(i, j) = md[free[i]];
    }
    modes.compute(K, M);
  }
};

/// The error of u(T) of a run of barDeck(4, 1, ...) against the exact
/// solution of its semi-discrete system M ü + C u̇ + K u = 0, C = α_R M +
/// β_R K, over the free DOFs: with the model's own modes φ_k, ω_k (M- and
/// K-orthogonal, so C is diagonal too: 2 ζ_k ω_k = α_R + β_R ω_k²),
/// u(T) = Σ_k φ_k (φ_kᵀ M v0) q_k(T), q_k(T) = e^{−ζ ω T} sin(ω_d T)/ω_d,
/// ω_d = ω √(1 − ζ²) (sinh and √(ζ² − 1) for an overdamped mode, as the
/// bar's lowest bending mode is at the test's damping), relative to the
/// largest |u(T)|.
double modalError(const ddc::Analysis& a, double T, double alphaR, double betaR) {
  const FreeModes fm(a.model());
  const auto& free = fm.free;
  const auto& modes = fm.modes;
  const Eigen::MatrixXd& Mf = fm.M;
  const int f = static_cast<int>(free.size());
  // The initial velocity: 0.1 on every free x DOF.
  Eigen::VectorXd v(f);
  for (int i = 0; i < f; ++i) v[i] = fm.isX[i] ? 0.1 : 0.0;
  Eigen::VectorXd exact = Eigen::VectorXd::Zero(f);
  for (int k = 0; k < f; ++k) {
    const Eigen::VectorXd phi = modes.eigenvectors().col(k);  // M-orthonormal
    const double w = std::sqrt(modes.eigenvalues()[k]);
    const double zeta = 0.5 * (alphaR / w + betaR * w);
    // q(T) for q(0) = 0, q'(0) = 1: under-, over- or critically damped.
    const double s = w * std::sqrt(std::abs(1.0 - zeta * zeta));
    const double q = s < 1e-12 * w ? T
                     : zeta < 1.0  ? std::sin(s * T) / s
                                   : std::sinh(s * T) / s;
    exact += phi * (phi.dot(Mf * v)) * std::exp(-zeta * w * T) * q;
  }
  auto ud = a.displacement().getData();
  double err = 0.0;
  for (int i = 0; i < f; ++i) err = std::max(err, std::abs(ud[free[i]] - exact[i]));
  return err / exact.cwiseAbs().maxCoeff();
}

/// The observed order of u(T) in the time step, h = 0.5, 0.25, 0.125, with
/// Rayleigh damping α_R, β_R.
void expectSecondOrder(const Scheme& scheme, double alphaR, double betaR) {
  const double T = 5.0;
  std::vector<double> errors;
  for (double dt : {0.5, 0.25, 0.125}) {
    PL deck = barDeck(4, 1, T, dt);
    setScheme(deck, scheme);
    deck.sublist("Dynamics").set("Rayleigh Alpha", alphaR);
    deck.sublist("Dynamics").set("Rayleigh Beta", betaR);
    ddc::Analysis a(worldComm(), deck);
    a.run("");
    errors.push_back(modalError(a, T, alphaR, betaR));
  }
  const double order1 = std::log2(errors[0] / errors[1]), order2 = std::log2(errors[1] / errors[2]);
  std::cout << "[dynamics] " << scheme.integrator << (alphaR + betaR > 0 ? " (Rayleigh damping)" : "")
            << ": u(T) errors " << errors[0] << " " << errors[1] << " " << errors[2] << ", observed orders "
            << order1 << " " << order2 << "\n";
  EXPECT_NEAR(order2, 2.0, 0.1);
}

TEST(Dynamics, TheBarsLongitudinalPeriodConvergesAtSecondOrderInTheMesh) {
  // The clamped bar (ν = 0: its longitudinal modes are u_x(x) alone, exact
  // in 2-D) has the fundamental period 4L/c = 40; the model's lowest
  // longitudinal eigenfrequency (from its own K and consistent M; the
  // bending modes, lower, are skipped by their mode shape) approaches
  // ω = π c/(2L) from above at second order in the element size.
  if (worldComm()->getSize() > 1) GTEST_SKIP() << "the dense eigenproblem is built on one rank";
  const double exact = M_PI / 20.0;
  std::vector<double> errors;
  for (int nx : {10, 20, 40}) {
    PL deck = barDeck(nx, 1, 1.0, 0.5);
    ddc::Analysis a(worldComm(), deck);
    const FreeModes fm(a.model());
    const int f = static_cast<int>(fm.free.size());
    double omega = -1.0;
    for (int k = 0; k < f && omega < 0.0; ++k) {
      const Eigen::VectorXd phi = fm.modes.eigenvectors().col(k);
      double x = 0.0, y = 0.0;
      for (int i = 0; i < f; ++i) (fm.isX[i] ? x : y) += phi[i] * phi[i];
      if (y < 1e-20 * x) omega = std::sqrt(fm.modes.eigenvalues()[k]);  // u_x alone: longitudinal
    }
    ASSERT_GT(omega, 0.0) << "no longitudinal mode at nx = " << nx;
    EXPECT_GT(omega, exact) << "consistent mass: from above";
    errors.push_back(omega / exact - 1.0);
  }
  const double order = std::log2(errors[1] / errors[2]);
  std::cout << "[dynamics] longitudinal period 2 pi / omega against 40: frequency errors " << errors[0] << " "
            << errors[1] << " " << errors[2] << ", observed order " << std::log2(errors[0] / errors[1]) << " "
            << order << "\n";
  EXPECT_NEAR(order, 2.0, 0.1);
}

class DynamicsScheme : public testing::TestWithParam<Scheme> {};

TEST_P(DynamicsScheme, SecondOrderInTheTimeStep) {
  // Exact reference: the semi-discrete system of the same (small) model,
  // u(t) = Σ_k φ_k (φ_kᵀ M v0) sin(ω_k t) / ω_k over its free DOFs.
  if (worldComm()->getSize() > 1) GTEST_SKIP() << "the dense reference is built on one rank";
  expectSecondOrder(GetParam(), 0.0, 0.0);
}

TEST_P(DynamicsScheme, SecondOrderWithRayleighDamping) {
  // The same with C = 0.05 M + 0.02 K (the lowest, bending mode
  // overdamped, the others underdamped), the exact damped modes as
  // reference.
  if (worldComm()->getSize() > 1) GTEST_SKIP() << "the dense reference is built on one rank";
  expectSecondOrder(GetParam(), 0.05, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Schemes, DynamicsScheme, testing::ValuesIn(kSchemes),
                         [](const testing::TestParamInfo<Scheme>& i) {
                           std::string n = i.param.integrator;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

TEST(Dynamics, TheAlphaMethodsDampTheHighFrequenciesAsTheirParameterSays) {
  // Steps far beyond the bar's periods (h = 100, every mode has ω h > 15):
  // the α-methods dissipate, more for a smaller spectral radius (a more
  // negative HHT alpha); the energy never grows.
  std::vector<double> finalEnergy;
  for (const Scheme& s : {Scheme{"Generalized-alpha", "Spectral Radius", 0.9},
                          Scheme{"Generalized-alpha", "Spectral Radius", 0.5}, Scheme{"HHT-alpha", "HHT Alpha", -0.05},
                          Scheme{"HHT-alpha", "HHT Alpha", -0.3}}) {
    PL deck = barDeck(20, 2, 1500.0, 100.0);
    setScheme(deck, s);
    ddc::Analysis a(worldComm(), deck);
    a.run("");
    const auto& h = a.history();
    for (size_t i = 1; i < h.size(); ++i)
      EXPECT_LE(totalEnergy(h[i]), totalEnergy(h[i - 1]) * (1 + kEnergyConservation))
          << s.integrator << " " << s.value << ", step " << i + 1;
    finalEnergy.push_back(totalEnergy(h.back()) / totalEnergy(h.front()));
    if (isRoot())
      std::cout << "[dynamics] " << s.integrator << " " << s.parameter << " = " << s.value
                << ": energy after 15 steps of h = 100 / first step " << finalEnergy.back() << "\n";
  }
  EXPECT_LT(finalEnergy[0], 1.0);
  EXPECT_LT(finalEnergy[1], finalEnergy[0]) << "rho_inf 0.5 damps more than 0.9";
  EXPECT_LT(finalEnergy[2], 1.0);
  EXPECT_LT(finalEnergy[3], finalEnergy[2]) << "HHT alpha -0.3 damps more than -0.05";
}

TEST(Dynamics, AFreeBodyFallsAtTheGravitationalAcceleration) {
  // No boundary condition: under Gravity every node moves by g t^2 / 2 with
  // velocity g t — the trapezoidal rule integrates a constant acceleration
  // exactly once the initial acceleration balances M g — for the consistent
  // and the lumped masses; the kinetic energy is the work of gravity.
  for (const char* mass : {"Consistent", "HRZ"}) {
    PL deck = barDeck(8, 2, 1.0, 0.25);
    deck.sublist("Boundary Conditions").remove("Clamped");
    deck.sublist("Dynamics").sublist("Initial Velocity").remove("Push");
    deck.sublist("Dynamics").set("Mass Matrix", std::string(mass));
    PL& g = deck.sublist("Dynamics").sublist("Gravity").sublist("Earth");
    g.set("Set", std::string("Bar"));
    g.set("Acceleration Y", -2.0);
    ddc::Analysis a(worldComm(), deck);
    a.run("");
    const auto& m = a.model();
    double worstU = 0.0, worstV = 0.0;
    auto u = a.displacement().getData();
    auto v = a.velocity()->getData();
    for (int n = 0; n < m.mesh().numNodes(); ++n) {
      const ddc::GO gid = m.dof(n, 1);
      if (!m.ownedMap()->isNodeGlobalElement(gid)) continue;
      const ddc::LO l = m.ownedMap()->getLocalElement(gid);
      worstU = std::max(worstU, std::abs(u[l] - (-1.0)));  // ½ g t² at t = 1
      worstV = std::max(worstV, std::abs(v[l] - (-2.0)));
    }
    EXPECT_LT(worstU, kEnergyConservation) << mass;
    EXPECT_LT(worstV, kEnergyConservation) << mass;
    for (const auto& r : a.history())
      EXPECT_NEAR(r.kineticEnergy + r.strainEnergy, r.externalWork, kEnergyConservation * r.externalWork) << mass;
  }
}

TEST(Dynamics, GravityOnAClampedBarBalancesTheEnergy) {
  // The clamped bar released under gravity along it: kinetic + strain energy
  // equals the work of gravity at every step (trapezoidal rule, linear
  // problem) — which holds only with the initial acceleration solved from
  // M a0 = M g on the free DOFs (a0 = g is wrong next to the clamp).
  PL deck = barDeck(20, 2, 10.0, 0.25);
  deck.sublist("Dynamics").sublist("Initial Velocity").remove("Push");
  PL& g = deck.sublist("Dynamics").sublist("Gravity").sublist("Along");
  g.set("Set", std::string("Bar"));
  g.set("Acceleration X", 0.01);
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  double worst = 0.0, peak = 0.0;
  for (const auto& r : a.history()) {
    worst = std::max(worst, std::abs(r.kineticEnergy + r.strainEnergy - r.externalWork));
    peak = std::max(peak, r.externalWork);
  }
  ASSERT_GT(peak, 0.0);
  EXPECT_LT(worst / peak, kEnergyConservation);
  if (worldComm()->getRank() == 0)
    std::cout << "[gravity] clamped bar: |E - W| / max W = " << worst / peak << "\n";
}

/// One step of the Newmark-α family for the single mode q̈ + ω² q = 0 (the
/// formulas of DDC_TimeIntegrator.hpp written out for one DOF, independently
/// of the code): the state (q, q̇, q̈) after one step of h.
Eigen::Vector3d modalStep(const ddc::NewmarkParameters& p, double w2, double h, const Eigen::Vector3d& x) {
  const double qt = x[0] + h * x[1] + h * h * (0.5 - p.beta) * x[2], vt = x[1] + h * (1.0 - p.gamma) * x[2];
  const double a1 = -(p.alphaM * x[2] + (1.0 - p.alphaF) * w2 * qt + p.alphaF * w2 * x[0]) /
                    ((1.0 - p.alphaM) + (1.0 - p.alphaF) * w2 * p.beta * h * h);
  return {qt + p.beta * h * h * a1, vt + p.gamma * h * a1, a1};
}

TEST(Dynamics, TheAlphaMethodsDampAStiffModeAtTheirSpectralRadius) {
  // One Quad4 (1 x 1, ν = 0) clamped on its left edge, its right edge held
  // in y and started at q̇ = 1 in x: by symmetry a single mode of frequency
  // ω moves. At ω h = 1e6 (a mode far beyond the step) the energy per step
  // of the run equals that of the modal recurrence to round-off, and the
  // recurrence's spectral radius (of its 3 x 3 amplification matrix) is the
  // documented high-frequency damping: ρ∞ for generalised-α,
  // (1 + α)/(1 − α) for HHT-α.
  if (worldComm()->getSize() > 1) GTEST_SKIP() << "one element";
  struct Case {
    Scheme scheme;
    ddc::NewmarkParameters p;
    double documented;
  };
  const Case cases[] = {
      {{"Generalized-alpha", "Spectral Radius", 0.5}, ddc::NewmarkParameters::generalisedAlpha(0.5, "t"), 0.5},
      {{"Generalized-alpha", "Spectral Radius", 0.8}, ddc::NewmarkParameters::generalisedAlpha(0.8, "t"), 0.8},
      {{"HHT-alpha", "HHT Alpha", -0.3}, ddc::NewmarkParameters::hht(-0.3, "t"), 0.7 / 1.3},
      {{"HHT-alpha", "HHT Alpha", -0.1}, ddc::NewmarkParameters::hht(-0.1, "t"), 0.9 / 1.1}};
  for (const Case& c : cases) {
    // The mode's frequency from the model (any step: the run is rebuilt).
    auto deckFor = [&](double h, int steps) {
      PL deck("DDContact");
      RectangleSpec r;
      r.nx = r.ny = 1;
      r.material = "Linear Elastic";
      r.E = 1.0;
      r.nu = 0.0;
      addRectangle(deck, "Cell", r).sublist("Element").sublist("Material").set("Density", 1.0);
      addDisplacement(deck, "Clamped", "Cell/left", "XY");
      addDisplacement(deck, "Guided", "Cell/right", "Y");
      PL& dyn = deck.sublist("Dynamics");
      dyn.set("Final Time", h * steps);
      dyn.set("Time Step", h);
      dyn.sublist("Initial Velocity").sublist("Push").set("Set", std::string("Cell/right"));
      dyn.sublist("Initial Velocity").sublist("Push").set("Velocity X", 1.0);
      setScheme(deck, c.scheme);
      deck.sublist("Output").set("Progress", false);
      deck.sublist("Output").set("VTK", false);
      return deck;
    };
    PL probe = deckFor(1.0, 1);
    ddc::Analysis first(worldComm(), probe);
    const FreeModes fm(first.model());
    ASSERT_EQ(fm.free.size(), 2u);
    const double w2 = fm.K.sum() / fm.M.sum();  // the symmetric mode (1, 1)
    // ω h far beyond 1: the spectral radius tends to its limit slowly near
    // the (triple) root at infinity (0.537 for ρ∞ = 0.5 at ω h = 100).
    constexpr double kOmegaH = 1e6;
    const double h = kOmegaH / std::sqrt(w2);
    constexpr int kSteps = 12;
    PL deck = deckFor(h, kSteps);
    ddc::Analysis a(worldComm(), deck);
    a.run("");
    // E_n / E_0 of the run against (q̇_n² + ω² q_n²) / q̇_0² of the recurrence.
    Eigen::Vector3d x(0.0, 1.0, 0.0);
    const double E0 = 0.5 * fm.M.sum();  // ½ v0ᵀ M v0 with v0 = (1, 1)
    double worst = 0.0;
    for (const auto& r : a.history()) {
      x = modalStep(c.p, w2, h, x);
      const double expected = x[1] * x[1] + w2 * x[0] * x[0];
      worst = std::max(worst, std::abs((r.strainEnergy + r.kineticEnergy) / E0 - expected) / expected);
    }
    EXPECT_LT(worst, 1e-8) << c.scheme.integrator << " " << c.scheme.value;
    // The amplification matrix's spectral radius.
    Eigen::Matrix3d A;
    for (int j = 0; j < 3; ++j) A.col(j) = modalStep(c.p, w2, h, Eigen::Vector3d::Unit(j));
    const double rho = A.eigenvalues().cwiseAbs().maxCoeff();
    EXPECT_NEAR(rho / c.documented, 1.0, 0.01) << c.scheme.integrator << " " << c.scheme.value;
    std::cout << "[dynamics] " << c.scheme.integrator << " " << c.scheme.parameter << " = " << c.scheme.value
              << ": omega h = " << kOmegaH << ", run vs modal recurrence " << worst << ", spectral radius " << rho
              << " (documented " << c.documented << ")\n";
  }
}

TEST(Dynamics, FetiDpEqualsMonolithic) {
  // Undamped, and with Rayleigh damping under HHT-alpha (K^s (1 + β_R γ/(βh))
  // + (c + α_R γ/(βh)) M^s per subdomain, the previous step's C v_n).
  for (const bool damped : {false, true}) {
    std::vector<std::vector<ddc::StepRecord>> runs;
    for (const char* strategy : {"Monolithic", "FETI-DP"}) {
      PL deck = barDeck(20, 2, 5.0, 0.25);
      deck.sublist("Solver").set("Strategy", std::string(strategy));
      deck.sublist("Partition").set("Number of Subdomains", 4);
      if (damped) {
        deck.sublist("Dynamics").set("Integrator", std::string("HHT-alpha"));
        deck.sublist("Dynamics").set("Rayleigh Alpha", 0.05);
        deck.sublist("Dynamics").set("Rayleigh Beta", 0.02);
      }
      ddc::Analysis a(worldComm(), deck);
      a.run("");
      runs.push_back(a.history());
    }
    ASSERT_EQ(runs[0].size(), runs[1].size());
    double worst = 0.0;
    for (size_t i = 0; i < runs[0].size(); ++i) {
      const double E = totalEnergy(runs[0][i]);
      worst = std::max({worst, std::abs(runs[0][i].strainEnergy - runs[1][i].strainEnergy) / E,
                        std::abs(runs[0][i].kineticEnergy - runs[1][i].kineticEnergy) / E});
    }
    EXPECT_LT(worst, kFetiAgreement) << (damped ? "damped" : "undamped");
    if (isRoot())
      std::cout << "[dynamics] FETI-DP vs Monolithic" << (damped ? " (HHT-alpha, Rayleigh damping)" : "")
                << ", worst energy difference per step: " << worst << "\n";
  }
}

TEST(Dynamics, TheVtkOutputHasVelocityAndAcceleration) {
  // Step 0: the initial velocity (0.1 along x off the clamped edge, 0 on it)
  // and zero acceleration; a later step: some acceleration.
  namespace fs = std::filesystem;
  const fs::path dir = fs::current_path() / ("dynamics_vtk_np" + std::to_string(worldComm()->getSize()));
  if (isRoot()) fs::remove_all(dir);
  worldComm()->barrier();
  PL deck = barDeck(4, 1, 1.0, 0.25);
  deck.sublist("Output").set("VTK", true);
  ddc::Analysis a(worldComm(), deck);
  a.run(dir.string());
  if (isRoot()) {
    auto read = [](const fs::path& f) {
      std::ifstream in(f);
      std::stringstream ss;
      ss << in.rdbuf();
      return ss.str();
    };
    auto arrayOf = [](const std::string& xml, const std::string& name) {
      const std::size_t tag = xml.find("Name=\"" + name + "\" NumberOfComponents=\"3\"");
      EXPECT_NE(tag, std::string::npos) << name;
      std::vector<double> v;
      if (tag == std::string::npos) return v;
      const std::size_t open = xml.find('>', tag), close = xml.find("</DataArray>", open);
      std::istringstream in(xml.substr(open + 1, close - open - 1));
      for (double x; in >> x;) v.push_back(x);
      return v;
    };
    double maxV0 = 0.0, minV0 = 1.0, maxA0 = 0.0, maxA4 = 0.0;
    for (const auto& entry : fs::directory_iterator(dir / "vtk")) {
      const std::string name = entry.path().filename().string();
      if (entry.path().extension() != ".vtu") continue;
      const std::string xml = read(entry.path());
      if (name.rfind("step_00000_", 0) == 0) {
        const auto v = arrayOf(xml, "velocity"), acc = arrayOf(xml, "acceleration");
        for (size_t i = 0; i < v.size(); i += 3) maxV0 = std::max(maxV0, v[i]), minV0 = std::min(minV0, v[i]);
        for (double x : acc) maxA0 = std::max(maxA0, std::abs(x));
      }
      if (name.rfind("step_00004_", 0) == 0)
        for (double x : arrayOf(xml, "acceleration")) maxA4 = std::max(maxA4, std::abs(x));
    }
    EXPECT_EQ(maxV0, 0.1) << "the initial velocity";
    EXPECT_EQ(minV0, 0.0) << "the clamped nodes start at rest";
    EXPECT_EQ(maxA0, 0.0) << "no load at t = 0";
    EXPECT_GT(maxA4, 0.0) << "the clamp decelerates the bar";
    fs::remove_all(dir);
  }
  worldComm()->barrier();
}

TEST(Dynamics, BadInputNamesTheParameter) {
  {
    PL deck = barDeck(4, 1, 1.0, 0.25);
    deck.sublist("Mesh").sublist("Bodies").sublist("Bar").sublist("Element").sublist("Material").set("Density", 0.0);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("set 'Mesh/Bodies/Bar/Element/Material/Density' > 0"), std::string::npos) << msg;
  }
  {
    PL deck = barDeck(4, 1, 1.0, 0.3);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("'Dynamics/Final Time' = 1 is not a whole number of 'Dynamics/Time Step' = 0.3"),
              std::string::npos)
        << msg;
  }
  {
    PL deck = barDeck(4, 1, 1.0, 0.25);
    deck.sublist("Dynamics").set("Newmark Beta", 0.2);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("unconditionally stable only for 2 beta >= gamma >= 1/2"), std::string::npos) << msg;
  }
  {
    PL deck = barDeck(4, 1, 1.0, 0.25);
    deck.sublist("Dynamics").set("Newmark Gamma", 0.4);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("Dynamics/Newmark Gamma"), std::string::npos) << msg;
  }
  {
    PL deck = barDeck(4, 1, 1.0, 0.25);
    deck.sublist("Dynamics").sublist("Initial Velocity").sublist("Push").set("Set", std::string("Nope"));
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("'Dynamics/Initial Velocity/Push/Set' = 'Nope' is neither a body"), std::string::npos)
        << msg;
  }
  {
    PL deck = barDeck(4, 1, 1.0, 0.25);
    deck.sublist("Dynamics").sublist("Initial Velocity").sublist("Push").set("Velocity Z", 1.0);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("'Dynamics/Initial Velocity/Push/Velocity Z' is set but the model is 2-D"),
              std::string::npos)
        << msg;
  }
  {
    PL deck = barDeck(4, 1, 1.0, 0.25);
    deck.sublist("Dynamics").set("Integrator", std::string("HHT-alpha"));
    deck.sublist("Dynamics").set("HHT Alpha", -0.5);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("Dynamics/HHT Alpha"), std::string::npos) << msg;
  }
  {
    PL deck = barDeck(4, 1, 1.0, 0.25);
    deck.sublist("Dynamics").set("Integrator", std::string("Generalized-alpha"));
    deck.sublist("Dynamics").set("Spectral Radius", 1.5);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("Dynamics/Spectral Radius"), std::string::npos) << msg;
  }
  {
    // Row-sum masses are not positive at the corners of Hex20 (and Tet10).
    PL deck("DDContact");
    BoxSpec b;
    b.element = "Hex20";
    b.elements[0] = 2;  // one element per rank at least
    b.elements[1] = b.elements[2] = 1;
    addBox(deck, "Brick", b).sublist("Element").sublist("Material").set("Density", 1.0);
    addDisplacement(deck, "Clamped", "Brick/left", "XYZ");
    deck.sublist("Dynamics").set("Integrator", std::string("Newmark"));
    deck.sublist("Dynamics").set("Mass Matrix", std::string("Row-Sum"));
    deck.sublist("Output").set("Progress", false);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("'Dynamics/Mass Matrix' = Row-Sum gives zero or negative masses at the corners of Hex20"),
              std::string::npos)
        << msg;
  }
  {
    // Contact-surface mass redistribution needs a node off the surfaces in
    // every element: a bar one element thick, in contact on both faces, has
    // none.
    PL deck = barDeck(4, 1, 1.0, 0.25);
    for (const char* name : {"Top", "Floor"}) {
      RectangleSpec r;
      r.originY = std::string(name) == "Top" ? 1.0 : -0.5;
      r.lengthX = 2.0;
      r.lengthY = 0.5;
      r.nx = 2;
      r.ny = 1;
      addRectangle(deck, name, r).sublist("Element").sublist("Material").set("Density", 1.0);
    }
    PL& pairs = deck.sublist("Contact").sublist("Pairs");
    pairs.sublist("Above").set("Slave", std::string("Top/bottom"));
    pairs.sublist("Above").set("Master", std::string("Bar/top"));
    pairs.sublist("Below").set("Slave", std::string("Bar/bottom"));
    pairs.sublist("Below").set("Master", std::string("Floor/top"));
    addDisplacement(deck, "FloorHeld", "Floor/bottom", "XY");
    addDisplacement(deck, "TopHeld", "Top/top", "XY");
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("'Dynamics/Contact Surface Mass' = Redistributed: element 0 of body 'Bar' has all its nodes "
                       "on contact surfaces"),
              std::string::npos)
        << msg;
    // Kept: the same deck is accepted.
    deck.sublist("Dynamics").set("Contact Surface Mass", std::string("Kept"));
    EXPECT_NO_THROW(ddc::Analysis(worldComm(), deck));
  }
  {
    PL deck = barDeck(4, 1, 1.0, 0.25);
    deck.sublist("Dynamics").sublist("Initial Velocity").set("Loose", 0.1);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("'Dynamics/Initial Velocity/Loose' must be a sublist"), std::string::npos) << msg;
  }
  {
    PL deck = barDeck(4, 1, 1.0, 0.25);
    PL& g = deck.sublist("Dynamics").sublist("Gravity").sublist("Down");
    g.set("Set", std::string("Bar/left"));
    g.set("Acceleration Y", -1.0);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("'Dynamics/Gravity/Down/Set' = 'Bar/left' is not a body"), std::string::npos) << msg;
  }
  {
    PL deck = barDeck(4, 1, 1.0, 0.25);
    PL& g = deck.sublist("Dynamics").sublist("Gravity").sublist("Down");
    g.set("Set", std::string("Bar"));
    g.set("Acceleration Z", -1.0);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("'Dynamics/Gravity/Down/Acceleration Z' is set but the model is 2-D"), std::string::npos)
        << msg;
  }
  {
    PL deck = barDeck(4, 1, 1.0, 0.25);
    deck.sublist("Dynamics").set("Rayleigh Beta", -0.1);
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("'Dynamics/Rayleigh Beta' must be >= 0 and finite, got -0.1"), std::string::npos) << msg;
  }
  {
    PL deck = barDeck(4, 1, 1.0, 0.25);
    deck.sublist("Dynamics").set("Integrator", std::string("Explicit"));
    const std::string msg = inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
    EXPECT_NE(msg.find("Dynamics/Integrator"), std::string::npos) << msg;
  }
}

}  // namespace
