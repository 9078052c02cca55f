// FETI-DP solver (doc/feti-dp.md; rung 3 of doc/verification.md): synthetic
// structured-grid problems (scalar Laplacian and plane-stress elasticity
// with bilinear quads), split into Sx x Sy subdomains with the left edge
// fixed (eliminated), primal DOFs at the cross points and at the ends of
// every subdomain-subdomain interface on the domain boundary. FETI-DP must
// reproduce a direct MUMPS solve of the globally assembled matrix, B must
// annihilate continuous fields, the dual iteration counts must stay bounded
// as subdomains are added at fixed H/h, and bad input / singular subdomains
// must raise the documented errors on every rank.
#include <gtest/gtest.h>
#include <mpi.h>

#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_Core.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>

#include "DDC_DirectSolver.hpp"
#include "DDC_Error.hpp"
#include "DDC_FetiDpSolver.hpp"
#include "DDC_FetiEdgeFaceConstraints.hpp"
#include "DDC_FetiPrimalVertices.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_FetiTolerances.hpp"
#include "DDC_TestErrors.hpp"
#include "DDC_TestTolerances.hpp"


namespace {

using ddc::CrsMatrix;
using ddc::FetiDpSolver;
using ddc::FetiSubdomain;
using ddc::GO;
using ddc::LO;
using ddc::Map;
using ddc::MultiVector;
using ddc::Vector;
using Teuchos::RCP;
using Teuchos::rcp;
using Comm = Teuchos::Comm<int>;

RCP<const Comm> worldComm() { return Tpetra::getDefaultComm(); }
RCP<const Comm> selfComm() { return rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF)); }
int worldRank() { return worldComm()->getRank(); }
int worldSize() { return worldComm()->getSize(); }

using ddc::test::expectThrowWith;

// ---- element matrices ------------------------------------------------------

/// Bilinear element stiffness for the Laplacian on a square (independent of
/// its size in 2-D); nodes (0,0), (1,0), (1,1), (0,1).
std::vector<double> laplaceQ4() {
  const double k[4][4] = {{4, -1, -2, -1}, {-1, 4, -1, -2}, {-2, -1, 4, -1}, {-1, -2, -1, 4}};
  std::vector<double> K(16);
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) K[a * 4 + b] = k[a][b] / 6.0;
  return K;
}

/// Plane-stress bilinear quad on the unit square (E = 1, nu = 0.3), 2x2
/// Gauss; DOF 2 k + c = component c of node k.
std::vector<double> elasticityQ4(double nu = 0.3) {
  const double xi[4] = {-1, 1, 1, -1}, eta[4] = {-1, -1, 1, 1};
  const double f = 1.0 / (1.0 - nu * nu);
  const double D[3][3] = {{f, f * nu, 0}, {f * nu, f, 0}, {0, 0, f * (1 - nu) / 2}};
  std::vector<double> K(64, 0.0);
  const double g = 1.0 / std::sqrt(3.0);
  for (double gx : {-g, g})
    for (double gy : {-g, g}) {
      double B[3][8] = {};
      for (int k = 0; k < 4; ++k) {
        // unit square: x = (xi + 1) / 2, so d/dx = 2 d/dxi
        const double dx = 2.0 * 0.25 * xi[k] * (1 + gy * eta[k]);
        const double dy = 2.0 * 0.25 * eta[k] * (1 + gx * xi[k]);
        B[0][2 * k] = dx;
        B[1][2 * k + 1] = dy;
        B[2][2 * k] = dy;
        B[2][2 * k + 1] = dx;
      }
      const double detJ = 0.25;
      for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b) {
          double s = 0;
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) s += B[i][a] * D[i][j] * B[j][b];
          K[a * 8 + b] += s * detJ;
        }
    }
  return K;
}

// ---- the synthetic problem ---------------------------------------------------

struct Spec {
  int Sx = 2, Sy = 2;   ///< subdomains in x and y
  int H = 4;            ///< elements per subdomain edge (H/h)
  int dpn = 1;          ///< DOFs per node: 1 Laplacian, 2 elasticity
  bool primal = true;   ///< corner rule on; false: no primal DOFs at all
  /// Further filter on the corner rule's primal nodes (i, j).
  std::function<bool(int, int)> keepPrimal = [](int, int) { return true; };
  bool blockwise = false;  ///< subdomains to ranks blockwise instead of round-robin
  bool extraDof = false;   ///< owned map has one more DOF, in no subdomain
  std::function<double(int, int)> coef = [](int, int) { return 1.0; };  ///< per subdomain (a, b)
};

/// Structured grid of (Sx H) x (Sy H) unit squares, nodes (i, j); the nodes
/// with i = 0 are fixed and eliminated; free DOF (i, j, c) has the global id
/// ((j nx + i - 1) dpn + c).
class Problem {
 public:
  explicit Problem(const Spec& s) : s_(s), nx_(s.Sx * s.H), ny_(s.Sy * s.H) {
    Ke_ = s.dpn == 1 ? laplaceQ4() : elasticityQ4();
    const GO n = GO(ny_ + 1) * nx_ * s.dpn + (s.extraDof ? 1 : 0);
    ownedMap_ = rcp(new Map(n, 0, worldComm()));
  }

  RCP<const Map> ownedMap() const { return ownedMap_; }
  int numSubdomains() const { return s_.Sx * s_.Sy; }
  int rankOf(int id) const {
    const int P = worldSize(), S = numSubdomains();
    return s_.blockwise ? int(GO(id) * P / S) : id % P;
  }

  GO dof(int i, int j, int c) const { return (GO(j) * nx_ + (i - 1)) * s_.dpn + c; }
  /// Subdomains containing node (i, j).
  int nodeCount(int i, int j) const {
    auto count = [&](int i0, int S) {
      int c = 0;
      for (int a = 0; a < S; ++a) c += (a * s_.H <= i0 && i0 <= (a + 1) * s_.H) ? 1 : 0;
      return c;
    };
    return count(i, s_.Sx) * count(j, s_.Sy);
  }
  /// Corner rule: subdomain corners shared by >= 2 subdomains (cross points
  /// and ends of interfaces on the domain boundary).
  bool isPrimalNode(int i, int j) const {
    return s_.primal && i % s_.H == 0 && j % s_.H == 0 && nodeCount(i, j) >= 2 && s_.keepPrimal(i, j);
  }

  /// The subdomains of this rank.
  std::vector<FetiSubdomain> subdomains() const {
    std::vector<FetiSubdomain> out;
    for (int b = 0; b < s_.Sy; ++b)
      for (int a = 0; a < s_.Sx; ++a) {
        const int id = a + s_.Sx * b;
        if (rankOf(id) != worldRank()) continue;
        FetiSubdomain sd;
        sd.id = id;
        sd.dim = 2;
        std::map<GO, LO> local;
        for (int j = b * s_.H; j <= (b + 1) * s_.H; ++j)
          for (int i = a * s_.H; i <= (a + 1) * s_.H; ++i) {
            if (i == 0) continue;
            for (int c = 0; c < s_.dpn; ++c) {
              local[dof(i, j, c)] = LO(sd.dofs.size());
              sd.dofs.push_back(dof(i, j, c));
              sd.primal.push_back(isPrimalNode(i, j) ? 1 : 0);
              sd.component.push_back(c);
              sd.coordinates.push_back(double(i));
              sd.coordinates.push_back(double(j));
            }
          }
        const LO n = LO(sd.dofs.size());
        std::vector<std::map<LO, double>> rows(n);
        for (int ej = b * s_.H; ej < (b + 1) * s_.H; ++ej)
          for (int ei = a * s_.H; ei < (a + 1) * s_.H; ++ei)
            addElement(ei, ej, s_.coef(a, b), [&](GO r, GO c, double v) { rows[local.at(r)][local.at(c)] += v; });
        auto map = rcp(new Map(n, 0, selfComm()));
        auto K = rcp(new CrsMatrix(map, 18));
        for (LO r = 0; r < n; ++r) {
          std::vector<GO> cols;
          std::vector<double> vals;
          for (auto& [c, v] : rows[r]) cols.push_back(c), vals.push_back(v);
          K->insertGlobalValues(r, Teuchos::ArrayView<const GO>(cols), Teuchos::ArrayView<const double>(vals));
        }
        K->fillComplete();
        sd.K = K;
        out.push_back(std::move(sd));
      }
    return out;
  }

  /// The globally assembled stiffness (rows of this rank), independent of
  /// the subdomain code: loops over all elements.
  RCP<CrsMatrix> globalK() const {
    std::map<GO, std::map<GO, double>> rows;
    for (int ej = 0; ej < ny_; ++ej)
      for (int ei = 0; ei < nx_; ++ei)
        addElement(ei, ej, s_.coef(ei / s_.H, ej / s_.H), [&](GO r, GO c, double v) {
          if (ownedMap_->isNodeGlobalElement(r)) rows[r][c] += v;
        });
    auto K = rcp(new CrsMatrix(ownedMap_, 18));
    for (auto& [r, row] : rows) {
      std::vector<GO> cols;
      std::vector<double> vals;
      for (auto& [c, v] : row) cols.push_back(c), vals.push_back(v);
      K->insertGlobalValues(r, Teuchos::ArrayView<const GO>(cols), Teuchos::ArrayView<const double>(vals));
    }
    if (s_.extraDof) {  // keep the reference matrix nonsingular
      const GO last = GO(ownedMap_->getGlobalNumElements()) - 1;
      if (ownedMap_->isNodeGlobalElement(last)) {
        const double one = 1.0;
        K->insertGlobalValues(last, 1, &one, &last);
      }
    }
    K->fillComplete();
    return K;
  }

  /// A deterministic, rank-independent load (0 on the extra DOF).
  RCP<Vector> load() const {
    auto b = rcp(new Vector(ownedMap_));
    auto v = b->getDataNonConst();
    const GO nFree = GO(ny_ + 1) * nx_ * s_.dpn;
    for (LO l = 0; l < LO(v.size()); ++l) {
      const GO g = ownedMap_->getGlobalElement(l);
      v[l] = g < nFree ? std::sin(0.37 * double(g) + 0.1) + 0.5 : 0.0;
    }
    return b;
  }

 private:
  template <class Add>
  void addElement(int ei, int ej, double coef, Add add) const {
    const int ni[4] = {ei, ei + 1, ei + 1, ei}, nj[4] = {ej, ej, ej + 1, ej + 1};
    const int d = s_.dpn, ne = 4 * d;
    for (int ka = 0; ka < 4; ++ka)
      for (int ca = 0; ca < d; ++ca) {
        if (ni[ka] == 0) continue;
        for (int kb = 0; kb < 4; ++kb)
          for (int cb = 0; cb < d; ++cb) {
            if (ni[kb] == 0) continue;
            add(dof(ni[ka], nj[ka], ca), dof(ni[kb], nj[kb], cb), coef * Ke_[(ka * d + ca) * ne + kb * d + cb]);
          }
      }
  }

  Spec s_;
  int nx_, ny_;
  std::vector<double> Ke_;
  RCP<const Map> ownedMap_;
};

/// The tests written for vertex (corner) primal DOFs keep "Vertices"; the
/// edge-average tests pass their choice.
Teuchos::ParameterList fetiParams(const std::string& prec = "Dirichlet", const std::string& scaling = "Multiplicity",
                                  const std::string& solver = "CG", double tol = ddc::test::kTightBelos,
                                  const std::string& primal = "Vertices") {
  Teuchos::ParameterList p("FETI-DP");
  p.set("Primal Constraints", primal);
  p.set("Preconditioner", prec);
  p.set("Scaling", scaling);
  p.sublist("Belos").set("Solver Type", solver);
  p.sublist("Belos").set("Convergence Tolerance", tol);
  return p;
}

/// u from a direct MUMPS solve of the assembled matrix on the world comm.
RCP<Vector> directSolve(const Problem& pb, const Vector& b) {
  auto K = pb.globalK();
  Teuchos::ParameterList p;
  p.set("Type", std::string("MUMPS"));
  auto solver = ddc::DirectSolverFactory::withBuiltins().create(p, "Reference");
  solver->symbolic(K);
  solver->numeric();
  auto u = rcp(new Vector(pb.ownedMap()));
  solver->solve(b, *u);
  // check the reference by its residual (doc/trilinos-notes.md: check every direct solve)
  Vector r(pb.ownedMap());
  K->apply(*u, r);
  r.update(1.0, b, -1.0);
  EXPECT_LT(r.norm2() / b.norm2(), 1e-10) << "reference direct solve";
  return u;
}

double relDiff(const Vector& a, const Vector& b) {
  Vector d(a, Teuchos::Copy);
  d.update(-1.0, b, 1.0);
  return d.norm2() / b.norm2();
}

struct FetiRun {
  FetiDpSolver::Info info;
  double error = -1.0;  ///< vs direct (if computed)
};

/// Set up, factorise and solve one problem; compare with the direct solve.
/// `beforeTopology` (if any) sees the solver between its construction and
/// setTopology().
FetiRun runFeti(const Spec& spec, Teuchos::ParameterList params, bool compare = true,
                const std::function<void(FetiDpSolver&)>& beforeTopology = {}) {
  Problem pb(spec);
  FetiDpSolver feti(worldComm(), params, "FETI-DP");
  if (beforeTopology) beforeTopology(feti);
  feti.setTopology(pb.subdomains(), pb.ownedMap());
  feti.numeric();
  auto b = pb.load();
  Vector u(pb.ownedMap());
  FetiRun run;
  run.info = feti.solve(*b, u);
  if (compare) run.error = relDiff(u, *directSolve(pb, *b));
  return run;
}

void report(const std::string& what, const FetiRun& r) {
  if (worldRank() == 0)
    std::printf("[ feti-dp  ] %-52s it %3d  res %.2e  err vs direct %.2e\n", what.c_str(), r.info.iterations,
                r.info.relativeResidual, r.error);
}

// ---- accuracy against the direct solve -------------------------------------

struct Layout {
  int Sx, Sy, dpn;
  bool blockwise;
};

class FetiDpAccuracy : public ::testing::TestWithParam<Layout> {};

TEST_P(FetiDpAccuracy, MatchesDirectSolve) {
  const Layout L = GetParam();
  Spec s;
  s.Sx = L.Sx, s.Sy = L.Sy, s.dpn = L.dpn, s.H = 4, s.blockwise = L.blockwise;
  const FetiRun r = runFeti(s, fetiParams());
  char name[96];
  std::snprintf(name, sizeof name, "%s %dx%d H/h=4 %s", L.dpn == 1 ? "Laplace" : "elasticity", L.Sx, L.Sy,
                L.blockwise ? "blockwise" : "round-robin");
  report(name, r);
  EXPECT_LT(r.error, ddc::test::kFetiVsDirect);
  EXPECT_LE(r.info.relativeResidual, ddc::test::kTightBelos);
  if (L.Sx * L.Sy == 1) EXPECT_EQ(r.info.iterations, 0);  // no interface
}

/// The same layouts with edge constraints (doc/feti-dp.md "Primal
/// constraints"): averages only, and averages with the edge rotations.
TEST_P(FetiDpAccuracy, MatchesDirectSolveWithEdgeConstraints) {
  const Layout L = GetParam();
  Spec s;
  s.Sx = L.Sx, s.Sy = L.Sy, s.dpn = L.dpn, s.H = 4, s.blockwise = L.blockwise;
  for (bool rotations : {false, true}) {
    auto p = fetiParams("Dirichlet", "Multiplicity", "CG", ddc::test::kTightBelos, "Vertices and Edges");
    p.set("Rotational Constraints", rotations);
    const FetiRun r = runFeti(s, p);
    char name[128];
    std::snprintf(name, sizeof name, "%s %dx%d H/h=4 %s edges%s", L.dpn == 1 ? "Laplace" : "elasticity", L.Sx, L.Sy,
                  L.blockwise ? "blockwise" : "round-robin", rotations ? " + rotations" : "");
    report(name, r);
    EXPECT_LT(r.error, ddc::test::kFetiVsDirect) << name;
    EXPECT_LE(r.info.relativeResidual, ddc::test::kTightBelos) << name;
  }
}

/// The explicit Phi^s = K_rr^{-1} K_rPi path ("Local Schur Complement" =
/// false; what local solvers without a Schur capability use) against the
/// direct solve and against MUMPS' Schur complement path: the same
/// iteration count (F and M^{-1} are the same operators), solutions within
/// the FETI-vs-direct tolerance.
TEST_P(FetiDpAccuracy, ExplicitPhiMatchesSchurComplement) {
  const Layout L = GetParam();
  Spec s;
  s.Sx = L.Sx, s.Sy = L.Sy, s.dpn = L.dpn, s.H = 4, s.blockwise = L.blockwise;
  for (const char* primal : {"Vertices", "Vertices and Edges"}) {
    auto p = fetiParams("Dirichlet", "Multiplicity", "CG", ddc::test::kTightBelos, primal);
    const FetiRun schur = runFeti(s, p);
    p.set("Local Schur Complement", false);
    const FetiRun phi = runFeti(s, p);
    report(std::string("explicit Phi, ") + primal, phi);
    EXPECT_LT(phi.error, ddc::test::kFetiVsDirect) << primal;
    EXPECT_LT(schur.error, ddc::test::kFetiVsDirect) << primal;
    EXPECT_LE(std::abs(phi.info.iterations - schur.info.iterations), 1) << primal;
  }
}

// 1x1: no interface, no LM (must work); 2x1, 3x3, 4x4 contain floating
// subdomains (a > 0: not touching the fixed left edge); 3x3 and 4x4 put
// several subdomains on each rank.
INSTANTIATE_TEST_SUITE_P(Layouts, FetiDpAccuracy,
                         ::testing::Values(Layout{1, 1, 1, false}, Layout{2, 1, 1, false}, Layout{1, 2, 1, false},
                                           Layout{2, 2, 1, false}, Layout{3, 3, 1, false}, Layout{4, 4, 1, true},
                                           Layout{1, 1, 2, false}, Layout{2, 1, 2, false}, Layout{2, 2, 2, false},
                                           Layout{3, 3, 2, false}, Layout{3, 3, 2, true}, Layout{4, 4, 2, false},
                                           Layout{4, 4, 2, true}),
                         [](const ::testing::TestParamInfo<Layout>& i) {
                           const Layout& L = i.param;
                           return std::string(L.dpn == 1 ? "Laplace" : "Elasticity") + std::to_string(L.Sx) + "x" +
                                  std::to_string(L.Sy) + (L.blockwise ? "Blockwise" : "RoundRobin");
                         });

/// CHOLMOD as the local solver (K_rr^s and K_II^s: SPD here; no Schur
/// capability, so the explicit Phi path): the same answer and iteration
/// count as MUMPS, with vertices and with edge constraints.
TEST(FetiDp, CholmodLocalSolverMatchesMumps) {
  for (const Layout L : {Layout{3, 3, 2, false}, Layout{4, 4, 1, true}}) {
    Spec s;
    s.Sx = L.Sx, s.Sy = L.Sy, s.dpn = L.dpn, s.H = 4, s.blockwise = L.blockwise;
    for (const char* primal : {"Vertices", "Vertices and Edges"}) {
      auto p = fetiParams("Dirichlet", "Multiplicity", "CG", ddc::test::kTightBelos, primal);
      const FetiRun mumps = runFeti(s, p);
      p.sublist("Local Solver").set("Type", std::string("CHOLMOD"));
      const FetiRun cholmod = runFeti(s, p);
      char name[96];
      std::snprintf(name, sizeof name, "CHOLMOD local, %s %dx%d, %s", L.dpn == 1 ? "Laplace" : "elasticity", L.Sx,
                    L.Sy, primal);
      report(name, cholmod);
      EXPECT_LT(cholmod.error, ddc::test::kFetiVsDirect) << name;
      EXPECT_LE(cholmod.info.relativeResidual, ddc::test::kTightBelos) << name;
      EXPECT_LE(std::abs(cholmod.info.iterations - mumps.info.iterations), 1) << name;
    }
  }
}

TEST(FetiDp, OtherKrylovSolversConverge) {
  Spec s;
  s.Sx = 3, s.Sy = 3, s.dpn = 2, s.H = 4;
  for (const std::string solver : {"GMRES", "MINRES"})
    for (const std::string prec : {"Dirichlet", "None"}) {
      const FetiRun r = runFeti(s, fetiParams(prec, "Multiplicity", solver));
      report("elasticity 3x3 " + solver + " / " + prec, r);
      EXPECT_LT(r.error, ddc::test::kFetiVsDirect) << solver << " " << prec;
    }
}

TEST(FetiDp, LumpedAndStiffnessScalingMatchDirect) {
  Spec s;
  s.Sx = 3, s.Sy = 2, s.dpn = 2, s.H = 4;
  s.coef = [](int a, int b) { return (a + b) % 2 ? 1000.0 : 1.0; };  // checkerboard
  for (const std::string prec : {"Dirichlet", "Lumped"})
    for (const std::string scaling : {"Multiplicity", "Stiffness"}) {
      const FetiRun r = runFeti(s, fetiParams(prec, scaling));
      report("elasticity 3x2 checkerboard " + prec + " / " + scaling, r);
      EXPECT_LT(r.error, ddc::test::kFetiVsDirect) << prec << " " << scaling;
    }
}

// ---- structure: maps, B, F --------------------------------------------------

TEST(FetiDp, MapsAndConstraintCounts) {
  // 2x2 Laplacian, H = 4: primal nodes (H,0), (H,H), (H,2H), (2H,H); dual
  // nodes: the vertical interface i = H minus its 3 primal nodes (2H - 2)
  // and the horizontal one j = H minus (0,H) (fixed), (H,H), (2H,H): 2H - 2.
  Spec s;
  s.Sx = 2, s.Sy = 2, s.H = 4;
  Problem pb(s);
  auto params = fetiParams();
  FetiDpSolver feti(worldComm(), params, "FETI-DP");
  feti.setTopology(pb.subdomains(), pb.ownedMap());
  EXPECT_EQ(feti.primalMap()->getGlobalNumElements(), 4u);
  EXPECT_EQ(feti.numDualDofs(), GO(4 * s.H - 4));
  EXPECT_EQ(feti.lmMap()->getGlobalNumElements(), size_t(4 * s.H - 4));  // m = 2 everywhere
  for (GO g : feti.primalMap()->getNodeElementList()) EXPECT_TRUE(pb.ownedMap()->isNodeGlobalElement(g));
}

TEST(FetiDp, RedundantMultipliersAtANonPrimalCrossPoint) {
  // 2x2 with the cross point (H, H) not primal: the floating subdomains
  // still get 2 primal nodes each (interface ends on the boundary), and the
  // cross point is a dual DOF shared by 4 subdomains with 4*3/2 = 6
  // redundant multipliers per DOF. F is then only semidefinite (dependent
  // rows of B), d is in its range, and CG must still converge.
  for (int dpn : {1, 2}) {
    Spec s;
    s.Sx = 2, s.Sy = 2, s.H = 4, s.dpn = dpn;
    s.keepPrimal = [&](int i, int j) { return !(i == s.H && j == s.H); };
    Problem pb(s);
    {
      auto params = fetiParams();
      FetiDpSolver feti(worldComm(), params, "FETI-DP");
      feti.setTopology(pb.subdomains(), pb.ownedMap());
      EXPECT_EQ(feti.primalMap()->getGlobalNumElements(), size_t(3 * dpn));
      EXPECT_EQ(feti.numDualDofs(), GO((4 * s.H - 3) * dpn));
      EXPECT_EQ(feti.lmMap()->getGlobalNumElements(), size_t((4 * s.H - 4 + 6) * dpn));
    }
    for (const std::string prec : {"Dirichlet", "Lumped"}) {
      const FetiRun r = runFeti(s, fetiParams(prec));
      report(std::string(dpn == 1 ? "Laplace" : "elasticity") + " 2x2 non-primal cross point " + prec, r);
      EXPECT_LT(r.error, ddc::test::kFetiVsDirect);
    }
  }
}

TEST(FetiDp, BAnnihilatesContinuousFields) {
  for (const std::string primal : {"Vertices", "Vertices and Edges"})
  for (int dpn : {1, 2}) {
    Spec s;
    s.Sx = 3, s.Sy = 3, s.H = 3, s.dpn = dpn;
    Problem pb(s);
    auto params = fetiParams("Dirichlet", "Multiplicity", "CG", ddc::test::kTightBelos, primal);
    FetiDpSolver feti(worldComm(), params, "FETI-DP");
    auto subs = pb.subdomains();
    std::vector<std::vector<double>> cont, jump;
    for (const auto& sd : subs) {
      cont.emplace_back(), jump.emplace_back();
      for (GO g : sd.dofs) {
        cont.back().push_back(std::cos(0.1 * double(g)) + 2.0);
        jump.back().push_back(std::cos(0.1 * double(g)) + 2.0 + sd.id);
      }
    }
    feti.setTopology(subs, pb.ownedMap());
    ASSERT_GT(feti.lmMap()->getGlobalNumElements(), 0u);
    EXPECT_LE(feti.applyB(cont)->normInf(), ddc::test::kRoundoff) << "B u != 0 for a continuous field";
    // A field jumping by the subdomain id: each row is u_s - u_t with s < t
    // (+1 for the smaller id), so every entry is id_s - id_t < 0.
    auto bj = feti.applyB(jump);
    EXPECT_GT(bj->normInf(), 0.5);
    for (double v : bj->getData()) EXPECT_LE(v, -1.0 + ddc::test::kRoundoff);
  }
}

TEST(FetiDp, FIsSymmetricPositiveDefinite) {
  Spec s;
  s.Sx = 3, s.Sy = 2, s.H = 4, s.dpn = 2;
  Problem pb(s);
  auto params = fetiParams();
  FetiDpSolver feti(worldComm(), params, "FETI-DP");
  feti.setTopology(pb.subdomains(), pb.ownedMap());
  feti.numeric();
  auto F = feti.fOperator();
  MultiVector x(feti.lmMap(), 2), Fx(feti.lmMap(), 2);
  x.randomize();
  F->apply(x, Fx);
  const double a = x.getVector(0)->dot(*Fx.getVector(1)), b = x.getVector(1)->dot(*Fx.getVector(0));
  EXPECT_LT(ddc::test::relDiff(a, b), 1e-10) << "(x0, F x1) vs (x1, F x0)";
  EXPECT_GT(x.getVector(0)->dot(*Fx.getVector(0)), 0.0);
  // alpha / beta handling of the operator: Y = 2 F x + 3 Y
  MultiVector y(Fx, Teuchos::Copy);
  F->apply(x, y, Teuchos::NO_TRANS, 2.0, 3.0);
  y.update(-5.0, Fx, 1.0);
  EXPECT_LT(y.getVector(0)->normInf(), 1e-12 * Fx.getVector(0)->normInf());
}

TEST(FetiDp, NumericReusesTopologyAfterValueUpdate) {
  // Newton pattern: the caller rescales K's values, calls numeric() again;
  // u must scale inversely.
  Spec s;
  s.Sx = 2, s.Sy = 2, s.H = 4, s.dpn = 2;
  Problem pb(s);
  auto params = fetiParams();
  FetiDpSolver feti(worldComm(), params, "FETI-DP");
  auto subs = pb.subdomains();
  std::vector<RCP<CrsMatrix>> Ks;
  for (auto& sd : subs) Ks.push_back(sd.K);
  feti.setTopology(subs, pb.ownedMap());
  feti.numeric();
  auto b = pb.load();
  Vector u1(pb.ownedMap()), u2(pb.ownedMap());
  feti.solve(*b, u1);
  for (auto& K : Ks) {
    K->resumeFill();
    K->scale(4.0);
    K->fillComplete();
  }
  feti.numeric();
  feti.solve(*b, u2);
  u2.scale(4.0);
  EXPECT_LT(relDiff(u2, u1), ddc::test::kFetiVsDirect);
}

// ---- extra (contact) constraint rows ------------------------------------------

/// Extra rows sum_k coef_k u(node_k, comp_k) = c across subdomains, some on
/// primal and dual interface DOFs, one inactive (multiplier restrained to 0).
struct ExtraRow {
  std::vector<std::array<int, 3>> at;  // (i, j, component)
  std::vector<double> coef;
  double c;
  bool active;
};

std::vector<ExtraRow> extraRows() {
  return {
      {{{2, 3, 0}, {6, 5, 0}}, {1.0, -1.0}, 0.1, true},     // interior of subdomain 0 vs interior of 3
      {{{4, 4, 1}, {7, 1, 1}}, {0.6, 0.8}, -0.2, true},     // primal cross point vs subdomain 1
      {{{3, 7, 0}, {5, 2, 1}}, {1.0, -1.0}, 0.3, false},    // released: multiplier restrained to zero
      {{{4, 2, 0}, {1, 8, 1}, {2, 8, 1}}, {1.0, -0.5, -0.5}, 0.0, true},  // dual interface DOF vs an edge
      // Primal DOFs only (a slave node on a primal master node): the
      // preconditioner must still see the row (lumped), or CG breaks down.
      {{{4, 4, 0}, {8, 4, 1}}, {1.0, -1.0}, 0.05, true},
  };
}

/// One row of the reference saddle-point system: entries (global DOF,
/// coefficient), right-hand side, active (inactive: identity row, mu = 0).
struct ReferenceRow {
  std::vector<std::pair<GO, double>> entries;
  double c;
  bool active;
};

/// Coupled rows in the reference (FetiDpSolver::setConstraintCoupling()),
/// dense over the rows: multipliers T x, equations G B u - E x.
struct ReferenceCoupling {
  std::vector<std::vector<double>> T, G;
  std::vector<double> E;
};

/// [K B^T; B 0] [u; mu] = [b; c] solved by MUMPS (checked by its residual),
/// the multiplier of row r at n + r (n = K's size); returned on every rank
/// (a replicated map), to compare with a solution in any layout. With a
/// coupling: [K B^T T; G B -E] [u; x] = [b; c], x the dual unknowns.
Vector saddlePointReference(const CrsMatrix& K, const Vector& b, const std::vector<ReferenceRow>& rows,
                            const ReferenceCoupling* coupling = nullptr) {
  const int me = worldRank();
  const GO n = GO(K.getRowMap()->getGlobalNumElements());
  const GO N = n + GO(rows.size());
  auto bigMap = rcp(new Map(N, 0, worldComm()));
  auto A = rcp(new CrsMatrix(bigMap, 24));
  CrsMatrix::local_inds_host_view_type inds;
  CrsMatrix::values_host_view_type vals;
  for (LO l = 0; l < LO(K.getNodeNumRows()); ++l) {
    K.getLocalRowView(l, inds, vals);
    std::vector<GO> cols;
    std::vector<double> v;
    for (size_t e = 0; e < inds.extent(0); ++e) cols.push_back(K.getColMap()->getGlobalElement(inds(e))), v.push_back(vals(e));
    A->insertGlobalValues(K.getRowMap()->getGlobalElement(l), Teuchos::ArrayView<const GO>(cols),
                          Teuchos::ArrayView<const double>(v));
  }
  auto bigB = rcp(new Vector(bigMap));
  if (me == 0)
    for (size_t r = 0; r < rows.size(); ++r) {
      const GO row = n + GO(r);
      if (!rows[r].active) {
        const double one = 1.0;
        A->insertGlobalValues(row, 1, &one, &row);
        continue;
      }
      if (!coupling) {
        for (const auto& [d, v] : rows[r].entries) {
          A->insertGlobalValues(row, 1, &v, &d);
          A->insertGlobalValues(d, 1, &v, &row);
        }
        continue;
      }
      for (size_t q = 0; q < rows.size(); ++q)  // the equation: sum_q G(r, q) B_q u
        for (const auto& [d, v] : rows[q].entries) {
          const double gv = coupling->G[r][q] * v;
          if (gv != 0.0) A->insertGlobalValues(row, 1, &gv, &d);
        }
      const double e = -coupling->E[r];
      if (e != 0.0) A->insertGlobalValues(row, 1, &e, &row);
    }
  if (me == 0 && coupling)  // the columns: B_r^T lambda_r, lambda_r = sum_j T(r, j) x_j
    for (size_t r = 0; r < rows.size(); ++r)
      for (size_t j = 0; j < rows.size(); ++j)
        for (const auto& [d, v] : rows[r].entries) {
          const double tv = coupling->T[r][j] * v;
          const GO col = n + GO(j);
          if (tv != 0.0) A->insertGlobalValues(d, 1, &tv, &col);
        }
  A->fillComplete();
  {
    // b on the saddle-point map (a different distribution): moved by an Export.
    Tpetra::Export<LO, GO, ddc::Node> toBig(b.getMap(), bigMap);
    bigB->doExport(b, toBig, Tpetra::INSERT);
    for (size_t r = 0; r < rows.size(); ++r)
      if (bigMap->isNodeGlobalElement(n + GO(r))) bigB->replaceGlobalValue(n + GO(r), rows[r].active ? rows[r].c : 0.0);
  }
  Teuchos::ParameterList dp;
  dp.set("Type", std::string("MUMPS"));
  if (coupling) dp.sublist("MUMPS").set("Symmetric", false);  // T != Gᵀ: the whole matrix, not its lower triangle
  auto direct = ddc::DirectSolverFactory::withBuiltins().create(dp, "Reference");
  direct->symbolic(A);
  direct->numeric();
  Vector x(bigMap);
  direct->solve(*bigB, x);
  {
    Vector r(bigMap);
    A->apply(x, r);
    r.update(1.0, *bigB, -1.0);
    EXPECT_LT(r.norm2() / bigB->norm2(), 1e-10) << "reference saddle-point solve";
  }
  std::vector<GO> every(N);
  for (GO k = 0; k < N; ++k) every[k] = k;
  auto allMap = rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                            Teuchos::ArrayView<const GO>(every), 0, worldComm()));
  Tpetra::Import<LO, GO, ddc::Node> toAll(bigMap, allMap);
  Vector xAll(allMap);
  xAll.doImport(x, toAll, Tpetra::INSERT);
  return xAll;
}

/// A coupling of extraRows() for checkExtraRows(): the rows' active flags
/// and right-hand sides, the coupled rows (LID = row number: every row on
/// rank 0), and the same as dense matrices for the reference.
struct CouplingCase {
  std::vector<char> active;
  std::vector<double> c;
  std::vector<ddc::CoupledRow> rows;
  ReferenceCoupling dense;
  bool nonsymmetric;
};

/// K u + B_c^T mu = b, B_c u = c on the active rows, mu = 0 on the
/// inactive one: FETI-DP with setConstraintRows()/setConstraintState()
/// against MUMPS on the assembled saddle-point matrix; with a coupling
/// (setConstraintCoupling()) its saddle point.
void checkExtraRows(const std::string& primal, const CouplingCase* coupling = nullptr) {
  Spec s;
  s.Sx = 2, s.Sy = 2, s.H = 4, s.dpn = 2;
  Problem pb(s);
  auto rows = extraRows();
  if (coupling)
    for (size_t r = 0; r < rows.size(); ++r) rows[r].active = coupling->active[r], rows[r].c = coupling->c[r];
  const int P = worldSize(), me = worldRank();
  const GO n = GO(pb.ownedMap()->getGlobalNumElements());
  // Rows owned round-robin (a coupling: all on rank 0, its rows are local
  // to one rank); row GIDs 100 + r (any one-to-one map will do).
  std::vector<GO> mine;
  for (size_t r = 0; r < rows.size(); ++r)
    if ((coupling ? 0 : int(r) % P) == me) mine.push_back(100 + GO(r));
  auto rowMap = rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                            Teuchos::ArrayView<const GO>(mine), 0, worldComm()));
  auto subs = pb.subdomains();
  // Each entry goes to the lowest-id subdomain containing its node.
  auto firstSub = [&](int i, int j) {
    for (int b = 0; b < s.Sy; ++b)
      for (int a = 0; a < s.Sx; ++a)
        if (a * s.H <= i && i <= (a + 1) * s.H && b * s.H <= j && j <= (b + 1) * s.H) return a + s.Sx * b;
    return -1;
  };
  std::vector<std::vector<ddc::ConstraintEntry>> entries(subs.size());
  for (size_t r = 0; r < rows.size(); ++r)
    for (size_t k = 0; k < rows[r].at.size(); ++k) {
      const auto [i, j, c] = rows[r].at[k];
      for (size_t ls = 0; ls < subs.size(); ++ls) {
        if (subs[ls].id != firstSub(i, j)) continue;
        const auto it = std::find(subs[ls].dofs.begin(), subs[ls].dofs.end(), pb.dof(i, j, c));
        ASSERT_NE(it, subs[ls].dofs.end());
        entries[ls].push_back({100 + GO(r), LO(it - subs[ls].dofs.begin()), rows[r].coef[k]});
      }
    }
  // The DOFs of the row entries are "constrainable" (Dirichlet preconditioner sees them).
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    subs[ls].constrainable.assign(subs[ls].dofs.size(), 0);
    for (const auto& e : entries[ls]) subs[ls].constrainable[e.dof] = 1;
  }
  auto params = fetiParams("Dirichlet", "Multiplicity", "CG", ddc::test::kTightBelos, primal);
  FetiDpSolver feti(worldComm(), params, "FETI-DP");
  feti.setTopology(subs, pb.ownedMap());
  feti.setConstraintRows(rowMap, entries);
  std::vector<char> active;
  std::vector<double> c;
  for (GO g : mine) active.push_back(rows[g - 100].active), c.push_back(rows[g - 100].c);
  feti.setConstraintState(active, c);
  if (coupling) feti.setConstraintCoupling(me == 0 ? coupling->rows : std::vector<ddc::CoupledRow>{});
  feti.numeric();
  auto b = pb.load();
  Vector u(pb.ownedMap());
  const auto info = feti.solve(*b, u);
  auto mu = feti.constraintMultipliers();
  ASSERT_FALSE(mu.is_null());
  if (coupling) EXPECT_EQ(info.gmresForCoupledRows, coupling->nonsymmetric);

  // Reference: [K B^T; B 0] (identity row for the inactive multiplier).
  std::vector<ReferenceRow> refRows;
  for (const auto& row : rows) {
    ReferenceRow rr{{}, row.c, row.active};
    for (size_t k = 0; k < row.at.size(); ++k) {
      const auto [i, j, cc] = row.at[k];
      rr.entries.emplace_back(pb.dof(i, j, cc), row.coef[k]);
    }
    refRows.push_back(rr);
  }
  Vector xAll = saddlePointReference(*pb.globalK(), *b, refRows, coupling ? &coupling->dense : nullptr);
  auto xa = xAll.getData();
  // The reference multipliers: T x (x itself without a coupling).
  std::vector<double> lambdaRef(rows.size());
  for (size_t r = 0; r < rows.size(); ++r)
    if (!coupling) {
      lambdaRef[r] = xa[n + GO(r)];
    } else {
      for (size_t j = 0; j < rows.size(); ++j) lambdaRef[r] += coupling->dense.T[r][j] * xa[n + GO(j)];
    }
  double du = 0.0, un = 0.0;
  {
    auto uv = u.getData();
    for (LO l = 0; l < LO(uv.size()); ++l) {
      const GO g = pb.ownedMap()->getGlobalElement(l);
      du = std::max(du, std::abs(uv[l] - xa[g]));
      un = std::max(un, std::abs(xa[g]));
    }
  }
  double dm = 0.0, mn = 0.0;
  {
    auto m = mu->getData();
    for (size_t k = 0; k < mine.size(); ++k) {
      const GO r = mine[k] - 100;
      dm = std::max(dm, std::abs(m[k] - lambdaRef[r]));
      mn = std::max(mn, std::abs(lambdaRef[r]));
      if (!rows[r].active && !coupling) EXPECT_EQ(m[k], 0.0) << "released row " << r << " multiplier must be exactly zero";
    }
  }
  double g[4] = {du, un, dm, mn}, G[4];
  MPI_Allreduce(g, G, 4, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  if (me == 0)
    std::printf("[ feti-dp  ] extra rows (%s): it %d, max |u - u_ref| / max|u_ref| %.2e, multipliers %.2e\n",
                primal.c_str(), info.iterations, G[0] / G[1], G[2] / G[3]);
  EXPECT_GT(G[3], 0.0) << "the reference multipliers vanish: the rows do nothing";
  EXPECT_LT(G[0] / G[1], ddc::test::kFetiVsDirect);
  EXPECT_LT(G[2] / G[3], ddc::test::kFetiVsDirect);
  // The active rows hold: B_c u = c.
  for (size_t r = 0; r < rows.size(); ++r) {
    if (!rows[r].active || coupling) continue;
    double v = 0.0;
    for (size_t k = 0; k < rows[r].at.size(); ++k) {
      const auto [i, j, cc] = rows[r].at[k];
      v += rows[r].coef[k] * xa[pb.dof(i, j, cc)];
    }
    EXPECT_NEAR(v, rows[r].c, 1e-10) << "reference row " << r;
  }
}

TEST(FetiDp, ExtraRowsMatchTheSaddlePointSolve) { checkExtraRows("Vertices"); }

/// Coupled rows as the friction rows use them (doc/feti-dp.md "Coupled
/// rows"): rows 3 and 4 rotated into one unknown (row 4 inactive, its
/// multiplier 0.8 x_3, row 3's 0.6 x_3, its equation 0.6 B_3 u + 0.8 B_4 u
/// with a compliance) and, when `dependent`, inactive row 2's multiplier a
/// combination of rows 0 and 1 (T != Gᵀ: GMRES).
CouplingCase couplingCase(bool dependent) {
  const size_t R = extraRows().size();
  CouplingCase cc;
  cc.active = {1, 1, 0, 1, 0};
  cc.c = {0.1, -0.2, 0.0, 0.02, 0.0};
  cc.dense.T.assign(R, std::vector<double>(R, 0.0));
  cc.dense.G = cc.dense.T;
  cc.dense.E.assign(R, 0.0);
  for (size_t r = 0; r < R; ++r)
    if (cc.active[r]) cc.dense.T[r][r] = cc.dense.G[r][r] = 1.0;
  const double compliance = 0.05;
  cc.rows.push_back({3, {{3, 0.6}}, {{3, 0.6}, {4, 0.8}}, compliance});
  cc.rows.push_back({4, {{3, 0.8}}, {}, 0.0});
  cc.dense.T[3][3] = 0.6, cc.dense.T[4][3] = 0.8;
  cc.dense.G[3][3] = 0.6, cc.dense.G[3][4] = 0.8;
  cc.dense.E[3] = compliance;
  if (dependent) {
    cc.rows.push_back({2, {{0, 0.3}, {1, -0.2}}, {}, 0.0});
    cc.dense.T[2][0] = 0.3, cc.dense.T[2][1] = -0.2;
  }
  cc.nonsymmetric = dependent;
  return cc;
}

TEST(FetiDp, SymmetricCoupledRowsMatchTheSaddlePointSolve) {
  const CouplingCase cc = couplingCase(false);
  checkExtraRows("Vertices", &cc);
}

TEST(FetiDp, NonsymmetricCoupledRowsMatchTheSaddlePointSolveByGmres) {
  const CouplingCase cc = couplingCase(true);
  checkExtraRows("Vertices", &cc);
}

/// Contact rows keep working with edge constraints: rows on edge DOFs are
/// transformed with the change of basis (ChangeOfBasis::rowToNew).
TEST(FetiDp, ExtraRowsMatchTheSaddlePointSolveWithEdgeConstraints) { checkExtraRows("Vertices and Edges"); }

// ---- extra rows between bodies of different stiffness ---------------------------

/// Insert the local rows of `src` into `dst`, rows and columns shifted by
/// `shift` global ids (a block of a block-diagonal matrix).
void insertShifted(const CrsMatrix& src, GO shift, CrsMatrix& dst) {
  CrsMatrix::local_inds_host_view_type inds;
  CrsMatrix::values_host_view_type vals;
  std::vector<GO> cols;
  std::vector<double> v;
  for (LO l = 0; l < LO(src.getNodeNumRows()); ++l) {
    src.getLocalRowView(l, inds, vals);
    cols.clear(), v.clear();
    for (size_t e = 0; e < inds.extent(0); ++e)
      cols.push_back(src.getColMap()->getGlobalElement(inds(e)) + shift), v.push_back(vals(e));
    dst.insertGlobalValues(src.getRowMap()->getGlobalElement(l) + shift, Teuchos::ArrayView<const GO>(cols),
                           Teuchos::ArrayView<const double>(v));
  }
}

/// One subdomain per pair: the first `nLocalA` of `subs` are body A's, the
/// rest body B's (ids shifted by `idB`); A's (a, b) takes B's (Sx-1-a, b),
/// which must be on this rank, its DOFs appended and its matrix placed
/// block-diagonally after A's.
std::vector<FetiSubdomain> pairedSubdomains(const std::vector<FetiSubdomain>& subs, size_t nLocalA, int idB,
                                            int Sx) {
  std::vector<FetiSubdomain> out;
  for (size_t la = 0; la < nLocalA; ++la) {
    const FetiSubdomain& A = subs[la];
    const int partner = idB + (Sx - 1 - A.id % Sx) + Sx * (A.id / Sx);
    const auto it = std::find_if(subs.begin() + long(nLocalA), subs.end(),
                                 [&](const FetiSubdomain& s) { return s.id == partner; });
    if (it == subs.end()) throw std::logic_error("pairedSubdomains: partner not on this rank");
    const FetiSubdomain& B = *it;
    FetiSubdomain m = A;
    m.dofs.insert(m.dofs.end(), B.dofs.begin(), B.dofs.end());
    m.primal.insert(m.primal.end(), B.primal.begin(), B.primal.end());
    m.component.insert(m.component.end(), B.component.begin(), B.component.end());
    m.coordinates.insert(m.coordinates.end(), B.coordinates.begin(), B.coordinates.end());
    const LO nA = LO(A.dofs.size()), n = LO(m.dofs.size());
    auto K = rcp(new CrsMatrix(rcp(new Map(n, 0, selfComm())), 18));
    insertShifted(*A.K, 0, *K);
    insertShifted(*B.K, nA, *K);
    K->fillComplete();
    m.K = K;
    out.push_back(std::move(m));
  }
  return out;
}

/// Body A (coefficient 1) and body B (coefficient `ratio`), each a grid of
/// Sx x Sy subdomains with its left edge fixed, coupled only by extra rows
/// u_A(H, j, 1) - u_B(H, j, 1) = c at every other node (odd j) of the line
/// i = H, an interface between subdomains in both bodies: the entries sit
/// on dual DOFs shared by two subdomains (A's in its lower-id copy, B's in
/// its higher-id copy), like slave nodes and master facets on METIS cuts,
/// and the edge constraints find representatives off the rows' DOFs. Solves with the given
/// Scaling; checks FETI-DP = MUMPS on the saddle-point system; returns the
/// dual iterations and CG's condition estimate.
///
/// With `shared`, every subdomain holds a piece of each body, as a METIS
/// partition of two bodies makes: A's subdomain (a, b) and B's (Sx-1-a, b)
/// are one subdomain, whose matrix is block diagonal (two parts its graph
/// does not connect), so that the two entries of a row lie in one subdomain.
std::pair<int, double> twoBodiesAcrossAStiffnessJump(double ratio, const std::string& scaling, bool shared = false) {
  Spec sa;
  sa.Sx = 2, sa.Sy = 2, sa.H = 6, sa.dpn = 2;
  sa.blockwise = shared;  // A's (a, b) and B's (Sx-1-a, b) on one rank
  Spec sb = sa;
  sb.coef = [ratio](int, int) { return ratio; };
  const Problem A(sa), B(sb);
  const GO nA = GO(A.ownedMap()->getGlobalNumElements()), nB = GO(B.ownedMap()->getGlobalNumElements());
  const int idB = A.numSubdomains();
  auto owned = rcp(new Map(nA + nB, 0, worldComm()));
  auto subs = A.subdomains();
  const size_t nLocalA = subs.size();
  for (auto sd : B.subdomains()) {
    for (GO& g : sd.dofs) g += nA;
    sd.id += idB;
    subs.push_back(std::move(sd));
  }
  if (shared) subs = pairedSubdomains(subs, nLocalA, idB, sa.Sx);
  // The rows: one per node (H, j) off the subdomain corners.
  std::vector<ReferenceRow> rows;
  std::vector<std::pair<int, int>> at;  // (j, row)
  for (int j = 1; j < sa.Sy * sa.H; j += 2) {
    rows.push_back(ReferenceRow{{{A.dof(sa.H, j, 1), 1.0}, {nA + B.dof(sa.H, j, 1), -1.0}}, 0.01, true});
    at.emplace_back(j, int(rows.size()) - 1);
  }
  const int P = worldSize(), me = worldRank();
  std::vector<GO> mine;
  for (size_t r = 0; r < rows.size(); ++r)
    if (int(r) % P == me) mine.push_back(GO(r));
  auto rowMap = rcp(new Map(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                            Teuchos::ArrayView<const GO>(mine), 0, worldComm()));
  std::vector<std::vector<ddc::ConstraintEntry>> entries(subs.size());
  for (size_t ls = 0; ls < subs.size(); ++ls) {
    subs[ls].constrainable.assign(subs[ls].dofs.size(), 0);
    // The pieces of the subdomain: (is A, its subdomain id in that body).
    std::vector<std::pair<bool, int>> pieces;
    if (shared) {
      const int a = subs[ls].id % sa.Sx, b = subs[ls].id / sa.Sx;
      pieces = {{true, subs[ls].id}, {false, (sa.Sx - 1 - a) + sa.Sx * b}};
    } else {
      const bool inA = ls < nLocalA;
      pieces = {{inA, inA ? subs[ls].id : subs[ls].id - idB}};
    }
    for (const auto& [inA, local] : pieces) {
      const int a = local % sa.Sx, b = local / sa.Sx;
      for (const auto& [j, r] : at) {
        // A's entry in the copy of subdomain column 0, B's in column 1.
        if (a != (inA ? 0 : 1) || j < b * sa.H || j > (b + 1) * sa.H) continue;
        const GO g = inA ? A.dof(sa.H, j, 1) : nA + B.dof(sa.H, j, 1);
        const auto it = std::find(subs[ls].dofs.begin(), subs[ls].dofs.end(), g);
        if (it == subs[ls].dofs.end()) continue;
        const LO l = LO(it - subs[ls].dofs.begin());
        entries[ls].push_back({GO(r), l, inA ? 1.0 : -1.0});
        subs[ls].constrainable[l] = 1;
      }
    }
  }
  // Every copy of a constrained node is constrainable (the solver would unify them anyway).
  for (size_t ls = 0; ls < subs.size(); ++ls)
    for (size_t k = 0; k < subs[ls].dofs.size(); ++k)
      for (const auto& row : rows)
        for (const auto& [g, c] : row.entries)
          if (subs[ls].dofs[k] == g) subs[ls].constrainable[k] = 1;
  auto params = fetiParams("Dirichlet", scaling, "CG", ddc::test::kTightBelos, "Automatic");
  params.sublist("Belos").set("Maximum Iterations", 2000);
  params.sublist("Belos").set("Estimate Condition Number", true);
  FetiDpSolver feti(worldComm(), params, "FETI-DP");
  feti.setTopology(subs, owned);
  feti.setConstraintRows(rowMap, entries);
  feti.setConstraintState(std::vector<char>(mine.size(), 1), std::vector<double>(mine.size(), 0.01));
  feti.numeric();
  Vector b(owned);
  {
    auto v = b.getDataNonConst();
    for (LO l = 0; l < LO(v.size()); ++l) v[l] = std::sin(0.37 * double(owned->getGlobalElement(l)) + 0.1) + 0.5;
  }
  Vector u(owned);
  const auto info = feti.solve(b, u);

  // Reference: the block-diagonal K of the two bodies.
  auto K = rcp(new CrsMatrix(owned, 24));
  insertShifted(*A.globalK(), 0, *K);
  insertShifted(*B.globalK(), nA, *K);
  K->fillComplete();
  Vector xAll = saddlePointReference(*K, b, rows);
  auto xa = xAll.getData();
  const GO n = nA + nB;
  double g[4] = {0, 0, 0, 0}, G[4];
  {
    auto uv = u.getData();
    for (LO l = 0; l < LO(uv.size()); ++l) {
      const GO gid = owned->getGlobalElement(l);
      g[0] = std::max(g[0], std::abs(uv[l] - xa[gid]));
      g[1] = std::max(g[1], std::abs(xa[gid]));
    }
    auto mu = feti.constraintMultipliers()->getData();
    for (size_t k = 0; k < mine.size(); ++k) {
      g[2] = std::max(g[2], std::abs(mu[k] - xa[n + mine[k]]));
      g[3] = std::max(g[3], std::abs(xa[n + mine[k]]));
    }
  }
  MPI_Allreduce(g, G, 4, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  if (me == 0)
    std::printf("[ feti-dp  ] two bodies 1:%g, %zu rows, Scaling %s: it %d, condition ~%.3g, max |u - u_ref| / "
                "max|u_ref| %.2e, multipliers %.2e\n",
                ratio, rows.size(), scaling.c_str(), info.iterations, info.conditionEstimate, G[0] / G[1],
                G[2] / G[3]);
  EXPECT_GT(G[3], 0.0) << "the reference multipliers vanish: the rows do nothing";
  EXPECT_LT(G[0] / G[1], ddc::test::kFetiVsDirect);
  EXPECT_LT(G[2] / G[3], ddc::test::kFetiVsDirect);
  return {info.iterations, info.conditionEstimate};
}

/// How much a 1:1000 stiffness jump between the bodies may raise the
/// condition estimate with stiffness-weighted contact rows (measured: not at
/// all), and how much it must raise it with equal weights to show what the
/// weights are for (measured: 250 times).
constexpr double kJumpConditionGrowth = 1.5;
constexpr double kEqualWeightsConditionGrowth = 10.0;

TEST(FetiDp, ExtraRowsAcrossAStiffnessJumpArePreconditioned) {
  // Contact rows join bodies of different stiffness: weighted by the
  // stiffness of their two sides (Scaling = Automatic) the condition of the
  // preconditioned dual operator does not depend on the ratio; with equal
  // weights (Multiplicity, 1/2 each side) the rows' preconditioner is ~250
  // times too stiff at 1:1000 (doc/feti-dp.md "Extra rows"). Measured on 1
  // and 2 ranks: condition ~112 (1:1) and ~112 (1:1000) against 2.8e4, 13-15
  // iterations against 23-24.
  const auto same = twoBodiesAcrossAStiffnessJump(1.0, "Automatic");
  const auto jump = twoBodiesAcrossAStiffnessJump(1000.0, "Automatic");
  const auto equal = twoBodiesAcrossAStiffnessJump(1000.0, "Multiplicity");
  EXPECT_LE(jump.second, kJumpConditionGrowth * same.second) << "the 1:1000 jump raised the condition";
  EXPECT_GT(equal.second, kEqualWeightsConditionGrowth * same.second) << "equal weights did not suffer from the jump";
  EXPECT_LE(jump.first, same.first + 2);
}

/// How many more dual iterations rows within subdomains of two bodies may
/// take than rows between subdomains of one body each (measured 19 against
/// 13 on 1 and 2 ranks; 36 with one weight per subdomain).
constexpr double kSharedSubdomainIterationGrowth = 1.6;

TEST(FetiDp, ExtraRowsWithinASubdomainOfTwoBodiesArePreconditioned) {
  // A METIS subdomain may hold pieces of two bodies that only contact joins;
  // a contact row then has both entries in one subdomain. Its sides are the
  // parts of the subdomain's graph, not the subdomain: weighted as one side
  // (the stiff body's entry at full weight) the row's preconditioner was
  // ~1000 times too stiff: condition ~1.95e4 at 1:1000, 36 iterations
  // (ironing on 4 METIS subdomains: ~5e4 and 190-480 iterations). Weighted
  // by part: ~112 and 19, as with the bodies in different subdomains
  // (measured on 1 and 2 ranks).
  const auto separate = twoBodiesAcrossAStiffnessJump(1000.0, "Automatic");
  const auto shared = twoBodiesAcrossAStiffnessJump(1000.0, "Automatic", true);
  EXPECT_LE(shared.second, kJumpConditionGrowth * separate.second) << "a row within a subdomain raised the condition";
  EXPECT_LE(shared.first, kSharedSubdomainIterationGrowth * separate.first);
}

TEST(FetiDp, ExtraRowErrorsAreCollective) {
  Spec s;
  s.Sx = 2, s.Sy = 1, s.H = 2, s.dpn = 1;
  Problem pb(s);
  auto params = fetiParams();
  FetiDpSolver feti(worldComm(), params, "FETI-DP");
  auto subs = pb.subdomains();
  const size_t nLocal = subs.size();
  feti.setTopology(subs, pb.ownedMap());
  auto rowMap = rcp(new Map(1, 0, worldComm()));
  // A row GID not in the row map.
  std::vector<std::vector<ddc::ConstraintEntry>> bad(nLocal);
  if (nLocal) bad[0].push_back({7, 0, 1.0});
  expectThrowWith<std::invalid_argument>([&] { feti.setConstraintRows(rowMap, bad); }, {"row 7", "not in the row map"});
  // A local DOF out of range.
  std::vector<std::vector<ddc::ConstraintEntry>> range(nLocal);
  if (nLocal) range[0].push_back({0, 100000, 1.0});
  expectThrowWith<std::invalid_argument>([&] { feti.setConstraintRows(rowMap, range); }, {"local DOF outside"});
  // An active row without entries cannot be enforced.
  feti.setConstraintRows(rowMap, std::vector<std::vector<ddc::ConstraintEntry>>(nLocal));
  const size_t owned = rowMap->getNodeNumElements();
  expectThrowWith<ddc::SolverError>([&] { feti.setConstraintState(std::vector<char>(owned, 1), std::vector<double>(owned, 1.0)); },
                  {"constraint row 0", "no entry"});
  // Coupled rows (on the row's owner; the others pass none): a row outside
  // the row map, an equation on an inactive row, a negative compliance.
  feti.setConstraintState(std::vector<char>(owned, 0), std::vector<double>(owned, 0.0));
  auto coupled = [&](const ddc::CoupledRow& r) {
    return owned ? std::vector<ddc::CoupledRow>{r} : std::vector<ddc::CoupledRow>{};
  };
  expectThrowWith<std::invalid_argument>([&] { feti.setConstraintCoupling(coupled({5, {}, {}, 0.0})); },
                                         {"row 5", "not a local row"});
  expectThrowWith<std::invalid_argument>([&] { feti.setConstraintCoupling(coupled({0, {}, {{0, 1.0}}, 0.0})); },
                                         {"row 0", "inactive row"});
  expectThrowWith<std::invalid_argument>([&] { feti.setConstraintCoupling(coupled({0, {{0, 1.0}}, {}, 0.0})); },
                                         {"row 0", "active local row"});
  expectThrowWith<std::invalid_argument>([&] { feti.setConstraintCoupling(coupled({0, {}, {}, -1.0})); },
                                         {"row 0", "finite and >= 0"});
}

// ---- a host-registered local solver --------------------------------------------

/// A host's own back end: MUMPS behind a wrapper that counts factorisations.
class CountingSolver : public ddc::DirectSolver {
 public:
  CountingSolver(std::unique_ptr<ddc::DirectSolver> inner, int* count) : inner_(std::move(inner)), count_(count) {}
  void symbolic(const RCP<const CrsMatrix>& A) override { inner_->symbolic(A); }
  void numeric() override {
    ++*count_;
    inner_->numeric();
  }
  void solve(const MultiVector& b, MultiVector& x) override { inner_->solve(b, x); }
  std::string name() const override { return "Counting " + inner_->name(); }

 private:
  std::unique_ptr<ddc::DirectSolver> inner_;
  int* count_;
};

TEST(FetiDp, HostRegisteredLocalSolverIsUsed) {
  // DirectSolverFactory::add() + the factory argument of FetiDpSolver: the
  // subdomain matrices (K_rr and, for the Dirichlet preconditioner, K_II of
  // every subdomain) are factorised by the host's back end.
  int numerics = 0;
  auto solvers = ddc::DirectSolverFactory::withBuiltins();
  ddc::DirectSolverFactory::Entry counting;
  counting.create = [&numerics](const Teuchos::ParameterList&) -> std::unique_ptr<ddc::DirectSolver> {
    Teuchos::ParameterList p;
    p.set("Type", std::string("MUMPS"));
    return std::make_unique<CountingSolver>(ddc::DirectSolverFactory::withBuiltins().create(p, "inner"), &numerics);
  };
  counting.validParameters = rcp(new Teuchos::ParameterList("Counting"));
  counting.description = "MUMPS counting its factorisations (a test back end)";
  solvers.add("Counting", counting);

  Spec s;
  s.Sx = 3, s.Sy = 3, s.H = 4, s.dpn = 2;
  Problem pb(s);
  auto params = fetiParams();
  params.sublist("Local Solver").set("Type", std::string("Counting"));
  FetiDpSolver feti(worldComm(), params, "FETI-DP", solvers);
  const auto subs = pb.subdomains();
  const int nLocal = int(subs.size());
  feti.setTopology(subs, pb.ownedMap());
  feti.numeric();
  EXPECT_EQ(numerics, 2 * nLocal) << "one K_rr and one K_II factorisation per local subdomain";
  auto b = pb.load();
  Vector u(pb.ownedMap());
  feti.solve(*b, u);
  EXPECT_LT(relDiff(u, *directSolve(pb, *b)), ddc::test::kFetiVsDirect);
  // The built-in factory does not know it: an InputError naming the path.
  auto unknown = fetiParams();
  unknown.sublist("Local Solver").set("Type", std::string("Counting"));
  expectThrowWith<ddc::InputError>([&] { FetiDpSolver f(worldComm(), unknown, "Solver/FETI-DP"); },
                                   {"Solver/FETI-DP/Local Solver/Type", "Counting"});
}

// ---- edge constraints: change of basis and counts -------------------------------

/// ChangeOfBasis against dense algebra on a 7-DOF example with two groups:
/// T^{-1} T = I, K̂ = T^T K T, f̂ = T^T f, rows c^T T, and û_R = C u.
TEST(FetiDpChangeOfBasis, MatchesDenseAlgebra) {
  const LO n = 7;
  std::vector<ddc::PrimalGroup> groups(2);
  groups[0].dofs = {1, 3, 4, 6};
  groups[0].rows = {{0.25, 0.25, 0.25, 0.25}, {-0.6, -0.2, 0.2, 0.6}};
  groups[1].dofs = {2, 5};
  groups[1].rows = {{0.5, 0.5}};
  ddc::ChangeOfBasis T(n, groups);
  EXPECT_EQ(T.numConstraints(), 3);
  // K: a dense SPD matrix (all couplings present).
  std::vector<double> K(n * n);
  for (LO i = 0; i < n; ++i)
    for (LO j = 0; j < n; ++j) K[i * n + j] = (i == j ? 10.0 : 0.0) + 1.0 / (1.0 + i + j);
  auto map = rcp(new Map(n, 0, selfComm()));
  auto Km = rcp(new CrsMatrix(map, n));
  for (LO i = 0; i < n; ++i) {
    std::vector<GO> cols(n);
    for (LO j = 0; j < n; ++j) cols[j] = j;
    Km->insertGlobalValues(i, Teuchos::ArrayView<const GO>(cols), Teuchos::ArrayView<const double>(&K[i * n], n));
  }
  Km->fillComplete();
  // Dense T from its columns T e_a.
  std::vector<double> Td(n * n);
  for (LO a = 0; a < n; ++a) {
    std::vector<double> e(n, 0.0);
    e[a] = 1.0;
    T.displacementToOld(e);
    for (LO i = 0; i < n; ++i) Td[i * n + a] = e[i];
  }
  // T^{-1} T = I.
  std::vector<double> x(n);
  for (LO i = 0; i < n; ++i) x[i] = std::sin(1.0 + i);
  std::vector<double> y(x);
  T.displacementToOld(y);
  T.displacementToNew(y);
  for (LO i = 0; i < n; ++i) EXPECT_NEAR(y[i], x[i], ddc::test::kRoundoff);
  // û_R holds the constraint values c_j^T u.
  std::vector<double> u(x), uh(x);
  T.displacementToNew(uh);
  std::vector<double> values;
  for (const auto& g : groups)
    for (const auto& row : g.rows) {
      double v = 0.0;
      for (size_t q = 0; q < g.dofs.size(); ++q) v += row[q] * u[g.dofs[q]];
      values.push_back(v);
    }
  std::vector<double> held;
  for (LO i = 0; i < n; ++i)
    if (T.holdsConstraint(i)) held.push_back(uh[i]);
  ASSERT_EQ(held.size(), 3u);
  for (double v : values)
    EXPECT_TRUE(std::any_of(held.begin(), held.end(), [&](double h) { return std::abs(h - v) < 1e-12; }))
        << "constraint value " << v << " not held by any representative DOF";
  // K̂ = T^T K T.
  auto Khat = T.setPattern(*Km);
  CrsMatrix::local_inds_host_view_type inds;
  CrsMatrix::values_host_view_type vals;
  std::vector<double> KhatD(n * n, 0.0);
  for (LO r = 0; r < n; ++r) {
    Khat->getLocalRowView(r, inds, vals);
    for (size_t e = 0; e < inds.extent(0); ++e) KhatD[r * n + Khat->getColMap()->getGlobalElement(inds(e))] += vals(e);
  }
  for (LO a = 0; a < n; ++a)
    for (LO b = 0; b < n; ++b) {
      double v = 0.0;
      for (LO i = 0; i < n; ++i)
        for (LO j = 0; j < n; ++j) v += Td[i * n + a] * K[i * n + j] * Td[j * n + b];
      EXPECT_NEAR(KhatD[a * n + b], v, 1e-12 * 20.0) << "K^(" << a << ", " << b << ")";
    }
  // f̂ = T^T f and rows c^T T.
  std::vector<double> f(x);
  T.forceToNew(f);
  for (LO a = 0; a < n; ++a) {
    double v = 0.0;
    for (LO i = 0; i < n; ++i) v += Td[i * n + a] * x[i];
    EXPECT_NEAR(f[a], v, ddc::test::kRoundoff);
  }
  const auto row = T.rowToNew({{3, 2.0}, {0, -1.0}});
  std::vector<double> rowD(n, 0.0);
  for (const auto& [a, v] : row) rowD[a] = v;
  for (LO a = 0; a < n; ++a) EXPECT_NEAR(rowD[a], 2.0 * Td[3 * n + a] - Td[0 * n + a], ddc::test::kRoundoff);
  // Dependent rows are rejected.
  std::vector<ddc::PrimalGroup> bad(1);
  bad[0].dofs = {0, 1};
  bad[0].rows = {{0.5, 0.5}, {1.0, 1.0}};
  expectThrowWith<std::invalid_argument>([&] { ddc::ChangeOfBasis(n, bad); }, {"linearly dependent"});
}

TEST(FetiDp, EdgeConstraintCounts) {
  // 3x3 elasticity, H = 4: 12 subdomain-subdomain edges, each with the two
  // component averages and (with coordinates) one rotation; 10 vertex nodes.
  Spec s;
  s.Sx = 3, s.Sy = 3, s.H = 4, s.dpn = 2;
  Problem pb(s);
  for (bool rotations : {false, true}) {
    auto params = fetiParams("Dirichlet", "Multiplicity", "CG", ddc::test::kTightBelos, "Vertices and Edges");
    params.set("Rotational Constraints", rotations);
    FetiDpSolver feti(worldComm(), params, "FETI-DP");
    feti.setTopology(pb.subdomains(), pb.ownedMap());
    const GO perEdge = rotations ? 3 : 2;
    EXPECT_EQ(feti.numEdgeFaceConstraints(), 12 * perEdge);
    EXPECT_EQ(feti.primalMap()->getGlobalNumElements(), size_t(10 * 2 + 12 * perEdge));
  }
  // "Vertices, Edges and Faces" is the same in 2-D.
  auto params = fetiParams("Dirichlet", "Multiplicity", "CG", ddc::test::kTightBelos, "Vertices, Edges and Faces");
  FetiDpSolver feti(worldComm(), params, "FETI-DP");
  feti.setTopology(pb.subdomains(), pb.ownedMap());
  EXPECT_EQ(feti.numEdgeFaceConstraints(), 12 * 3);
}

TEST(FetiDp, EdgeRotationsFixAFloatingSubdomain) {
  // Elasticity 2x1 without any vertex: the edge's two averages leave
  // subdomain 1 its rotation (singular), its rotation constraint removes it.
  Spec s;
  s.Sx = 2, s.Sy = 1, s.H = 4, s.dpn = 2, s.primal = false;
  auto p = fetiParams("Dirichlet", "Multiplicity", "CG", ddc::test::kTightBelos, "Vertices and Edges");
  p.set("Rotational Constraints", false);
  expectThrowWith<ddc::SolverError>([&] { runFeti(s, p, false); }, {"subdomain 1", "singular"});
  p.set("Rotational Constraints", true);
  const FetiRun r = runFeti(s, p);
  report("elasticity 2x1 no vertices, edge + rotation", r);
  EXPECT_LT(r.error, ddc::test::kFetiVsDirect);
}

// ---- mesh-free vertices ----------------------------------------------------------

/// findPrimalVertices() on the synthetic grid: from the DOFs, coordinates and
/// stiffness patterns alone it finds exactly the cross points (nodes of four
/// subdomains); the ends of interfaces on the boundary stay in their edges.
TEST(FetiDpPrimalVertices, FindsTheCrossPointsFromTheSharingAlone) {
  for (int S : {2, 3, 4}) {
    Spec s;
    s.Sx = S, s.Sy = S, s.H = 4, s.dpn = 2, s.blockwise = S == 4;
    Problem pb(s);
    const auto subs = pb.subdomains();
    const auto flags = ddc::findPrimalVertices(ddc::rawComm(*worldComm()), *pb.ownedMap(), subs, 2);
    ASSERT_EQ(flags.size(), subs.size());
    long found = 0;
    for (size_t ls = 0; ls < subs.size(); ++ls)
      for (size_t k = 0; k < subs[ls].dofs.size(); ++k) {
        const GO node = subs[ls].dofs[k] / 2;
        const int i = int(node % (S * s.H)) + 1, j = int(node / (S * s.H));
        const bool cross = i % s.H == 0 && j % s.H == 0 && pb.nodeCount(i, j) == 4;
        EXPECT_EQ(flags[ls][k] != 0, cross) << S << "x" << S << " subdomain " << subs[ls].id << " node (" << i << ", "
                                            << j << ")";
        found += flags[ls][k];
      }
    long total = 0;
    Teuchos::reduceAll(*worldComm(), Teuchos::REDUCE_SUM, found, Teuchos::outArg(total));
    EXPECT_GT(total, 0L) << "a copy of each cross-point DOF in each of its 4 subdomains";
  }
}

/// With those vertices and the default edge constraints (averages and
/// rotations) FETI-DP solves the problem like the direct solver, floating
/// subdomains included: a host needs no mesh to choose its primal DOFs.
TEST(FetiDpPrimalVertices, MeshFreeVerticesWithEdgesMatchTheDirectSolve) {
  Spec s;
  s.Sx = 3, s.Sy = 3, s.H = 4, s.dpn = 2;
  Problem pb(s);
  auto subs = pb.subdomains();
  const auto flags = ddc::findPrimalVertices(ddc::rawComm(*worldComm()), *pb.ownedMap(), subs, 2);
  for (size_t ls = 0; ls < subs.size(); ++ls) subs[ls].primal = flags[ls];
  auto p = fetiParams("Dirichlet", "Multiplicity", "CG", ddc::test::kTightBelos, "Vertices, Edges and Faces");
  FetiDpSolver feti(worldComm(), p, "FETI-DP");
  feti.setTopology(subs, pb.ownedMap());
  feti.numeric();
  auto b = pb.load();
  Vector u(pb.ownedMap());
  FetiRun r;
  r.info = feti.solve(*b, u);
  r.error = relDiff(u, *directSolve(pb, *b));
  report("elasticity 3x3 mesh-free vertices + edges", r);
  EXPECT_LT(r.error, ddc::test::kFetiVsDirect);
}

TEST(FetiDpPrimalVertices, InputIsChecked) {
  Spec s;
  Problem pb(s);
  auto subs = pb.subdomains();
  for (auto& sd : subs) sd.coordinates.clear();
  expectThrowWith<std::invalid_argument>(
      [&] { ddc::findPrimalVertices(ddc::rawComm(*worldComm()), *pb.ownedMap(), subs, 2); },
      {"coordinates per DOF needed"});
  expectThrowWith<std::invalid_argument>(
      [&] { ddc::findPrimalVertices(ddc::rawComm(*worldComm()), *pb.ownedMap(), pb.subdomains(), 4); },
      {"spatial dimension 4"});
}

// ---- iteration counts --------------------------------------------------------

TEST(FetiDp, IterationCountsBoundedAtFixedHOverh) {
  // Elasticity, H/h = 16, CG to 1e-8; table of Dirichlet vs lumped,
  // multiplicity vs stiffness scaling, homogeneous and checkerboard (E 1 :
  // 1000) coefficients.
  struct Row {
    std::string prec, scaling;
    bool jump;
    int it[2];
  };
  std::vector<Row> rows;
  for (bool jump : {false, true})
    for (const std::string prec : {"Dirichlet", "Lumped"})
      for (const std::string scaling : {"Multiplicity", "Stiffness"}) rows.push_back(Row{prec, scaling, jump, {0, 0}});
  const int sizes[2] = {4, 8};
  for (auto& row : rows)
    for (int k = 0; k < 2; ++k) {
      Spec s;
      s.Sx = s.Sy = sizes[k];
      s.H = 16;
      s.dpn = 2;
      if (row.jump) s.coef = [](int a, int b) { return (a + b) % 2 ? 1000.0 : 1.0; };
      const FetiRun r = runFeti(s, fetiParams(row.prec, row.scaling, "CG", ddc::test::kCountBelos), false);
      row.it[k] = r.info.iterations;
      if (worldRank() == 0 && !row.jump && row.prec == "Dirichlet" && row.scaling == "Multiplicity")
        std::printf(
            "[ feti-dp  ] %dx%d timings (s, max over ranks): setup %.3f (local factor %.3f, Dirichlet %.3f, coarse "
            "%.3f), solve %.3f (Belos %.3f, local solves %.3f, coarse solves %.3f, preconditioner %.3f), %d F "
            "applications\n",
            sizes[k], sizes[k], r.info.setupSeconds, r.info.localFactorSeconds, r.info.dirichletFactorSeconds,
            r.info.coarseFactorSeconds, r.info.solveSeconds, r.info.belosSeconds, r.info.localSolveSeconds,
            r.info.coarseSolveSeconds, r.info.preconditionerSeconds, r.info.operatorApplications);
    }
  if (worldRank() == 0) {
    std::printf("[ feti-dp  ] CG iterations to 1e-8, elasticity, H/h = 16, %d rank(s)\n", worldSize());
    std::printf("[ feti-dp  ] %-12s %-10s %-13s %5s %5s\n", "coefficient", "precond", "scaling", "4x4", "8x8");
    for (const auto& row : rows)
      std::printf("[ feti-dp  ] %-12s %-10s %-13s %5d %5d\n", row.jump ? "checker 1e3" : "homogeneous",
                  row.prec.c_str(), row.scaling.c_str(), row.it[0], row.it[1]);
  }
  const Row& d = rows[0];  // homogeneous, Dirichlet, multiplicity
  EXPECT_LE(d.it[0], ddc::test::kMaxDirichletIterations);
  EXPECT_LE(d.it[1], ddc::test::kMaxDirichletIterations);
  EXPECT_LT(double(d.it[1] - d.it[0]) / d.it[0], ddc::test::kMaxGrowth)
      << "Dirichlet CG iterations grew from " << d.it[0] << " (4x4) to " << d.it[1] << " (8x8)";
}

// ---- BDDC -----------------------------------------------------------------------

/// BDDC and FETI-DP with the same primal space and scaling have the same
/// spectrum but for eigenvalues 1 (Mandel, Dohrmann & Tezaur 2005); they
/// stop on different residuals (the interface forces against the jumps), so
/// their CG iteration counts may differ by a few, not by a factor.
constexpr int kBddcExtraIterations = 3;

/// BDDC ("Method" = BDDC) against the direct solve and FETI-DP's iteration
/// count, on layouts with floating subdomains and several subdomains per
/// rank; with CHOLMOD (K_rr and Phi) and MUMPS (Schur rows) as local solver.
TEST(FetiDpBddc, MatchesDirectSolveInFetiDpsIterations) {
  for (const Layout L : {Layout{1, 1, 2, false}, Layout{2, 1, 1, false}, Layout{3, 3, 1, false}, Layout{4, 4, 1, true},
                         Layout{3, 3, 2, true}, Layout{4, 4, 2, false}})
    for (const char* local : {"CHOLMOD", "MUMPS"}) {
      Spec s;
      s.Sx = L.Sx, s.Sy = L.Sy, s.dpn = L.dpn, s.H = 4, s.blockwise = L.blockwise;
      auto p = fetiParams();
      p.sublist("Local Solver").set("Type", std::string(local));
      const FetiRun feti = runFeti(s, p, false);
      p.set("Method", std::string("BDDC"));
      const FetiRun bddc = runFeti(s, p);
      char name[96];
      std::snprintf(name, sizeof name, "BDDC %s %dx%d %s, %s local (FETI-DP: %d it)",
                    L.dpn == 1 ? "Laplace" : "elasticity", L.Sx, L.Sy, L.blockwise ? "blockwise" : "round-robin",
                    local, feti.info.iterations);
      report(name, bddc);
      EXPECT_LT(bddc.error, ddc::test::kFetiVsDirect) << name;
      EXPECT_LE(bddc.info.relativeResidual, ddc::test::kTightBelos) << name;
      EXPECT_LE(bddc.info.iterations, feti.info.iterations + kBddcExtraIterations) << name;
      EXPECT_GE(bddc.info.iterations, feti.info.iterations - kBddcExtraIterations) << name;
      if (L.Sx * L.Sy == 1) EXPECT_EQ(bddc.info.iterations, 0) << name;  // no interface
    }
}

/// BDDC's coarse solve is in its preconditioner: by default single
/// precision (MUMPS "Precision" = Single), which must leave the answer and,
/// up to one, the iterations of the double-precision coarse solve.
TEST(FetiDpBddc, SinglePrecisionCoarseSolveKeepsAnswerAndIterations) {
  for (const Layout L : {Layout{4, 4, 1, true}, Layout{4, 4, 2, false}}) {
    Spec s;
    s.Sx = L.Sx, s.Sy = L.Sy, s.dpn = L.dpn, s.H = 4, s.blockwise = L.blockwise;
    auto p = fetiParams();
    p.set("Method", std::string("BDDC"));
    p.sublist("Coarse Solver").sublist("MUMPS").set("Precision", std::string("Double"));
    const FetiRun dbl = runFeti(s, p, false);
    p.sublist("Coarse Solver").sublist("MUMPS").remove("Precision");
    const FetiRun single = runFeti(s, p);
    {
      auto filled = p;  // the constructor fills in the defaults it chose
      FetiDpSolver feti(worldComm(), filled, "FETI-DP");
      EXPECT_EQ(filled.sublist("Coarse Solver").sublist("MUMPS").get<std::string>("Precision"), "Single");
    }
    report("BDDC single-precision coarse solve", single);
    EXPECT_LT(single.error, ddc::test::kFetiVsDirect);
    EXPECT_LE(std::abs(single.info.iterations - dbl.info.iterations), 1);
  }
}

/// "Method" = Automatic is FETI-DP unless the caller selects BDDC before
/// setTopology() (the app does on many subdomains without contact); then it
/// is the run an explicit BDDC makes. Options BDDC cannot honour keep
/// FETI-DP, and an explicit Method is kept.
TEST(FetiDpBddc, AutomaticMethodIsBddcOnlyWhereTheCallerAndOptionsAllow) {
  Spec s;
  s.Sx = 3, s.Sy = 3, s.dpn = 2, s.H = 4, s.blockwise = true;
  auto p = fetiParams();
  ASSERT_EQ(p.get<std::string>("Method", "Automatic"), "Automatic");
  bool fetiUsed = true;
  const FetiRun feti = runFeti(s, p, false, [&](FetiDpSolver& f) { fetiUsed = !f.usesBddc(); });
  EXPECT_TRUE(fetiUsed) << "Automatic without the caller's choice is FETI-DP";
  bool chose = false;
  const FetiRun automatic = runFeti(s, p, true, [&](FetiDpSolver& f) { chose = f.setAutomaticMethod(true); });
  auto q = p;
  q.set("Method", std::string("BDDC"));
  const FetiRun bddc = runFeti(s, q, false);
  report("Automatic, BDDC selected", automatic);
  EXPECT_TRUE(chose);
  EXPECT_LT(automatic.error, ddc::test::kFetiVsDirect);
  EXPECT_EQ(automatic.info.iterations, bddc.info.iterations) << "FETI-DP took " << feti.info.iterations;
  EXPECT_EQ(automatic.info.operatorApplications, bddc.info.operatorApplications);

  const std::pair<const char*, const char*> keepFeti[] = {
      {"Scaling", "Stiffness"}, {"Preconditioner", "Lumped"}, {"Primal Constraints", "Vertices and Edges"},
      {"Method", "FETI-DP"}};
  for (const auto& [name, value] : keepFeti) {
    auto r = p;
    r.set(name, std::string(value));
    FetiDpSolver f(worldComm(), r, "FETI-DP");
    EXPECT_FALSE(f.setAutomaticMethod(true)) << name << " = " << value;
    EXPECT_FALSE(f.usesBddc()) << name << " = " << value;
  }
  {
    FetiDpSolver f(worldComm(), q, "FETI-DP");
    EXPECT_TRUE(f.setAutomaticMethod(false)) << "an explicit BDDC is kept";
  }
  Problem pb(s);
  FetiDpSolver f(worldComm(), p, "FETI-DP");
  f.setTopology(pb.subdomains(), pb.ownedMap());
  EXPECT_THROW(f.setAutomaticMethod(true), std::logic_error);
}

/// BDDC iterates on the caller's DOFs with vertices and weights 1/m: the
/// options it cannot honour, extra rows and DOFs marked for them are
/// refused by name.
TEST(FetiDpErrors, BddcRefusesWhatItCannotHonour) {
  const std::pair<const char*, const char*> bad[] = {
      {"Preconditioner", "Lumped"}, {"Scaling", "Stiffness"}, {"Primal Constraints", "Vertices and Edges"}};
  for (const auto& [name, value] : bad) {
    auto p = fetiParams();
    p.set("Method", std::string("BDDC"));
    p.set(name, std::string(value));
    expectThrowWith<ddc::InputError>([&] { FetiDpSolver f(worldComm(), p, "Solver/FETI-DP"); },
                                     {std::string("Solver/FETI-DP/") + name, value, "Solver/FETI-DP/Method", "BDDC"});
  }
  {
    // FETI-DP's coarse solve is inside F: single precision is refused.
    auto p = fetiParams();
    p.sublist("Coarse Solver").sublist("MUMPS").set("Precision", std::string("Single"));
    expectThrowWith<ddc::InputError>([&] { FetiDpSolver f(worldComm(), p, "Solver/FETI-DP"); },
                                     {"Solver/FETI-DP/Coarse Solver/MUMPS/Precision", "Single",
                                      "Solver/FETI-DP/Method", "BDDC"});
  }
  Spec s;
  s.Sx = 2, s.Sy = 1, s.H = 2, s.dpn = 1;
  Problem pb(s);
  auto p = fetiParams();
  p.set("Method", std::string("BDDC"));
  {
    FetiDpSolver feti(worldComm(), p, "Solver/FETI-DP");
    auto subs = pb.subdomains();
    feti.setTopology(subs, pb.ownedMap());
    auto rowMap = rcp(new Map(1, 0, worldComm()));
    std::vector<std::vector<ddc::ConstraintEntry>> rows(subs.size());
    expectThrowWith<ddc::InputError>([&] { feti.setConstraintRows(rowMap, rows); },
                                     {"Solver/FETI-DP/Method", "BDDC", "extra rows"});
  }
  {
    FetiDpSolver feti(worldComm(), p, "Solver/FETI-DP");
    auto subs = pb.subdomains();
    for (auto& sub : subs) sub.constrainable.assign(sub.dofs.size(), 1);
    expectThrowWith<ddc::InputError>([&] { feti.setTopology(subs, pb.ownedMap()); },
                                     {"Solver/FETI-DP/Method", "BDDC", "extra rows"});
  }
}

// ---- errors -------------------------------------------------------------------

TEST(FetiDpErrors, UnknownBelosSolverNamesThePath) {
  auto p = fetiParams("Dirichlet", "Multiplicity", "BiCGStab");
  expectThrowWith<ddc::InputError>([&] { FetiDpSolver f(worldComm(), p, "Solver/FETI-DP"); },
                                   {"Solver/FETI-DP/Belos/Solver Type", "BiCGStab", "CG"});
}

TEST(FetiDpErrors, MisspeltParametersNameThePath) {
  {
    Teuchos::ParameterList p;
    p.set("Preconditoner", std::string("Dirichlet"));
    expectThrowWith<ddc::InputError>([&] { FetiDpSolver f(worldComm(), p, "Solver/FETI-DP"); },
                                     {"Solver/FETI-DP/Preconditoner", "Preconditioner"});
  }
  {
    Teuchos::ParameterList p;
    p.sublist("Belos").set("Maximum Iteration", 10);
    expectThrowWith<ddc::InputError>([&] { FetiDpSolver f(worldComm(), p, "Solver/FETI-DP"); },
                                     {"Solver/FETI-DP/Belos/Maximum Iteration"});
  }
  {
    Teuchos::ParameterList p;
    p.set("Scaling", std::string("Rho"));
    expectThrowWith<ddc::InputError>([&] { FetiDpSolver f(worldComm(), p, "Solver/FETI-DP"); },
                                     {"Solver/FETI-DP/Scaling", "Rho"});
  }
  {
    Teuchos::ParameterList p;
    p.sublist("Local Solver").set("Type", std::string("SuperLU"));
    expectThrowWith<ddc::InputError>([&] { FetiDpSolver f(worldComm(), p, "Solver/FETI-DP"); },
                                     {"Solver/FETI-DP/Local Solver/Type", "SuperLU"});
  }
  {
    Teuchos::ParameterList p;
    p.sublist("Coarse Solver").sublist("MUMPS").set("Orderin", std::string("AMD"));
    expectThrowWith<ddc::InputError>([&] { FetiDpSolver f(worldComm(), p, "Solver/FETI-DP"); },
                                     {"Solver/FETI-DP/Coarse Solver/MUMPS/Orderin"});
  }
  // Defaults are filled in and documented.
  Teuchos::ParameterList p;
  FetiDpSolver f(worldComm(), p, "FETI-DP");
  EXPECT_EQ(p.get<std::string>("Preconditioner"), "Dirichlet");
  EXPECT_EQ(p.get<std::string>("Scaling"), "Automatic");
  EXPECT_EQ(p.get<std::string>("Primal Constraints"), "Automatic");
  EXPECT_EQ(f.convergenceTolerance(), 1e-10);
  EXPECT_NO_THROW(f.setSolveTolerance(1e-3));
  EXPECT_THROW(f.setSolveTolerance(1.0), std::invalid_argument);
  EXPECT_THROW(f.setSolveTolerance(1e-11), std::invalid_argument);
  EXPECT_TRUE(p.get<bool>("Rotational Constraints"));
  EXPECT_EQ(p.sublist("Belos").get<std::string>("Solver Type"), "CG");
  EXPECT_EQ(p.sublist("Belos").get<int>("Maximum Iterations"), 500);
  EXPECT_EQ(p.sublist("Local Solver").get<std::string>("Type"), "CHOLMOD");
  EXPECT_EQ(p.sublist("Coarse Solver").get<std::string>("Type"), "MUMPS");
  for (auto it = FetiDpSolver::getValidParameters()->begin(); it != FetiDpSolver::getValidParameters()->end(); ++it)
    EXPECT_FALSE(FetiDpSolver::getValidParameters()->entry(it).docString().empty())
        << FetiDpSolver::getValidParameters()->name(it);
}

TEST(FetiDpErrors, PrimalConstraintInputIsChecked) {
  {
    auto p = fetiParams("Dirichlet", "Multiplicity", "CG", ddc::test::kTightBelos, "Edges");
    expectThrowWith<ddc::InputError>([&] { FetiDpSolver f(worldComm(), p, "Solver/FETI-DP"); },
                                     {"Solver/FETI-DP/Primal Constraints", "Edges", "Vertices and Edges"});
  }
  Spec s;
  s.Sx = 2, s.Sy = 2, s.H = 2, s.dpn = 2;
  Problem pb(s);
  {
    // No dimension / components: the solver cannot tell edges from faces.
    auto subs = pb.subdomains();
    for (auto& sd : subs) sd.dim = 0, sd.component.clear();
    auto p = fetiParams("Dirichlet", "Multiplicity", "CG", ddc::test::kTightBelos, "Vertices and Edges");
    FetiDpSolver feti(worldComm(), p, "Solver/FETI-DP");
    expectThrowWith<std::invalid_argument>([&] { feti.setTopology(subs, pb.ownedMap()); },
                                           {"Solver/FETI-DP/Primal Constraints", "FetiSubdomain::dim", "Vertices"});
  }
  {
    // Rotations without coordinates.
    auto subs = pb.subdomains();
    for (auto& sd : subs) sd.coordinates.clear();
    auto p = fetiParams("Dirichlet", "Multiplicity", "CG", ddc::test::kTightBelos, "Vertices and Edges");
    FetiDpSolver feti(worldComm(), p, "Solver/FETI-DP");
    expectThrowWith<std::invalid_argument>([&] { feti.setTopology(subs, pb.ownedMap()); },
                                           {"Solver/FETI-DP/Rotational Constraints", "FetiSubdomain::coordinates"});
  }
}

TEST(FetiDp, OtherBelosParametersArePassedThrough) {
  Spec s;
  s.Sx = 3, s.Sy = 3, s.dpn = 2, s.H = 4;
  auto p = fetiParams("Dirichlet", "Multiplicity", "GMRES");
  p.sublist("Belos").set("Num Blocks", 7);
  p.sublist("Belos").set("Orthogonalization", std::string("ICGS"));
  const FetiRun r = runFeti(s, p);
  report("elasticity 3x3 GMRES(7), ICGS", r);
  EXPECT_LT(r.error, ddc::test::kFetiVsDirect);
  EXPECT_EQ(p.sublist("Belos").get<int>("Num Blocks"), 7);
}

TEST(FetiDpErrors, BelosParametersAreValidatedAgainstTheChosenSolver) {
  {
    // CG has no restart length.
    auto p = fetiParams("Dirichlet", "Multiplicity", "CG");
    p.sublist("Belos").set("Num Blocks", 7);
    expectThrowWith<ddc::InputError>([&] { FetiDpSolver f(worldComm(), p, "Solver/FETI-DP"); },
                                     {"Solver/FETI-DP/Belos/Num Blocks", "CG", "Convergence Tolerance"});
  }
  {
    auto p = fetiParams("Dirichlet", "Multiplicity", "GMRES");
    p.sublist("Belos").set("Num Blocks", std::string("7"));
    expectThrowWith<ddc::InputError>([&] { FetiDpSolver f(worldComm(), p, "Solver/FETI-DP"); },
                                     {"Solver/FETI-DP/Belos/Num Blocks", "must be of type int"});
  }
}

/// 2x1 without primal DOFs: subdomain 1 floats freely (its K_rr is the
/// singular Neumann matrix). With 2 ranks it lives on rank 1, and rank 0
/// must raise the same error. `localSolver`: the Local Solver's Type, or ""
/// for the default (CHOLMOD, whose Cholesky factorisation either breaks on
/// a pivot <= 0, then MUMPS, the fallback, finds the matrix singular, or
/// factorises with a tiny positive pivot, which FETI-DP's condition
/// estimate reports); either way the same error naming the subdomain.
void checkSingularSubdomain(const std::string& localSolver) {
  for (int dpn : {1, 2}) {
    Spec s;
    s.Sx = 2, s.Sy = 1, s.H = 4, s.dpn = dpn, s.primal = false;
    Problem pb(s);
    auto params = fetiParams();
    if (!localSolver.empty()) params.sublist("Local Solver").set("Type", localSolver);
    FetiDpSolver feti(worldComm(), params, "FETI-DP");
    feti.setTopology(pb.subdomains(), pb.ownedMap());
    try {
      feti.numeric();
      ADD_FAILURE() << "singular subdomain not detected";
    } catch (const ddc::SolverError& e) {
      const std::string what = e.what();
      if (worldRank() == 0)
        std::printf("[ feti-dp  ] %s, dpn %d: %s\n", localSolver.empty() ? "default" : localSolver.c_str(), dpn,
                    what.c_str());
      for (const std::string n : {"subdomain 1", "the corner rule could not fix this subdomain's rigid modes"})
        EXPECT_NE(what.find(n), std::string::npos) << "'" << n << "' not in: " << what;
    }
  }
}

TEST(FetiDpErrors, SingularSubdomainNamesIt) { checkSingularSubdomain(""); }

TEST(FetiDpErrors, SingularSubdomainWithMumps) { checkSingularSubdomain("MUMPS"); }

TEST(FetiDpErrors, OnePrimalNodeLeavesARotation) {
  // Elasticity 2x1 with only the lower end (H, 0) of the interface primal:
  // subdomain 1 keeps its rotation about that node.
  Spec s;
  s.Sx = 2, s.Sy = 1, s.H = 4, s.dpn = 2;
  s.keepPrimal = [](int, int j) { return j == 0; };
  Problem pb(s);
  auto params = fetiParams();
  FetiDpSolver feti(worldComm(), params, "FETI-DP");
  feti.setTopology(pb.subdomains(), pb.ownedMap());
  EXPECT_EQ(feti.primalMap()->getGlobalNumElements(), 2u);
  expectThrowWith<ddc::SolverError>([&] { feti.numeric(); }, {"subdomain 1", "corner rule"});
}

TEST(FetiDpErrors, BelosNonConvergenceIsReported) {
  Spec s;
  s.Sx = 3, s.Sy = 3, s.H = 4, s.dpn = 2;
  auto p = fetiParams("None");
  p.sublist("Belos").set("Maximum Iterations", 2);
  expectThrowWith<ddc::SolverError>([&] { runFeti(s, p, false); },
                                    {"did not converge", "2 iterations", "FETI-DP/Belos/Maximum Iterations"});
}

TEST(FetiDpErrors, LoadOnDofInNoSubdomain) {
  Spec s;
  s.Sx = 2, s.Sy = 1, s.H = 2, s.extraDof = true;
  Problem pb(s);
  auto params = fetiParams();
  FetiDpSolver feti(worldComm(), params, "FETI-DP");
  feti.setTopology(pb.subdomains(), pb.ownedMap());
  feti.numeric();
  auto b = pb.load();
  Vector u(pb.ownedMap());
  feti.solve(*b, u);  // zero there: fine, and u = 0 there
  const GO last = GO(pb.ownedMap()->getGlobalNumElements()) - 1;
  if (pb.ownedMap()->isNodeGlobalElement(last)) {
    EXPECT_EQ(u.getData()[pb.ownedMap()->getLocalElement(last)], 0.0);
    b->replaceGlobalValue(last, 1.0);
  }
  expectThrowWith<std::invalid_argument>([&] { feti.solve(*b, u); }, {"belongs to no subdomain"});
}

TEST(FetiDpErrors, InconsistentPrimalFlagsAreRejected) {
  Spec s;
  s.Sx = 2, s.Sy = 1, s.H = 2;
  Problem pb(s);
  auto subs = pb.subdomains();
  // Subdomain 0 marks its first shared DOF primal, subdomain 1 does not.
  for (auto& sd : subs)
    if (sd.id == 0)
      for (size_t k = 0; k < sd.dofs.size(); ++k)
        if (!sd.primal[k] && pb.nodeCount(int(sd.dofs[k] % (2 * s.H)) + 1, int(sd.dofs[k] / (2 * s.H))) == 2) {
          sd.primal[k] = 1;
          break;
        }
  auto params = fetiParams();
  FetiDpSolver feti(worldComm(), params, "FETI-DP");
  expectThrowWith<std::invalid_argument>([&] { feti.setTopology(subs, pb.ownedMap()); }, {"primal in 1 of the 2"});
}

}  // namespace
