// Verification checks that need the whole analysis (doc/verification.md;
// item 1 is rung 2 of its ladder, the others are checks beside it):
//   1. patch tests on distorted meshes (affine boundary data -> exact affine
//      solution, uniform closed-form stress), Quad4 / Quad9 x 3 materials;
//   2. a 90 degree rigid rotation stores no energy and no stress (objectivity);
//   3. plane-strain uniaxial stretch of a neo-Hookean block against the
//      closed-form homogeneous solution (lateral stretch from sigma_yy = 0);
//   4. cantilever against Timoshenko beam theory, with mesh refinement;
//   5. rank independence: world communicator vs MPI_COMM_SELF;
//   6. linear elasticity energy identity U = 1/2 f_ext . u.
// Every model is built from an in-memory Teuchos::ParameterList. The test
// runs on 1 and 2 ranks; the measured numbers are printed on rank 0 so they
// can be quoted in doc/verification.md.
#include <gtest/gtest.h>
#include <mpi.h>

#include <Eigen/Dense>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_Core.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_Error.hpp"
#include "DDC_AnalysisTestDecks.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using PL = Teuchos::ParameterList;
using Comm = Teuchos::RCP<const Teuchos::Comm<int>>;
using ddc::test::relDiff;
using namespace ddc::test;  // deck builders, communicators (DDC_AnalysisTestDecks.hpp)

// ---------------------------------------------------------------------------
// Named tolerances of this file (see also DDC_TestTolerances.hpp).

/// Patch test, nodal displacements: |u_h - H X| relative to max |H X|. The
/// finite element space contains the exact (affine) solution, so the only
/// error is the Newton stopping criterion (residual 1e-8 relative, then one
/// more quadratically convergent correction) and round-off amplified by the
/// condition number of K: measured <= 5e-16 (1 and 2 ranks), while any
/// element or assembly bug shows up as O(1e-3) or larger.
constexpr double kPatchDisplacement = 1e-9;

/// Patch test, element Cauchy stresses against the closed form, relative to
/// the largest closed-form stress component. Stresses are gradients: the
/// displacement error above divided by an element size (~0.15 on the
/// distorted 4x4 mesh of a unit square) times the stiffness, i.e. about ten
/// times kPatchDisplacement. Measured <= 3e-15.
constexpr double kPatchStress = 1e-8;

/// Rigid rotation, strain energy relative to the energy of a 10% uniaxial
/// plane-strain stretch of the same block. In exact arithmetic it is 0; with
/// F = R + O(eps) the energy density is O(mu eps) (ln J and tr C - 2 are
/// linear in the round-off), i.e. ~1e-13 relative to the reference. A
/// non-objective formulation (e.g. small-strain elasticity, checked below)
/// gives a ratio > 1 (286 measured, see SmallStrainElasticityIsNotObjective).
/// Measured: 7e-16 (neo-Hookean), 2e-28 (SVK, quadratic in E).
constexpr double kRigidEnergy = 1e-10;

/// Rigid rotation, largest Cauchy stress component relative to mu.
/// Round-off strain O(1e-15) times the stiffness plus the Newton error.
/// Measured <= 3e-15.
constexpr double kRigidStress = 1e-9;

/// Homogeneous deformations (uniaxial stretch): strain energy and nodal
/// displacements against the closed form; the FE space holds the exact
/// solution, so like kPatchDisplacement this only covers Newton's stopping
/// criterion and round-off (and the 1e-14 scalar Newton of the test).
constexpr double kHomogeneous = 1e-9;


// ---------------------------------------------------------------------------
// Helpers.

/// A rectangle body "Block" with one element type and material.
using BlockSpec = ddc::test::RectangleSpec;

PL blockDeck(const BlockSpec& s, int steps) {
  PL deck("DDContact");
  addRectangle(deck, "Block", s);
  setRunOptions(deck, steps);
  return deck;
}

/// Element Cauchy stresses (xx, yy, xy, zz) of every element on every rank.
std::vector<std::array<double, 4>> gatherCauchy(const ddc::Analysis& a) {
  const ddc::Model& m = a.model();
  const ddc::Mesh& mesh = m.mesh();
  auto uov = m.toOverlap(a.displacement());
  auto ud = uov->getData();
  const auto& ov = *m.overlapMap();
  const int ne = mesh.numElements();
  std::vector<double> local(4 * ne, 0.0), global(4 * ne, 0.0);
  Eigen::MatrixX2d X, u;
  for (int e : m.localElements()) {
    const int nn = mesh.elementNumNodes(e);
    X.resize(nn, 2);
    u.resize(nn, 2);
    for (int i = 0; i < nn; ++i) {
      const int n = mesh.elementNodes(e)[i];
      for (int c = 0; c < 2; ++c) {
        X(i, c) = mesh.coord(n)[c];
        u(i, c) = ud[ov.getLocalElement(m.dof(n, c))];
      }
    }
    ddc::ElementPostResult post;
    m.elementOf(e).postprocess(X, u, post);
    const int slot[4] = {0, 1, 5, 2};  // xx, yy, xy, zz in post.cauchy
    for (int k = 0; k < 4; ++k) local[4 * e + k] = post.cauchy[slot[k]];
  }
  Teuchos::reduceAll(*m.comm(), Teuchos::REDUCE_SUM, 4 * ne, local.data(), global.data());
  std::vector<std::array<double, 4>> out(ne);
  for (int e = 0; e < ne; ++e)
    for (int k = 0; k < 4; ++k) out[e][k] = global[4 * e + k];
  return out;
}

/// Nodes of a node set ("Block/left", ...).
const std::vector<int>& nodeSet(const ddc::Analysis& a, const std::string& name) {
  return a.model().mesh().nodeSet(name);
}

// ---------------------------------------------------------------------------
// Closed-form plane-strain material laws (F33 = 1), written out here
// independently of DDC_Material.cpp.

struct Lame {
  double lambda, mu;
  Lame(double E, double nu) : lambda(E * nu / ((1 + nu) * (1 - 2 * nu))), mu(E / (2 * (1 + nu))) {}
};

/// Strain energy density W(F).
double energyDensity(const std::string& material, const Lame& L, const Eigen::Matrix2d& F) {
  if (material == "Linear Elastic") {
    const Eigen::Matrix2d eps = 0.5 * (F + F.transpose()) - Eigen::Matrix2d::Identity();
    return 0.5 * L.lambda * eps.trace() * eps.trace() + L.mu * (eps.array() * eps.array()).sum();
  }
  if (material == "Neo-Hookean") {
    const double J = F.determinant(), I1 = (F.transpose() * F).trace() + 1.0;
    return 0.5 * L.mu * (I1 - 3) - L.mu * std::log(J) + 0.5 * L.lambda * std::log(J) * std::log(J);
  }
  // St. Venant-Kirchhoff, E33 = 0.
  const Eigen::Matrix2d E = 0.5 * (F.transpose() * F - Eigen::Matrix2d::Identity());
  return 0.5 * L.lambda * E.trace() * E.trace() + L.mu * (E.array() * E.array()).sum();
}

/// Cauchy stress (xx, yy, xy, zz) of a homogeneous deformation F.
std::array<double, 4> cauchyStress(const std::string& material, const Lame& L, const Eigen::Matrix2d& F) {
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  Eigen::Matrix2d s;
  double szz;
  if (material == "Linear Elastic") {
    const Eigen::Matrix2d eps = 0.5 * (F + F.transpose()) - I;
    s = L.lambda * eps.trace() * I + 2 * L.mu * eps;
    szz = L.lambda * eps.trace();
  } else if (material == "Neo-Hookean") {
    // sigma = mu/J (b - I) + lambda ln J / J I; b33 = 1 so sigma_zz = lambda ln J / J.
    const double J = F.determinant();
    s = L.mu / J * (F * F.transpose() - I) + L.lambda * std::log(J) / J * I;
    szz = L.lambda * std::log(J) / J;
  } else {
    // sigma = F S F^T / J with S = lambda tr E I + 2 mu E; S33 = lambda tr E.
    const double J = F.determinant();
    const Eigen::Matrix2d E = 0.5 * (F.transpose() * F - I);
    const Eigen::Matrix2d S = L.lambda * E.trace() * I + 2 * L.mu * E;
    s = F * S * F.transpose() / J;
    szz = L.lambda * E.trace() / J;
  }
  return {s(0, 0), s(1, 1), s(0, 1), szz};
}

// ---------------------------------------------------------------------------
// 1. Patch tests.

struct PatchCase {
  std::string element, material;
  bool large;  ///< the large displacement gradient (hyperelastic only)
};

std::string patchName(const testing::TestParamInfo<PatchCase>& info) {
  std::string n = info.param.element + "_" + info.param.material + (info.param.large ? "_large" : "_small");
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

class PatchTest : public testing::TestWithParam<PatchCase> {};

TEST_P(PatchTest, AffineBoundaryDataGiveExactAffineSolution) {
  const PatchCase& pc = GetParam();
  Eigen::Matrix2d H;
  if (pc.large)
    H << 0.3, 0.1, 0.05, -0.2;
  else
    H << 0.02, 0.01, -0.005, 0.03;
  BlockSpec spec;
  spec.element = pc.element;
  spec.material = pc.material;
  spec.distortion = 0.2;
  PL deck = blockDeck(spec, pc.large ? 4 : 1);
  for (const char* side : {"left", "right", "bottom", "top"}) {
    PL& c = addDisplacement(deck, std::string("Affine ") + side, std::string("Block/") + side, "XY");
    c.set("Gradient XX", H(0, 0));
    c.set("Gradient XY", H(0, 1));
    c.set("Gradient YX", H(1, 0));
    c.set("Gradient YY", H(1, 1));
  }
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  const ddc::Mesh& mesh = a.model().mesh();

  // Interior nodes: on no side set. The patch test is about them.
  std::set<int> boundary;
  for (const char* side : {"left", "right", "bottom", "top"})
    for (int n : nodeSet(a, std::string("Block/") + side)) boundary.insert(n);
  const auto u = gatherDisplacement(a);
  double maxExact = 0.0, maxErr = 0.0;
  int interior = 0;
  for (int n = 0; n < mesh.numNodes(); ++n) {
    const Eigen::Vector2d X(mesh.coord(n)[0], mesh.coord(n)[1]);
    const Eigen::Vector2d ue = H * X;
    maxExact = std::max(maxExact, ue.cwiseAbs().maxCoeff());
    if (boundary.count(n)) continue;
    ++interior;
    maxErr = std::max(maxErr, (Eigen::Vector2d(u[2 * n], u[2 * n + 1]) - ue).cwiseAbs().maxCoeff());
  }
  ASSERT_GT(interior, 0);
  EXPECT_LE(maxErr, kPatchDisplacement * maxExact) << "interior displacement differs from H X";

  // Element stresses: uniform and equal to the closed form at F = I + H.
  const auto sigma = gatherCauchy(a);
  const auto exact = cauchyStress(pc.material, Lame(spec.E, spec.nu), Eigen::Matrix2d::Identity() + H);
  double scale = 0.0, maxStressErr = 0.0, spread = 0.0;
  for (double s : exact) scale = std::max(scale, std::abs(s));
  for (const auto& se : sigma)
    for (int k = 0; k < 4; ++k) {
      maxStressErr = std::max(maxStressErr, std::abs(se[k] - exact[k]));
      spread = std::max(spread, std::abs(se[k] - sigma[0][k]));
    }
  EXPECT_LE(spread, kPatchStress * scale) << "element stresses are not uniform";
  EXPECT_LE(maxStressErr, kPatchStress * scale) << "element stresses differ from the closed form";
  if (isRoot())
    std::printf("[patch] %-5s %-21s %-5s  max|u-HX|/max|HX| = %.2e  max|sigma-exact|/max|sigma| = %.2e  (%d interior nodes)\n",
                pc.element.c_str(), pc.material.c_str(), pc.large ? "large" : "small", maxErr / maxExact,
                maxStressErr / scale, interior);
}

std::vector<PatchCase> patchCases() {
  std::vector<PatchCase> v;
  for (const char* el : {"Quad4", "Quad9"}) {
    for (const char* mat : {"Linear Elastic", "Neo-Hookean", "St. Venant-Kirchhoff"}) v.push_back({el, mat, false});
    for (const char* mat : {"Neo-Hookean", "St. Venant-Kirchhoff"}) v.push_back({el, mat, true});
  }
  return v;
}

INSTANTIATE_TEST_SUITE_P(DistortedMesh, PatchTest, testing::ValuesIn(patchCases()), patchName);

// ---------------------------------------------------------------------------
// 2. Rigid rotation.

/// 90 degree rotation of a 2 x 1 block about its centre, prescribed on the
/// whole boundary in 4 steps; returns (energy / reference, max |sigma| / mu).
std::array<double, 2> rigidRotation(const std::string& element, const std::string& material, double& uErr) {
  BlockSpec spec;
  spec.element = element;
  spec.material = material;
  spec.lengthX = 2.0;
  spec.nx = 8;
  spec.distortion = 0.2;
  PL deck = blockDeck(spec, 4);
  for (const char* side : {"left", "right", "bottom", "top"}) {
    PL& c = addDisplacement(deck, std::string("Rotate ") + side, std::string("Block/") + side, "XY");
    c.set("Rotation Angle", 90.0);
    c.set("Center X", 1.0);
    c.set("Center Y", 0.5);
  }
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  const Lame L(spec.E, spec.nu);
  Eigen::Matrix2d stretch = Eigen::Matrix2d::Identity();
  stretch(0, 0) = 1.1;
  const double reference = energyDensity(material, L, stretch) * spec.lengthX * spec.lengthY;
  const double energy = a.history().back().strainEnergy;
  double smax = 0.0;
  for (const auto& s : gatherCauchy(a))
    for (double v : s) smax = std::max(smax, std::abs(v));
  // Nodal displacements: u = (R - I)(X - c), R the 90 degree rotation.
  const auto u = gatherDisplacement(a);
  const ddc::Mesh& mesh = a.model().mesh();
  uErr = 0.0;
  for (int n = 0; n < mesh.numNodes(); ++n) {
    const double dx = mesh.coord(n)[0] - 1.0, dy = mesh.coord(n)[1] - 0.5;
    uErr = std::max({uErr, std::abs(u[2 * n] - (-dy - dx)), std::abs(u[2 * n + 1] - (dx - dy))});
  }
  return {std::abs(energy) / reference, smax / L.mu};
}

TEST(RigidRotation, NinetyDegreesStoresNoEnergyAndNoStress) {
  for (const char* el : {"Quad4", "Quad9"})
    for (const char* mat : {"Neo-Hookean", "St. Venant-Kirchhoff"}) {
      double uErr = 0.0;
      const auto r = rigidRotation(el, mat, uErr);
      EXPECT_LE(r[0], kRigidEnergy) << el << " " << mat << ": strain energy of a rigid rotation";
      EXPECT_LE(r[1], kRigidStress) << el << " " << mat << ": stress of a rigid rotation";
      // Max |X - c| is about 1.1, so the displacement scale is 1.
      EXPECT_LE(uErr, kPatchDisplacement) << el << " " << mat << ": displacement is not the rotation";
      if (isRoot())
        std::printf("[rotation] %-5s %-21s  U/U_ref(10%% stretch) = %.2e  max|sigma|/mu = %.2e  max|u-(R-I)(X-c)| = %.2e\n",
                    el, mat, r[0], r[1], uErr);
    }
}

/// The rotation test must be able to fail: small-strain elasticity is not
/// objective, so the same rotation stores a large energy.
TEST(RigidRotation, SmallStrainElasticityIsNotObjective) {
  double uErr = 0.0;
  const auto r = rigidRotation("Quad4", "Linear Elastic", uErr);
  EXPECT_GT(r[0], 1.0);
  if (isRoot()) std::printf("[rotation] Quad4 Linear Elastic (control)  U/U_ref = %.3g\n", r[0]);
}

// ---------------------------------------------------------------------------
// 3. Uniaxial plane-strain stretch of a neo-Hookean block.

/// Lateral stretch l2 of a plane-strain neo-Hookean body stretched by l1 with
/// sigma_yy = 0: S22 = mu (1 - 1/l2^2) + lambda ln(l1 l2) / l2^2 = 0, i.e.
/// g(l2) = mu (l2^2 - 1) + lambda ln(l1 l2) = 0 (monotone in l2).
double lateralStretch(const Lame& L, double l1) {
  double l2 = 1.0;
  for (int it = 0; it < 50; ++it) {
    const double g = L.mu * (l2 * l2 - 1) + L.lambda * std::log(l1 * l2);
    const double dg = 2 * L.mu * l2 + L.lambda / l2;
    const double step = g / dg;
    l2 -= step;
    if (std::abs(step) < 1e-15) break;
  }
  return l2;
}

TEST(UniaxialStretch, NeoHookeanMatchesClosedForm) {
  const double stretch = 1.5;
  for (const char* el : {"Quad4", "Quad9"}) {
    BlockSpec spec;
    spec.element = el;
    spec.material = "Neo-Hookean";
    spec.lengthX = 2.0;
    spec.nx = 8;
    spec.distortion = 0.2;
    PL deck = blockDeck(spec, 10);
    addDisplacement(deck, "Left roller", "Block/left", "X");
    addDisplacement(deck, "Bottom roller", "Block/bottom", "Y");
    addDisplacement(deck, "Pull", "Block/right", "X").set("Value X", (stretch - 1.0) * spec.lengthX);
    ddc::Analysis a(worldComm(), deck);
    a.run("");
    const Lame L(spec.E, spec.nu);
    const double area = spec.lengthX * spec.lengthY;
    ASSERT_FALSE(a.history().empty());
    // Every converged step: energy W(diag(l1, l2)) * area.
    double worst = 0.0;
    for (const auto& rec : a.history()) {
      const double l1 = 1.0 + (stretch - 1.0) * rec.loadFactor;
      const double l2 = lateralStretch(L, l1);
      const double W = energyDensity("Neo-Hookean", L, Eigen::Vector2d(l1, l2).asDiagonal());
      worst = std::max(worst, relDiff(rec.strainEnergy, W * area));
      EXPECT_LE(relDiff(rec.strainEnergy, W * area), kHomogeneous) << el << " load factor " << rec.loadFactor;
    }
    EXPECT_NEAR(a.history().back().loadFactor, 1.0, 1e-14);
    // Final state: u = (diag(l1, l2) - I) X at every node, in particular the
    // top edge moves by (l2 - 1) H.
    const double l2 = lateralStretch(L, stretch);
    const auto u = gatherDisplacement(a);
    const ddc::Mesh& mesh = a.model().mesh();
    double uErr = 0.0, topErr = 0.0, topMean = 0.0;
    for (int n = 0; n < mesh.numNodes(); ++n)
      uErr = std::max({uErr, std::abs(u[2 * n] - (stretch - 1) * mesh.coord(n)[0]),
                       std::abs(u[2 * n + 1] - (l2 - 1) * mesh.coord(n)[1])});
    const auto& top = nodeSet(a, "Block/top");
    for (int n : top) {
      topErr = std::max(topErr, std::abs(u[2 * n + 1] - (l2 - 1) * spec.lengthY));
      topMean += u[2 * n + 1] / top.size();
    }
    const double scale = (stretch - 1) * spec.lengthX;
    EXPECT_LE(uErr, kHomogeneous * scale) << el;
    EXPECT_LE(topErr, kHomogeneous * std::abs(l2 - 1) * spec.lengthY) << el;
    const double W = energyDensity("Neo-Hookean", L, Eigen::Vector2d(stretch, l2).asDiagonal());
    if (isRoot())
      std::printf("[stretch] %-5s l1 = %.2f  l2 = %.12f  U_fe = %.12e  W*A = %.12e  worst rel. energy diff over steps = %.2e  "
                  "top u_y = %.12f (closed form %.12f)  max nodal error = %.2e\n",
                  el, stretch, l2, a.history().back().strainEnergy, W * area, worst, topMean,
                  (l2 - 1) * spec.lengthY, uErr);
  }
}

// ---------------------------------------------------------------------------
// 4. Cantilever vs Timoshenko.

struct CantileverResult {
  int nx, ny;
  double tip, energy, fu;
};

/// Plane-strain cantilever L x h clamped at x = 0 (u = 0 on the whole edge),
/// total shear load P as a uniform traction on x = L. Returns the deflection
/// -u_y of the mid-height node of the loaded end.
CantileverResult cantilever(const std::string& element, int nx, int ny, double E, double nu, double P) {
  BlockSpec spec;
  spec.element = element;
  spec.material = "Linear Elastic";
  spec.E = E;
  spec.nu = nu;
  spec.lengthX = 10.0;
  spec.lengthY = 1.0;
  spec.originY = -0.5;  // mid-height at y = 0
  spec.nx = nx;
  spec.ny = ny;
  PL deck = blockDeck(spec, 1);
  addDisplacement(deck, "Clamped", "Block/left", "XY");
  addTraction(deck, "Shear", "Block/right", 0.0, -P / spec.lengthY);
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  const auto u = gatherDisplacement(a);
  const ddc::Mesh& mesh = a.model().mesh();
  int mid = -1;
  for (int n : nodeSet(a, "Block/right"))
    if (std::abs(mesh.coord(n)[1]) < 1e-12) mid = n;
  EXPECT_GE(mid, 0) << "no mid-height node on the loaded end";
  const double fu = a.model().externalForce().dot(a.displacement()) * a.history().back().loadFactor;
  return {nx, ny, mid >= 0 ? -u[2 * mid + 1] : 0.0, a.history().back().strainEnergy, fu};
}

TEST(Cantilever, ConvergesToTimoshenkoBeamTheory) {
  const double E = 1000.0, nu = 0.3, P = 0.01, L = 10.0, h = 1.0;
  // Timoshenko beam, plane strain: bending with E' = E / (1 - nu^2), shear
  // with G and the rectangular-section correction kappa = 5/6.
  const double Ep = E / (1 - nu * nu), G = E / (2 * (1 + nu)), I = h * h * h / 12, A = h, kappa = 5.0 / 6.0;
  const double bending = P * L * L * L / (3 * Ep * I), shear = P * L / (kappa * G * A);
  const double reference = bending + shear;
  if (isRoot())
    std::printf("[cantilever] L = %g, h = %g, E = %g, nu = %g, P = %g: Timoshenko delta = %.8e "
                "(bending %.6e + shear %.6e)\n",
                L, h, E, nu, P, reference, bending, shear);

  // Meshes: each refinement halves h in both directions. Quad4 (full 2x2
  // Gauss) locks in bending, so it needs the finer meshes.
  //
  // What the finest meshes can reach: the exact plane-strain solution of this
  // 2-D problem is not Timoshenko's. Clamping the whole edge (u = 0, no
  // warping, no Poisson contraction at the root) makes it stiffer; Quad9 on
  // 10x1 ... 160x16 gives 3.63624e-2, 3.65162e-2, 3.65631e-2, 3.65789e-2,
  // 3.65846e-2 (increments shrinking by ~2.8 per refinement: the clamped
  // corners are singular), so the 2-D limit is ~3.6588e-2, 0.34% below
  // Timoshenko's 3.6712e-2 (about 40% of the shear term, 3.12e-4). The error
  // against Timoshenko therefore decreases monotonically towards ~0.34%, not
  // to 0, and the finite element value stays below the reference (a
  // displacement method is too stiff, and so is the clamp).
  //
  // Bounds on the finest mesh = 0.34% model difference + the measured
  // discretisation error, with ~25% margin on the total:
  //   Quad4 160x16: measured 0.607% -> bound 0.75%;
  //   Quad9  80x8:  measured 0.363% -> bound 0.45%.
  // A plane-stress modulus in place of E' (9%), a missing or doubled shear
  // term (0.85%) or a wrong traction integral (O(1)) exceed these bounds.
  struct Series {
    std::string element;
    std::vector<std::array<int, 2>> meshes;
    double finestBound;  ///< relative error allowed on the last mesh (see above)
  };
  const std::vector<Series> series = {{"Quad4", {{20, 2}, {40, 4}, {80, 8}, {160, 16}}, 0.0075},
                                      {"Quad9", {{10, 1}, {20, 2}, {40, 4}, {80, 8}}, 0.0045}};
  for (const auto& s : series) {
    const double previous =
        checkCantileverSeries("cantilever", s.element, static_cast<int>(s.meshes.size()), reference, [&](int i) {
          const auto& m = s.meshes[i];
          const auto r = cantilever(s.element, m[0], m[1], E, nu, P);
          char mesh[32];
          std::snprintf(mesh, sizeof mesh, "%4d x %-3d", m[0], m[1]);
          return CantileverRun{mesh, r.tip, r.energy, r.fu};
        });
    EXPECT_LE(previous, s.finestBound) << s.element << ": finest mesh too far from Timoshenko";
  }
}

// ---------------------------------------------------------------------------
// 5. Rank independence: world communicator vs MPI_COMM_SELF.

PL archDeck(int steps) {
  PL deck("DDContact");
  PL& body = deck.sublist("Mesh").sublist("Bodies").sublist("Arch");
  body.set("Generator", std::string("Annular Sector"));
  PL& g = body.sublist("Annular Sector");
  g.set("Inner Radius", 1.5);
  g.set("Outer Radius", 2.0);
  g.set("Start Angle", 0.0);
  g.set("End Angle", 180.0);
  g.set("Radial Elements", 2);
  g.set("Circumferential Elements", 32);
  setElement(body, "Quad4", "Neo-Hookean", 1000.0, 0.3);
  setRunOptions(deck, steps);
  addDisplacement(deck, "Clamped end", "Arch/start", "XY");
  addDisplacement(deck, "Pushed end", "Arch/end", "XY").set("Value X", 1.0);
  return deck;
}

TEST(RankIndependence, WorldAndSelfCommunicatorsAgree) {
  PL deckWorld = archDeck(5), deckSelf = archDeck(5);
  ddc::Analysis world(worldComm(), deckWorld);
  world.run("");
  ddc::Analysis self(selfComm(), deckSelf);
  self.run("");
  const auto& hw = world.history();
  const auto& hs = self.history();
  ASSERT_EQ(hw.size(), hs.size());
  double worstEnergy = 0.0;
  std::string iterations;
  for (size_t k = 0; k < hw.size(); ++k) {
    iterations += (k ? " " : "") + std::to_string(hw[k].newtonIterations) + "/" + std::to_string(hs[k].newtonIterations);
    EXPECT_EQ(hw[k].loadFactor, hs[k].loadFactor) << "step record " << k;
    EXPECT_EQ(hw[k].newtonIterations, hs[k].newtonIterations) << "step record " << k;
    EXPECT_LE(relDiff(hw[k].strainEnergy, hs[k].strainEnergy), ddc::test::kRankIndependence) << "step record " << k;
    worstEnergy = std::max(worstEnergy, relDiff(hw[k].strainEnergy, hs[k].strainEnergy));
  }
  // Displacement field: same mesh node numbering in both (the mesh is built
  // the same way); compare node by node and the norms.
  const auto uw = gatherDisplacement(world), us = gatherDisplacement(self);
  ASSERT_EQ(uw.size(), us.size());
  double scale = 0.0, diff = 0.0, nw = 0.0, ns = 0.0;
  for (size_t i = 0; i < uw.size(); ++i) {
    scale = std::max(scale, std::abs(us[i]));
    diff = std::max(diff, std::abs(uw[i] - us[i]));
    nw += uw[i] * uw[i];
    ns += us[i] * us[i];
  }
  EXPECT_LE(diff, ddc::test::kRankIndependence * scale);
  EXPECT_LE(relDiff(std::sqrt(nw), std::sqrt(ns)), ddc::test::kRankIndependence);
  // The distributed norm of the world run agrees with the gathered one.
  EXPECT_LE(relDiff(world.displacement().norm2(), std::sqrt(nw)), ddc::test::kRoundoff);
  // Also check the run actually deformed the arch.
  EXPECT_GT(scale, 0.5);
  if (isRoot())
    std::printf("[ranks] %d rank(s) vs MPI_COMM_SELF: %zu steps, worst rel. energy diff = %.2e, "
                "max |u_world - u_self| / max|u| = %.2e, Newton iterations world/self per step: %s\n",
                worldComm()->getSize(), hw.size(), worstEnergy, diff / scale, iterations.c_str());
}

// ---------------------------------------------------------------------------
// 6. Linear elasticity energy identity.

TEST(EnergyIdentity, LinearElasticityUnderTraction) {
  for (const char* el : {"Quad4", "Quad9"}) {
    BlockSpec spec;
    spec.element = el;
    spec.material = "Linear Elastic";
    spec.lengthX = 4.0;
    spec.nx = 16;
    spec.ny = 4;
    spec.distortion = 0.2;
    PL deck = blockDeck(spec, 2);
    addDisplacement(deck, "Clamped", "Block/left", "XY");
    addTraction(deck, "Load", "Block/right", 10.0, -1.0);
    addTraction(deck, "Top load", "Block/top", 0.0, -0.5);
    ddc::Analysis a(worldComm(), deck);
    a.run("");
    const double lambda = a.history().back().loadFactor;
    const double fu = lambda * a.model().externalForce().dot(a.displacement());
    const double U = a.history().back().strainEnergy;
    EXPECT_GT(U, 0.0);
    EXPECT_LE(relDiff(U, 0.5 * fu), kEnergyIdentity) << el;
    // Linear: the energy after step 1 (load factor 1/2) is a quarter of the final one.
    ASSERT_EQ(a.history().size(), 2u);
    EXPECT_LE(relDiff(a.history()[0].strainEnergy, 0.25 * U), kEnergyIdentity) << el;
    if (isRoot())
      std::printf("[energy identity] %-5s U = %.12e  1/2 f.u = %.12e  rel. diff = %.2e\n", el, U, 0.5 * fu,
                  relDiff(U, 0.5 * fu));
  }
}

}  // namespace
