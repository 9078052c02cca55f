// 3-D continuum analysis (doc/verification.md "3-D analysis"):
//   1. tractions on faces: the nodal forces of a uniform traction on a face
//      set sum to traction x area, for every 3-D cell type (the facet's
//      quadrature rule, facetQuadratureRule()); a traction's Load Curve
//      scales them;
//   2. a cantilever of Hex20, Hex27 and Tet10 converges to Timoshenko beam
//      theory under mesh refinement (within 1% on the finest mesh);
//   3. a body held at two nodes only, or by prescribed displacements that
//      leave a rigid motion free, is refused with a message naming it.
// Decks are in-memory Teuchos::ParameterLists; the run uses the world
// communicator (1 and 2 ranks). The measured numbers are printed on rank 0
// for doc/verification.md.
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_AnalysisTestDecks.hpp"
#include "DDC_Error.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using PL = Teuchos::ParameterList;
using ddc::test::relDiff;
using namespace ddc::test;  // deck builders, communicators (DDC_AnalysisTestDecks.hpp)

const std::vector<std::string> kSolidTypes = {"Hex8", "Hex20", "Hex27", "Tet4", "Tet10"};

// ---------------------------------------------------------------------------
// 1. Tractions on faces.

/// Sum of the nodal forces of a uniform traction: exact up to round-off for
/// any facet rule (the shape functions of a facet sum to 1 and the faces are
/// flat, so sum_a f_a = t |face|); a wrong facet rule, Jacobian or node
/// order gives an O(1) error.
constexpr double kTractionResultant = 1e-13;

TEST(Solid3d, TractionOnAFaceSumsToTractionTimesArea) {
  for (const auto& type : kSolidTypes) {
    PL deck("DDContact");
    BoxSpec box;
    box.element = type;
    box.length[0] = 1.5, box.length[1] = 2.0, box.length[2] = 3.0;
    box.elements[0] = 2, box.elements[1] = 3, box.elements[2] = 2;
    addBox(deck, "Block", box);
    setRunOptions(deck, 1);
    addDisplacement(deck, "Clamped", "Block/left", "All");
    const std::array<double, 3> t = {0.7, -1.3, 2.1};
    addTraction3(deck, "Load", "Block/right", t);  // the face x = 1.5, area 2 x 3
    ddc::Analysis a(worldComm(), deck);
    const ddc::Model& m = a.model();
    ASSERT_EQ(m.dim(), 3);
    const auto f = gatherDisplacement(m, m.externalForce());  // any owned vector gathers alike
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0;
      for (int n = 0; n < m.mesh().numNodes(); ++n) sum += f[3 * n + c];
      EXPECT_LE(std::abs(sum - 6.0 * t[c]), kTractionResultant * 6.0 * std::abs(t[c]))
          << type << ": component " << c << " of the traction resultant is " << sum;
    }
  }
}

/// A Hex8 block 1.5 x 2 x 3 held on its left face, the traction `t` on its
/// right face (area 6) with `curve` as its Load Curve (empty: none), two
/// load steps.
PL tractionBlock(const std::array<double, 3>& t, const std::string& curve) {
  PL deck("DDContact");
  BoxSpec box;
  box.length[0] = 1.5, box.length[1] = 2.0, box.length[2] = 3.0;
  box.elements[0] = 2, box.elements[1] = 3, box.elements[2] = 2;
  addBox(deck, "Block", box);
  setRunOptions(deck, 2);
  addDisplacement(deck, "Clamped", "Block/left", "All");
  addTraction3(deck, "Load", "Block/right", t);
  if (!curve.empty()) deck.sublist("Boundary Conditions").sublist("Load").set("Load Curve", curve);
  return deck;
}

// A traction with the Load Curve '0 0, 0.5 0, 1 1' (a push after a press:
// examples/cattaneo_2d.xml) has no force up to load factor 0.5 and its whole
// force at 1 (the resultant s(λ) t |face|, as above), and the run's
// residual takes it so: no strain energy in step 1 (λ = 0.5), the energy of
// the plain traction's run at λ = 1 in step 2.
TEST(Solid3d, TractionWithALoadCurveStartsWhereTheCurveRises) {
  const std::array<double, 3> t = {0.7, -1.3, 2.1};
  PL curved = tractionBlock(t, "0 0, 0.5 0, 1 1"), straight = tractionBlock(t, "");
  ddc::Analysis a(worldComm(), curved);
  const ddc::Model& m = a.model();
  auto f = m.createVector();
  for (const auto& [lambda, s] : std::vector<std::array<double, 2>>{{0.25, 0.0}, {0.5, 0.0}, {0.75, 0.5}, {1.0, 1.0}}) {
    m.externalForceAt(lambda, *f);
    const auto g = gatherDisplacement(m, *f);
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0;
      for (int n = 0; n < m.mesh().numNodes(); ++n) sum += g[3 * n + c];
      EXPECT_LE(std::abs(sum - s * 6.0 * t[c]), kTractionResultant * 6.0 * std::abs(t[c]))
          << "load factor " << lambda << ": component " << c << " of the resultant is " << sum;
    }
  }
  a.run("");
  ddc::Analysis plain(worldComm(), straight);
  plain.run("");
  ASSERT_EQ(a.history().size(), 2u);
  ASSERT_EQ(plain.history().size(), 2u);
  EXPECT_EQ(a.history()[0].loadFactor, 0.5);
  EXPECT_EQ(a.history()[0].strainEnergy, 0.0);
  EXPECT_GT(plain.history()[0].strainEnergy, 0.0);
  EXPECT_LE(relDiff(a.history()[1].strainEnergy, plain.history()[1].strainEnergy), kEnergyIdentity);
}

// ---------------------------------------------------------------------------
// 2. Cantilever vs Timoshenko.

struct Cantilever3dResult {
  double tip, energy, fu;
  int dofs;
};

/// Cantilever L x h x h (x from 0 to L, section centred on the x axis),
/// clamped at x = 0 (u = 0 on the whole face), total shear load P along -y
/// as a uniform traction on x = L. Returns -u_y of the node at the centre of
/// the loaded face.
Cantilever3dResult cantilever(const std::string& element, int nx, int ny, double E, double nu, double P) {
  PL deck("DDContact");
  BoxSpec box;
  box.element = element;
  box.E = E;
  box.nu = nu;
  box.length[0] = 10.0;
  box.origin[1] = box.origin[2] = -0.5;
  box.elements[0] = nx;
  box.elements[1] = box.elements[2] = ny;
  addBox(deck, "Beam", box);
  setRunOptions(deck, 1);
  addDisplacement(deck, "Clamped", "Beam/left", "All");
  addTraction3(deck, "Shear", "Beam/right", {0.0, -P, 0.0});  // face area 1
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  const auto u = gatherDisplacement(a);
  const ddc::Mesh& mesh = a.model().mesh();
  int centre = -1;
  for (int n : mesh.nodeSet("Beam/right"))
    if (std::abs(mesh.coord(n)[1]) < 1e-12 && std::abs(mesh.coord(n)[2]) < 1e-12) centre = n;
  EXPECT_GE(centre, 0) << "no node at the centre of the loaded face";
  const double fu = a.model().externalForce().dot(a.displacement()) * a.history().back().loadFactor;
  return {centre >= 0 ? -u[3 * centre + 1] : 0.0, a.history().back().strainEnergy, fu,
          3 * mesh.numNodes()};
}

TEST(Solid3d, CantileverConvergesToTimoshenkoBeamTheory) {
  const double E = 1000.0, P = 0.01, L = 10.0, h = 1.0;
  // What the finest meshes can reach: clamping the whole root face (u = 0)
  // also stops the Poisson contraction there, which beam theory ignores;
  // with nu = 0.3 the 3-D solution is about 0.7% stiffer than Timoshenko's
  // beam (Hex20 / Hex27 / Tet10 on 10x2x2, 20x2x2, 40x4x4 measured 1.50 /
  // 1.29 / 1.72%, 1.04 / 0.91 / 1.10%, 0.795 / 0.746 / 0.796%, increments
  // shrinking towards that offset). With nu = 0 the clamp costs nothing and
  // the same meshes come to 3.4e-4 / 3.2e-4 / 6.7e-4, 1.3e-4 / 1.3e-4 /
  // 1.8e-4, 4.9e-5 / 4.8e-5 / 5.3e-5 of the beam. Bounds on the finest mesh:
  //   nu = 0.3: the 1% acceptance bound of doc/verification.md (measured <= 0.80%);
  //   nu = 0:   2e-4 (measured <= 5.3e-5): a missing shear term (0.6%), a
  //             plane-strain modulus (10%) or a wrong face integral (O(1))
  //             exceed it.
  struct Case {
    double nu, finestBound;
  };
  struct Series {
    std::string element;
    std::vector<std::array<int, 2>> meshes;  ///< elements along x, and along y and z
  };
  const std::vector<Series> series = {{"Hex20", {{10, 2}, {20, 2}, {40, 4}}},
                                      {"Hex27", {{10, 2}, {20, 2}, {40, 4}}},
                                      {"Tet10", {{10, 2}, {20, 2}, {40, 4}}}};
  for (const Case& c : {Case{0.0, 2e-4}, Case{0.3, 0.01}}) {
    // Timoshenko beam: bending E I, shear kappa G A with Cowper's factor of
    // a rectangular section, kappa = 10 (1 + nu) / (12 + 11 nu).
    const double nu = c.nu, G = E / (2 * (1 + nu)), I = h * h * h * h / 12, A = h * h;
    const double kappa = 10 * (1 + nu) / (12 + 11 * nu);
    const double bending = P * L * L * L / (3 * E * I), shear = P * L / (kappa * G * A);
    const double reference = bending + shear;
    if (isRoot())
      std::printf("[cantilever 3-D] L = %g, h = b = %g, E = %g, nu = %g, P = %g: Timoshenko delta = %.8e "
                  "(bending %.6e + shear %.6e)\n",
                  L, h, E, nu, P, reference, bending, shear);
    for (const auto& s : series) {
      char label[32];
      std::snprintf(label, sizeof label, "cantilever 3-D, nu = %.1f", nu);
      const double previous =
          checkCantileverSeries(label, s.element, static_cast<int>(s.meshes.size()), reference, [&](int i) {
            const auto& m = s.meshes[i];
            const auto r = cantilever(s.element, m[0], m[1], E, nu, P);
            char mesh[48];
            std::snprintf(mesh, sizeof mesh, "%3d x %d x %d (%6d DOFs)", m[0], m[1], m[1], r.dofs);
            return CantileverRun{mesh, r.tip, r.energy, r.fu};
          });
      EXPECT_LE(previous, c.finestBound) << s.element << ", nu = " << nu << ": finest mesh too far from Timoshenko";
    }
  }
}

// ---------------------------------------------------------------------------
// 3. Supports in 3-D.

std::string supportErrorOf(const std::vector<std::pair<std::string, std::string>>& conditions) {
  PL deck("DDContact");
  addBox(deck, "Block", BoxSpec{});
  setRunOptions(deck, 1);
  int i = 0;
  for (const auto& [set, components] : conditions) addDisplacement(deck, "Support " + std::to_string(i++), set, components);
  return inputErrorOf([&] { ddc::Analysis a(worldComm(), deck); });
}

TEST(Solid3d, ABodyNeedsSupportsAgainstAllSixRigidMotions) {
  // The left face (9 nodes, all components): supported.
  EXPECT_EQ(supportErrorOf({{"Block/left", "All"}}), kNoInputError);
  // x and y only: the body can translate along z.
  EXPECT_NE(supportErrorOf({{"Block/left", "XY"}}).find("act in x, y and z"), std::string::npos)
      << supportErrorOf({{"Block/left", "XY"}});
}

}  // namespace
