// FETI-DP acceptance tests at the analysis level (doc/feti-dp.md; rung 3 of
// doc/verification.md), on meshes, partitions and corner selection
// made by the analysis (the algebra alone is tested in
// packages/feti/test/DDC_FetiDpTest.cpp):
//   a. linear elasticity: FETI-DP = monolithic direct (MUMPS) to 1e-8, for
//      1, 2, 4, 9, 16 METIS subdomains, Box Grid partitions, floating
//      subdomains (a statically determinate support; an island subdomain that
//      needs the extra-corner rule), more subdomains than ranks;
//   b. neo-Hookean arch with large rotations: same Newton iteration counts per
//      step and the same strain energies;
//   c. iteration bounds at fixed H/h (Box Grid 4x4 and 8x8, H/h = 16) and a
//      table over subdomains x H/h x preconditioner (DDC_SKIP_TABLES=1 skips it);
//   d. a floating subdomain the corner rule cannot fix is an InputError
//      naming the subdomain and its body.
//
// Two levels of comparison, because the Newton loop hides the accuracy of
// one linear solve: whatever error a FETI-DP solve leaves is corrected by the
// next Newton iteration (the residual is assembled exactly), so equal final
// displacements alone would not catch an inaccurate FETI-DP solve. Hence
//   - "first solve": the first Newton system K du = -r(0) of the model, built
//     exactly as ddc::Analysis builds it (selectPrimalNodes,
//     buildSubdomainSystems, Model::assemble into the subdomain matrices) and
//     solved once by FetiDpSolver and once by MUMPS on the assembled K;
//     this is also where the dual iteration count of ONE solve is read:
//     StepRecord::dualIterations sums over the Newton iterations of a step and
//     a linear step always takes 2 (the convergence check needs it > 0);
//   - "analysis": whole runs with Solver/Strategy = FETI-DP and Monolithic with
//     the SAME Partition parameters. The DOF numbering (Model: a node belongs
//     to the lowest rank among its elements' subdomain owners) depends only on
//     the partition and the rank count, so both runs have the same owned
//     map; the test checks Map::isSameAs and compares the owned vectors
//     directly, and also node by node after a gather.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>
#include <Tpetra_Core.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <string>
#include <vector>

#include "DDC_Analysis.hpp"
#include "DDC_Error.hpp"
#include "DDC_FetiPrimalVertices.hpp"
#include "DDC_MpiRecords.hpp"
#include "DDC_Substructuring.hpp"
#include "DDC_AnalysisTestDecks.hpp"
#include "DDC_FetiTolerances.hpp"
#include "DDC_TestTolerances.hpp"

namespace {

using PL = Teuchos::ParameterList;
using Comm = Teuchos::RCP<const Teuchos::Comm<int>>;
using ddc::test::relDiff;
using namespace ddc::test;  // deck builders, communicators (DDC_AnalysisTestDecks.hpp)

// ---------------------------------------------------------------------------
// Named tolerances of this file (see also DDC_FetiTolerances.hpp and
// DDC_TestTolerances.hpp).

/// Relative residual ||K u_D - b|| / ||b|| of the MUMPS reference solve: a
/// backward-stable direct solve gives O(eps ||K|| ||u|| / ||b||), measured
/// 1e-14 .. 3e-13 here; 1e-10 keeps the reference 100x more accurate than
/// kFetiVsDirect requires of FETI-DP.
constexpr double kDirectResidual = 1e-10;

/// Strain energies of FETI-DP and Monolithic runs (1e-8 relative, doc/verification.md rung 3).
/// Both Newton loops converge to the same discrete solution; the difference
/// is the last Newton correction's solver error, squared in the energy.
constexpr double kEnergy = 1e-8;

// ---------------------------------------------------------------------------
// Helpers.

int worldSize() { return worldComm()->getSize(); }

/// A Quad4 rectangle body [x0, x0 + lx] x [y0, y0 + ly], E = 1000, nu = 0.3.
void addBlock(PL& deck, const std::string& name, double x0, double y0, double lx, double ly, int nx, int ny,
              const std::string& material) {
  RectangleSpec r;
  r.originX = x0, r.originY = y0, r.lengthX = lx, r.lengthY = ly, r.nx = nx, r.ny = ny;
  r.material = material;
  addRectangle(deck, name, r);
}

void quiet(PL& deck, int steps) { setRunOptions(deck, steps); }

/// How the block is held.
enum class Support {
  Clamped,     ///< whole left edge, both components (examples/elastic_block.xml)
  Determinate  ///< pin at the bottom-left corner, x-roller at the top-left corner:
               ///< every subdomain not touching these two nodes floats
};

/// Linear elastic block clamped / pinned on the left, traction (10, -1) on the
/// right: the shape of examples/elastic_block.xml.
PL blockDeck(double lx, double ly, int nx, int ny, Support support = Support::Clamped,
             const std::string& material = "Linear Elastic", int steps = 1) {
  PL deck("DDContact");
  addBlock(deck, "Block", 0.0, 0.0, lx, ly, nx, ny, material);
  if (support == Support::Clamped) {
    addDisplacement(deck, "Clamped", "Block/left", "XY");
  } else {
    addDisplacement(deck, "Pin", "Block/bottom left", "XY");
    addDisplacement(deck, "Roller", "Block/top left", "X");
  }
  addTraction(deck, "Load", "Block/right", 10.0, -1.0);
  quiet(deck, steps);
  return deck;
}

/// Partition parameters.
struct PartitionSpec {
  std::string method = "METIS";
  int subdomains = 0;  ///< METIS count (0: ranks)
  int bx = 2, by = 2, bz = 1;  ///< Box Grid
  std::string file;    ///< Element Map File
  std::string label() const {
    if (method == "Box Grid") return "BoxGrid" + std::to_string(bx) + "x" + std::to_string(by);
    if (method == "Element Map File") return "MapFile";
    if (method == "By Body") return "ByBody";
    return "METIS" + std::to_string(subdomains);
  }
};

void setPartition(PL& deck, const PartitionSpec& p) {
  PL& part = deck.sublist("Partition");
  part.set("Method", p.method);
  if (p.method == "METIS") part.set("Number of Subdomains", p.subdomains);
  if (p.method == "Box Grid") {
    part.set("Box Grid X", p.bx);
    part.set("Box Grid Y", p.by);
    if (p.bz != 1) part.set("Box Grid Z", p.bz);
  }
  if (p.method == "Element Map File") part.set("Element Map File", p.file);
}

/// The Solver/FETI-DP sublist.
PL fetiParams(double tol, const std::string& prec = "Dirichlet", const std::string& scaling = "Multiplicity",
              const std::string& krylov = "CG", const std::string& primal = "") {
  PL f("FETI-DP");
  if (!primal.empty()) f.set("Primal Constraints", primal);  // else the default
  f.set("Preconditioner", prec);
  f.set("Scaling", scaling);
  PL& b = f.sublist("Belos");
  b.set("Solver Type", krylov);
  b.set("Convergence Tolerance", tol);
  b.set("Maximum Iterations", 1000);
  return f;
}

/// The iteration studies of vertex-only FETI-DP (its bounds were set for
/// corners; the edge/face study is FetiIterations.PrimalChoices*).
PL vertexParams(double tol, const std::string& prec = "Dirichlet") {
  return fetiParams(tol, prec, "Multiplicity", "CG", "Vertices");
}

void useFeti(PL& deck, const PL& feti) {
  PL& s = deck.sublist("Solver");
  s.set("Strategy", std::string("FETI-DP"));
  s.set("FETI-DP", feti);
}

void useMonolithic(PL& deck) {
  PL& s = deck.sublist("Solver");
  s.set("Strategy", std::string("Monolithic"));
  s.sublist("Linear Solver").set("Type", std::string("MUMPS"));
}

/// ||a - b||_2 / ||b||_2 of two node-indexed fields.
double relErr(const std::vector<double>& a, const std::vector<double>& b) {
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    num += (a[i] - b[i]) * (a[i] - b[i]);
    den += b[i] * b[i];
  }
  return std::sqrt(num) / std::max(std::sqrt(den), 1e-300);
}

/// ||a - b||_2 / ||b||_2 of two vectors on the same map.
double relErr(const ddc::Vector& a, const ddc::Vector& b) {
  ddc::Vector d(a, Teuchos::Copy);
  d.update(-1.0, b, 1.0);
  return d.norm2() / std::max(b.norm2(), 1e-300);
}

// ---------------------------------------------------------------------------
// The first Newton system solved by FETI-DP and by MUMPS.

struct FirstSolve {
  ddc::FetiDpSolver::Info info;
  double error = 0.0;            ///< ||u_feti - u_direct|| / ||u_direct|| (owned layout)
  double directResidual = 0.0;   ///< ||K u_direct - b|| / ||b||: the reference is checked too
  size_t numPrimal = 0, numLm = 0;
  long long numDual = 0;
  long long numEdgeFace = 0;  ///< edge/face constraints among the primal DOFs
  int subdomains = 0;
  std::vector<std::string> primalReport;  ///< subdomains that needed extra corners
  double seconds = 0.0;
};

/// Build the model of `deck` (partition included), assemble K du = -r(0) at
/// u = 0, load factor 1 (for a linear problem: the whole solution), and solve
/// it by FETI-DP with `feti` and (if `direct`) by MUMPS.
/// With `meshFreeVertices`, the primal vertices come from
/// findPrimalVertices() (DOF sharing and stiffness patterns only) instead of
/// the analysis' corner rule.
FirstSolve firstSolve(PL deck, const PL& feti, bool direct = true, bool meshFreeVertices = false) {
  const auto t0 = std::chrono::steady_clock::now();
  useMonolithic(deck);  // the Analysis is only used to build and hold the model
  ddc::Analysis a(worldComm(), deck);
  const ddc::Model& model = a.model();
  FirstSolve out;
  out.subdomains = model.partition().numSubdomains;

  // Exactly what Analysis does for Solver/Strategy = FETI-DP.
  const auto primal = ddc::selectPrimalNodes(model, &out.primalReport);
  auto systems = ddc::buildSubdomainSystems(model, primal);
  ddc::SubdomainSink sink;
  sink.systems = &systems;
  sink.where.assign(model.mesh().numElements(), {-1, -1});
  std::vector<ddc::FetiSubdomain> fs;
  for (size_t i = 0; i < systems.size(); ++i) {
    for (size_t j = 0; j < systems[i].elements.size(); ++j)
      sink.where[systems[i].elements[j]] = {static_cast<int>(i), static_cast<int>(j)};
    fs.push_back({systems[i].id, systems[i].dofs, systems[i].primal, systems[i].K, {}, model.dim(),
                  systems[i].component, systems[i].coordinates});
  }
  if (meshFreeVertices) {
    const auto flags = ddc::findPrimalVertices(ddc::rawComm(*worldComm()), *model.ownedMap(), fs, model.dim());
    for (size_t i = 0; i < fs.size(); ++i) fs[i].primal = flags[i];
  }
  auto u0 = model.createVector();
  auto dp = model.createVector();
  model.prescribedIncrement(0.0, 1.0, *dp);
  auto r = model.createVector();
  ddc::AssemblyRequest request;
  request.residual = r.get();
  request.prescribedStep = dp.get();
  request.subdomains = &sink;
  model.assemble(*u0, 1.0, request);
  r->scale(-1.0);
  PL fp(feti);
  ddc::FetiDpSolver solver(worldComm(), fp, "Solver/FETI-DP");
  solver.setTopology(std::move(fs), model.ownedMap());
  solver.numeric();
  auto uf = model.createVector();
  out.info = solver.solve(*r, *uf);
  out.numPrimal = solver.primalMap()->getGlobalNumElements();
  out.numLm = solver.lmMap()->getGlobalNumElements();
  out.numDual = solver.numDualDofs();
  out.numEdgeFace = solver.numEdgeFaceConstraints();

  if (direct) {
    auto K = model.createMatrix();
    auto rd = model.createVector();
    ddc::AssemblyRequest direct;
    direct.residual = rd.get();
    direct.tangent = K.get();
    direct.prescribedStep = dp.get();
    model.assemble(*u0, 1.0, direct);
    rd->scale(-1.0);
    // The same right-hand side both ways (the sink path must not change r).
    EXPECT_LE(relErr(*rd, *r), ddc::test::kRoundoff) << "residual assembled with the subdomain sink differs";
    PL ls;
    ls.set("Type", std::string("MUMPS"));
    auto mumps = ddc::DirectSolverFactory::withBuiltins().create(ls, "test");
    mumps->symbolic(K);
    mumps->numeric();
    auto ud = model.createVector();
    mumps->solve(*rd, *ud);
    auto res = model.createVector();
    K->apply(*ud, *res);
    res->update(-1.0, *rd, 1.0);
    out.directResidual = res->norm2() / std::max(rd->norm2(), 1e-300);
    out.error = relErr(*uf, *ud);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

// ---------------------------------------------------------------------------
// a. Linear elasticity: FETI-DP = monolithic direct.

struct LinearCase {
  std::string name;
  PL deck;
  PartitionSpec part;
  int expectSubdomains;
  bool expectExtraCorners;  ///< the corner rule alone leaves a subdomain floating
};

/// 32 x 8 block of examples/elastic_block.xml (4 x 1).
PL elasticBlock(Support s = Support::Clamped) { return blockDeck(4.0, 1.0, 32, 8, s); }

std::vector<LinearCase> linearCases() {
  std::vector<LinearCase> v;
  auto metis = [](int n) {
    PartitionSpec p;
    p.subdomains = n;
    return p;
  };
  auto box = [](int x, int y) {
    PartitionSpec p;
    p.method = "Box Grid";
    p.bx = x, p.by = y;
    return p;
  };
  // METIS: irregular subdomains, 1 (no interface) ... 16.
  for (int n : {1, 2, 4, 9, 16}) v.push_back({"Clamped_" + metis(n).label(), elasticBlock(), metis(n), n, false});
  // Box Grid: regular strips and boxes. 4x1: subdomains 1..3 touch no
  // Dirichlet data (floating, fixed by the interface ends).
  v.push_back({"Clamped_BoxGrid4x1", elasticBlock(), box(4, 1), 4, false});
  v.push_back({"Clamped_BoxGrid3x3", elasticBlock(), box(3, 3), 9, false});
  v.push_back({"Clamped_BoxGrid8x2", elasticBlock(), box(8, 2), 16, false});
  // Statically determinate support: all subdomains but the one or two at
  // the left corners float.
  v.push_back({"Determinate_BoxGrid4x1", elasticBlock(Support::Determinate), box(4, 1), 4, false});
  v.push_back({"Determinate_METIS9", elasticBlock(Support::Determinate), metis(9), 9, false});
  v.push_back({"Determinate_METIS16", elasticBlock(Support::Determinate), metis(16), 16, false});
  // test/inputs/feti_island.map on a 12 x 12 unit square clamped on the
  // left: subdomain 1 is an island of 4 x 4 elements in the middle (its
  // interface is a closed loop with no cross point and no boundary node, so
  // rule 3 of selectPrimalNodes must add two corners), subdomain 2 the top
  // strip, subdomain 0 the rest.
  PartitionSpec island;
  island.method = "Element Map File";
  island.file = std::string(DDC_SOURCE_DIR) + "/test/inputs/feti_island.map";
  v.push_back({"Clamped_Island", blockDeck(1.0, 1.0, 12, 12), island, 3, true});
  return v;
}

void PrintTo(const LinearCase& c, std::ostream* os) { *os << c.name; }
void PrintTo(const PartitionSpec& p, std::ostream* os) { *os << p.label(); }

class FetiLinear : public testing::TestWithParam<LinearCase> {
 protected:
  void SetUp() override {
    // A rank without a subdomain is not allowed (Partition docs): the
    // 1-subdomain case runs on one rank only.
    if (GetParam().expectSubdomains < worldSize()) GTEST_SKIP() << "fewer subdomains than ranks";
  }
  PL deckFor(const LinearCase& c) {
    PL deck = c.deck;
    setPartition(deck, c.part);
    return deck;
  }
};

/// Every value of Solver/FETI-DP/Primal Constraints (doc/feti-dp.md).
const std::vector<std::string> kPrimalChoices = {"Vertices", "Vertices and Edges", "Vertices, Edges and Faces"};

TEST_P(FetiLinear, FirstSolveMatchesMumps) {
  const LinearCase& c = GetParam();
  for (const auto& primal : kPrimalChoices) {
  SCOPED_TRACE(primal);
  const auto s = firstSolve(deckFor(c), fetiParams(kTightBelos, "Dirichlet", "Multiplicity", "CG", primal));
  if (isRoot())
    std::printf("[feti-accuracy] first solve %-24s %2d subdomains on %d rank(s), %s: |u_F - u_D|/|u_D| = %.2e  "
                "(MUMPS residual %.1e)  CG %2d it, rel. res %.1e  primal %zu  dual %lld  LMs %zu%s\n",
                c.name.c_str(), s.subdomains, worldSize(), primal.c_str(), s.error, s.directResidual,
                s.info.iterations, s.info.relativeResidual, s.numPrimal, s.numDual, s.numLm,
                s.primalReport.empty() ? "" : "  (extra corners)");
  EXPECT_EQ(s.subdomains, c.expectSubdomains);
  EXPECT_LE(s.directResidual, kDirectResidual) << "the MUMPS reference itself is inaccurate";
  EXPECT_LE(s.info.relativeResidual, kTightBelos);
  EXPECT_LE(s.error, kFetiVsDirect);
  EXPECT_EQ(!s.primalReport.empty(), c.expectExtraCorners)
      << (s.primalReport.empty() ? std::string("no subdomain needed extra corners") : s.primalReport.front());
  if (c.expectSubdomains == 1) {
    EXPECT_EQ(s.numLm, 0u);
    EXPECT_EQ(s.info.iterations, 0);
  } else {
    EXPECT_GT(s.numLm, 0u);
    EXPECT_GT(s.info.iterations, 0);
  }
  }
}

TEST_P(FetiLinear, AnalysisMatchesMonolithicWithTheSamePartition) {
  const LinearCase& c = GetParam();
  // Known bug (see the report): when selectPrimalNodes adds corners, the

  PL base = deckFor(c);
  PL df = base, dm = base;
  useFeti(df, fetiParams(kTightBelos));
  useMonolithic(dm);
  ddc::Analysis af(worldComm(), df), am(worldComm(), dm);
  af.run("");
  am.run("");
  // Same partition and rank count -> same DOF numbering and owned map.
  ASSERT_TRUE(af.displacement().getMap()->isSameAs(*am.displacement().getMap()))
      << "FETI-DP and Monolithic runs with the same Partition have different owned DOF maps";
  const double eOwned = relErr(af.displacement(), am.displacement());
  const double eNodes = relErr(gatherDisplacement(af.model(), af.displacement()),
                               gatherDisplacement(am.model(), am.displacement()));
  ASSERT_EQ(af.history().size(), 1u);
  ASSERT_EQ(am.history().size(), 1u);
  const auto& hf = af.history()[0];
  const auto& hm = am.history()[0];
  if (isRoot())
    std::printf("[feti-accuracy] analysis    %-24s %2d subdomains on %d rank(s): |u_F - u_M|/|u_M| = %.2e (owned) "
                "%.2e (by node)  energy rel. diff %.1e  Newton %d / %d  dual it %d\n",
                c.name.c_str(), af.model().partition().numSubdomains, worldSize(), eOwned, eNodes,
                relDiff(hf.strainEnergy, hm.strainEnergy), hf.newtonIterations, hm.newtonIterations,
                hf.dualIterations);
  EXPECT_LE(eOwned, kFetiVsDirect);
  EXPECT_LE(eNodes, kFetiVsDirect);
  EXPECT_LE(relDiff(hf.strainEnergy, hm.strainEnergy), kEnergy);
  // An accurate linear solve converges in the minimum 2 Newton iterations;
  // an inaccurate one needs a third (energy criterion 1e-16).
  EXPECT_EQ(hf.newtonIterations, hm.newtonIterations);
  EXPECT_EQ(hm.dualIterations, 0);
  if (c.expectSubdomains > 1) EXPECT_GT(hf.dualIterations, 0);
}

INSTANTIATE_TEST_SUITE_P(Partitions, FetiLinear, testing::ValuesIn(linearCases()),
                         [](const testing::TestParamInfo<LinearCase>& i) { return i.param.name; });

/// The accuracy measure must be able to fail: stopping CG at 1e-3 leaves an
/// error far above kFetiVsDirect.
TEST(FetiFirstSolve, LooseBelosToleranceIsDetected) {
  PL deck = elasticBlock();
  PartitionSpec p;
  p.subdomains = 9;
  setPartition(deck, p);
  const auto s = firstSolve(deck, fetiParams(1e-3));
  if (isRoot()) std::printf("[feti-accuracy] CG stopped at 1e-3: |u_F - u_D|/|u_D| = %.2e\n", s.error);
  EXPECT_GT(s.error, 100 * kFetiVsDirect);
}

/// Other Krylov solvers, the lumped preconditioner, stiffness scaling and the
/// Amesos2 (KLU2) local / coarse solvers give the same solution
/// (CG / Dirichlet / multiplicity / MUMPS is covered above).
TEST(FetiFirstSolve, OtherSolverOptionsMatchMumps) {
  PL deck = elasticBlock(Support::Determinate);
  PartitionSpec p;
  p.subdomains = 9;
  setPartition(deck, p);
  struct Opt {
    const char *prec, *scaling, *krylov, *local, *coarse;
  };
  for (const Opt o : {Opt{"Lumped", "Multiplicity", "CG", "MUMPS", "MUMPS"},
                      Opt{"Dirichlet", "Stiffness", "CG", "MUMPS", "MUMPS"},
                      Opt{"None", "Multiplicity", "CG", "MUMPS", "MUMPS"},
                      Opt{"Dirichlet", "Multiplicity", "GMRES", "MUMPS", "MUMPS"},
                      Opt{"Dirichlet", "Multiplicity", "MINRES", "MUMPS", "MUMPS"},
                      Opt{"Dirichlet", "Multiplicity", "CG", "Amesos2", "MUMPS"},
                      Opt{"Dirichlet", "Multiplicity", "CG", "MUMPS", "Amesos2"},
                      Opt{"Dirichlet", "Multiplicity", "CG", "Amesos2", "Amesos2"}}) {
    PL fp = fetiParams(kTightBelos, o.prec, o.scaling, o.krylov);
    fp.sublist("Local Solver").set("Type", std::string(o.local));
    fp.sublist("Coarse Solver").set("Type", std::string(o.coarse));
    const auto s = firstSolve(deck, fp);
    if (isRoot())
      std::printf("[feti-accuracy] METIS9 determinate %-9s %-12s %-6s local %-7s coarse %-7s: error %.2e, %d it, "
                  "rel. res %.1e\n",
                  o.prec, o.scaling, o.krylov, o.local, o.coarse, s.error, s.info.iterations,
                  s.info.relativeResidual);
    EXPECT_LE(s.error, kFetiVsDirect) << o.prec << " " << o.scaling << " " << o.krylov << " " << o.local << " "
                                      << o.coarse;
  }
}

// ---------------------------------------------------------------------------
// b. Neo-Hookean arch, large rotations: FETI-DP and Monolithic Newton
//    histories agree.

struct ArchResult {
  std::vector<ddc::StepRecord> history;
  int subdomains = 0;
};

ArchResult runArch(const PartitionSpec& part, bool feti, int steps) {
  auto deck = Teuchos::getParametersFromXmlFile(std::string(DDC_SOURCE_DIR) + "/examples/arch.xml");
  quiet(*deck, steps);
  setPartition(*deck, part);
  if (feti)
    useFeti(*deck, fetiParams(kTightBelos));
  else
    useMonolithic(*deck);
  ddc::Analysis a(worldComm(), *deck, ddc::ElementFactory::withBuiltins(), DDC_SOURCE_DIR "/examples");
  a.run("");
  return {a.history(), a.model().partition().numSubdomains};
}

class FetiArch : public testing::TestWithParam<PartitionSpec> {};

TEST_P(FetiArch, SameNewtonHistoryAsMonolithic) {
  const PartitionSpec part = GetParam();
  constexpr int kSteps = 5;
  const auto f = runArch(part, true, kSteps);
  const auto m = runArch(part, false, kSteps);
  ASSERT_EQ(f.history.size(), m.history.size()) << "different numbers of (sub)steps (bisections)";
  ASSERT_FALSE(m.history.empty());
  double worstEnergy = 0.0;
  for (size_t i = 0; i < f.history.size(); ++i) {
    const auto& a = f.history[i];
    const auto& b = m.history[i];
    EXPECT_EQ(a.loadFactor, b.loadFactor) << "record " << i;
    EXPECT_EQ(a.newtonIterations, b.newtonIterations) << "record " << i << " (step " << a.step << ")";
    EXPECT_LE(relDiff(a.strainEnergy, b.strainEnergy), kEnergy) << "record " << i;
    worstEnergy = std::max(worstEnergy, relDiff(a.strainEnergy, b.strainEnergy));
    if (isRoot()) {
      std::printf("[feti-arch] %-12s step %d load %.2f  Newton %d / %d  dual it %3d  energy %.10e / %.10e\n",
                  part.label().c_str(), a.step, a.loadFactor, a.newtonIterations, b.newtonIterations,
                  a.dualIterations, a.strainEnergy, b.strainEnergy);
      std::printf("[feti-arch]              |r| FETI-DP   :");
      for (double x : a.residualHistory) std::printf(" %.2e", x);
      std::printf("\n[feti-arch]              |r| Monolithic:");
      for (double x : b.residualHistory) std::printf(" %.2e", x);
      std::printf("\n");
    }
  }
  EXPECT_LE(relDiff(f.history.back().strainEnergy, m.history.back().strainEnergy), kEnergy);
  // Geometrically nonlinear indeed: a linear problem converges in 2 Newton
  // iterations, the arch takes 4 per step (measured).
  int maxNewton = 0;
  for (const auto& r : m.history) maxNewton = std::max(maxNewton, r.newtonIterations);
  EXPECT_GE(maxNewton, 4) << "the arch is expected to be geometrically nonlinear";
  if (isRoot())
    std::printf("[feti-arch] %-12s %d subdomains on %d rank(s): worst per-step energy rel. diff %.2e\n",
                part.label().c_str(), f.subdomains, worldSize(), worstEnergy);
}

std::vector<PartitionSpec> archPartitions() {
  PartitionSpec m4, m8, box;
  m4.subdomains = 4;
  m8.subdomains = 8;
  box.method = "Box Grid";
  box.bx = 4, box.by = 1;
  return {m4, m8, box};
}

INSTANTIATE_TEST_SUITE_P(Partitions, FetiArch, testing::ValuesIn(archPartitions()),
                         [](const testing::TestParamInfo<PartitionSpec>& i) { return i.param.label(); });

// ---------------------------------------------------------------------------
// c. Iteration counts at fixed H/h.

/// Unit square, (k * hH) x (k * hH) Quad4, Box Grid k x k: subdomains of
/// hH x hH elements. Clamped left, traction right, linear elastic.
PL squareDeck(int k, int hH) {
  PL deck = blockDeck(1.0, 1.0, k * hH, k * hH);
  PartitionSpec p;
  p.method = "Box Grid";
  p.bx = p.by = k;
  setPartition(deck, p);
  return deck;
}

TEST(FetiIterations, BoundedAtFixedHOverh) {
  constexpr int kHh = 16;
  int it[2] = {0, 0};
  const int ks[2] = {4, 8};
  for (int i = 0; i < 2; ++i) {
    const auto s = firstSolve(squareDeck(ks[i], kHh), vertexParams(kCountBelos), /*direct=*/false);
    it[i] = s.info.iterations;
    EXPECT_EQ(s.subdomains, ks[i] * ks[i]);
    EXPECT_LE(s.info.relativeResidual, kCountBelos);
    if (isRoot())
      std::printf("[feti-iterations] Box Grid %dx%d, H/h = %d (%dx%d elements), Dirichlet, multiplicity, CG to "
                  "%.0e: %d iterations (first Newton solve), %.1f s\n",
                  ks[i], ks[i], kHh, ks[i] * kHh, ks[i] * kHh, kCountBelos, it[i], s.seconds);
  }
  EXPECT_LE(it[0], kMaxDirichletIterations);
  EXPECT_LE(it[1], kMaxDirichletIterations);
  EXPECT_LT(double(it[1] - it[0]) / it[0], kMaxGrowth)
      << "iterations grew from " << it[0] << " (16 subdomains) to " << it[1] << " (64 subdomains)";

  // What the analysis reports: StepRecord::dualIterations sums the Newton
  // solves of the step, and there is no per-solve count. A linear step takes
  // at least 2 solves, and with CG stopped at 1e-8 a third one (the energy
  // criterion 1e-16 sees the 1e-8 solver error). The later solves have
  // round-off-sized right-hand sides but the same relative tolerance, so they
  // cost about as much as the first. The bound that holds per solve holds
  // for the average: dualIterations <= newtonIterations * bound.
  PL deck = squareDeck(4, kHh);
  useFeti(deck, vertexParams(kCountBelos));
  ddc::Analysis a(worldComm(), deck);
  a.run("");
  ASSERT_EQ(a.history().size(), 1u);
  const auto& rec = a.history()[0];
  if (isRoot())
    std::printf("[feti-iterations] analysis 4x4, H/h = 16: %d Newton solves, %d dual iterations in the step "
                "(first solve %d, the later ones %d)\n",
                rec.newtonIterations, rec.dualIterations, it[0], rec.dualIterations - it[0]);
  EXPECT_GE(rec.newtonIterations, 2);
  EXPECT_GE(rec.dualIterations, it[0]);
  EXPECT_LE(rec.dualIterations, rec.newtonIterations * kMaxDirichletIterations);
}

/// The iteration table of doc/performance.md: 4, 16, 64 subdomains x H/h = 8, 16, 32 x
/// Dirichlet / lumped (CG to 1e-8, multiplicity scaling, first Newton solve).
/// 64 x 32 is a 256 x 256 mesh (132k DOFs); the whole table took 17 s on one
/// rank and 21 s on two (Release), so it runs by default; DDC_SKIP_TABLES=1
/// skips it. Besides printing, it checks what FETI-DP theory predicts
/// (kappa <= C (1 + log H/h)^2 for Dirichlet): every Dirichlet count within
/// kMaxDirichletIterations (at H/h = 32 the bound of H/h = 16 grows by
/// (1 + log 32)/(1 + log 16) = 1.18 in sqrt(kappa), 22 -> 26 < 30), growth
/// from 16 to 64 subdomains below kMaxGrowth at every H/h, and the lumped
/// preconditioner never better than the Dirichlet one.
TEST(FetiIterations, TableOverSubdomainsAndHOverh) {
  const char* env = std::getenv("DDC_SKIP_TABLES");
  if (env && std::string(env) == "1") GTEST_SKIP() << "DDC_SKIP_TABLES=1";
  const int ks[3] = {2, 4, 8}, hs[3] = {8, 16, 32};
  int table[2][3][3];
  const std::string precs[2] = {"Dirichlet", "Lumped"};
  for (int p = 0; p < 2; ++p) {
    double secs[3][3];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const auto s = firstSolve(squareDeck(ks[a], hs[b]), vertexParams(kCountBelos, precs[p]), false);
        table[p][a][b] = s.info.iterations;
        secs[a][b] = s.seconds;
        EXPECT_LE(s.info.relativeResidual, kCountBelos);
      }
    if (isRoot()) {
      std::printf("[feti-table] CG iterations to %.0e, %s preconditioner, multiplicity scaling, %d rank(s) "
                  "(first Newton solve; wall s in parentheses, model set-up included)\n",
                  kCountBelos, precs[p].c_str(), worldSize());
      std::printf("[feti-table] %-14s %14s %14s %14s\n", "subdomains", "H/h = 8", "H/h = 16", "H/h = 32");
      for (int a = 0; a < 3; ++a) {
        std::printf("[feti-table] %2d (%dx%d)      ", ks[a] * ks[a], ks[a], ks[a]);
        for (int b = 0; b < 3; ++b) std::printf("    %4d (%5.1f)", table[p][a][b], secs[a][b]);
        std::printf("\n");
      }
    }
  }
  for (int b = 0; b < 3; ++b) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(table[0][a][b], kMaxDirichletIterations) << ks[a] * ks[a] << " subdomains, H/h = " << hs[b];
      EXPECT_GE(table[1][a][b], table[0][a][b]) << "lumped beat Dirichlet at " << ks[a] * ks[a]
                                                << " subdomains, H/h = " << hs[b];
    }
    EXPECT_LT(double(table[0][2][b] - table[0][1][b]) / table[0][1][b], kMaxGrowth) << "H/h = " << hs[b];
  }
}

// ---------------------------------------------------------------------------
// Primal constraints: vertices, edges, faces (doc/feti-dp.md "Primal
// constraints"). Same first-solve set-up as above; every choice must match
// MUMPS (FetiLinear.FirstSolveMatchesMumpsWithEveryPrimalChoice), and the
// edge/face averages must pay in iterations.

/// Iteration bounds with edge / face averages (Dirichlet, multiplicity, CG to
/// kCountBelos, first Newton solve, rotational constraints on): 2-D 64
/// subdomains at H/h = 32 with edges, 3-D 27 subdomains at H/h = 8 with
/// edges and faces. For scale:
/// PETSc 3.18's FETI-DP (ex71) needs 11 (2-D 8x8, H/h = 64, edges) and 10
/// (3-D 3x3x3, H/h = 8, edges and faces) with its default constraints.
constexpr int kMaxEdgeIterations2d = 14;
constexpr int kMaxFaceIterations3d = 14;

/// Unit cube of (k hH)^3 Hex8, Box Grid k x k x k (subdomains of hH^3
/// elements), clamped at x = 0, traction on x = 1, linear elastic.
PL cubeDeck(int k, int hH) {
  PL deck("DDContact");
  BoxSpec b;
  b.elements[0] = b.elements[1] = b.elements[2] = k * hH;
  addBox(deck, "Cube", b);
  addDisplacement(deck, "Clamped", "Cube/left", "All");
  addTraction3(deck, "Load", "Cube/right", {10.0, -1.0, 0.5});
  quiet(deck, 1);
  PartitionSpec p;
  p.method = "Box Grid";
  p.bx = p.by = p.bz = k;
  setPartition(deck, p);
  return deck;
}

/// Prints the table [choice][k][H/h] (k^dim subdomains) and returns it;
/// meshes of more than maxElements per direction are skipped (-1).
std::vector<std::vector<std::vector<int>>> primalTable(const std::string& label, const std::vector<int>& ks,
                                                       const std::vector<int>& hs, int dim, PL (*deckOf)(int, int),
                                                       int maxElements) {
  std::vector<std::vector<std::vector<int>>> t(kPrimalChoices.size(),
                                               std::vector<std::vector<int>>(ks.size(), std::vector<int>(hs.size())));
  for (size_t c = 0; c < kPrimalChoices.size(); ++c)
    for (size_t a = 0; a < ks.size(); ++a)
      for (size_t b = 0; b < hs.size(); ++b) {
        t[c][a][b] = -1;
        if (ks[a] * hs[b] > maxElements) continue;
        const auto s = firstSolve(deckOf(ks[a], hs[b]),
                                  fetiParams(kCountBelos, "Dirichlet", "Multiplicity", "CG", kPrimalChoices[c]), false);
        EXPECT_LE(s.info.relativeResidual, kCountBelos);
        t[c][a][b] = s.info.iterations;
        if (isRoot())
          std::printf("[feti-primal] %s %-26s %3d subdomains H/h = %2d: %3d iterations, coarse %5zu DOFs, %.1f s\n",
                      label.c_str(), kPrimalChoices[c].c_str(), s.subdomains, hs[b], t[c][a][b], s.numPrimal,
                      s.seconds);
      }
  if (isRoot()) {
    std::printf("[feti-primal] %s: CG iterations to %.0e, Dirichlet, multiplicity, %d rank(s)\n", label.c_str(),
                kCountBelos, worldSize());
    std::printf("[feti-primal] %-26s %-11s", "primal constraints", "subdomains");
    for (int h : hs) std::printf("  H/h = %-3d", h);
    std::printf("\n");
    for (size_t c = 0; c < kPrimalChoices.size(); ++c)
      for (size_t a = 0; a < ks.size(); ++a) {
        int n = 1;
        for (int d = 0; d < dim; ++d) n *= ks[a];
        std::printf("[feti-primal] %-26s %-11d", kPrimalChoices[c].c_str(), n);
        for (size_t b = 0; b < hs.size(); ++b)
          t[c][a][b] < 0 ? std::printf("  %9s", "-") : std::printf("  %9d", t[c][a][b]);
        std::printf("\n");
      }
  }
  return t;
}

TEST(FetiIterations, PrimalChoices2d) {
  // 4 / 16 / 64 subdomains x H/h = 8 / 16 / 32 (the largest 132k DOFs).
  const auto t = primalTable("2-D", {2, 4, 8}, {8, 16, 32}, 2, squareDeck, 256);
  EXPECT_LE(t[1][2][2], kMaxEdgeIterations2d) << "64 subdomains, H/h = 32, Vertices and Edges";
  for (size_t a = 0; a < 3; ++a)
    for (size_t b = 0; b < 3; ++b) {
      // No faces in 2-D: the default is the same method as Vertices and Edges.
      EXPECT_EQ(t[2][a][b], t[1][a][b]);
      EXPECT_LE(t[1][a][b], t[0][a][b]) << "edges cost iterations";
    }
}

/// FETI-DP = MUMPS in 3-D with every primal choice: Box Grid 2x2x2 and
/// 3x3x3 (H/h = 4) and METIS 8 on the same cube.
TEST(FetiFirstSolve, Cube3dMatchesMumpsWithEveryPrimalChoice) {
  std::vector<std::pair<std::string, PL>> cases = {{"BoxGrid2x2x2", cubeDeck(2, 4)}, {"BoxGrid3x3x3", cubeDeck(3, 4)}};
  PL metis = cubeDeck(2, 4);
  PartitionSpec p;
  p.subdomains = 8;
  metis.sublist("Partition") = PL("Partition");
  setPartition(metis, p);
  cases.emplace_back("METIS8", metis);
  for (const auto& [name, deck] : cases)
    for (const auto& primal : kPrimalChoices) {
      const auto s = firstSolve(deck, fetiParams(kTightBelos, "Dirichlet", "Multiplicity", "CG", primal));
      if (isRoot())
        std::printf("[feti-accuracy] first solve cube %-13s %2d subdomains, %-26s |u_F - u_D|/|u_D| = %.2e  CG %2d "
                    "it  coarse %zu\n",
                    name.c_str(), s.subdomains, primal.c_str(), s.error, s.info.iterations, s.numPrimal);
      EXPECT_LE(s.directResidual, kDirectResidual) << name;
      EXPECT_LE(s.error, kFetiVsDirect) << name << ", " << primal;
      EXPECT_GT(s.info.iterations, 0) << name;
    }
}

TEST(FetiIterations, PrimalChoices3d) {
  // 8 / 27 / 64 subdomains x H/h = 4 / 8; 64 x 8 (108k DOFs) is left to
  // the benchmark (doc/performance.md).
  const auto t = primalTable("3-D", {2, 3, 4}, {4, 8}, 3, cubeDeck, 24);
  EXPECT_LE(t[2][1][1], kMaxFaceIterations3d) << "27 subdomains, H/h = 8, Vertices, Edges and Faces";
  EXPECT_LT(double(t[2][2][0] - t[2][0][0]) / t[2][0][0], kMaxGrowth)
      << "Vertices, Edges and Faces at H/h = 4: iterations grew from " << t[2][0][0] << " (8 subdomains) to "
      << t[2][2][0] << " (64)";
  for (size_t a = 0; a < 3; ++a)
    for (size_t b = 0; b < 2; ++b)
      if (t[2][a][b] >= 0) EXPECT_LE(t[2][a][b], t[1][a][b]) << "faces cost iterations";
}

/// Mesh-free vertices in 3-D (doc/feti-dp.md "Primal nodes"): on a Box Grid
/// k x k x k of a cube, findPrimalVertices() picks exactly the points where
/// eight subdomains meet ((k-1)^3 of them); the subdomain edges' ends on the
/// boundary stay in their edges. With faces and edges FETI-DP then matches
/// MUMPS.
TEST(FetiMeshFreeVertices, CubeCrossPointsAndAccuracy) {
  for (int k : {2, 3}) {
    const auto s = firstSolve(cubeDeck(k, 3), fetiParams(kTightBelos), true, /*meshFreeVertices=*/true);
    const long long vertexDofs = (long long)(s.numPrimal) - s.numEdgeFace, expected = 3LL * (k - 1) * (k - 1) * (k - 1);
    if (isRoot())
      std::printf("[feti-accuracy] cube Box Grid %dx%dx%d mesh-free vertices: %lld vertex DOFs, %lld edge/face "
                  "constraints, error %.2e, CG %d it\n",
                  k, k, k, vertexDofs, s.numEdgeFace, s.error, s.info.iterations);
    EXPECT_EQ(vertexDofs, expected) << "the points where eight subdomains meet";
    EXPECT_LT(s.error, kFetiVsDirect) << k << "^3 subdomains";
    EXPECT_GT(s.numEdgeFace, 0) << "the edges and faces carry the rest of the coarse space";
  }
}

// ---------------------------------------------------------------------------
// d. Errors.

/// Two bodies, one held ("Held", clamped left) and one with no boundary
/// condition at all ("Free"); By Body gives each its own subdomain, so the
/// free one has no interface node that could become a corner.
PL twoBodyDeck() {
  PL deck("DDContact");
  addBlock(deck, "Held", 0.0, 0.0, 1.0, 1.0, 4, 4, "Linear Elastic");
  addBlock(deck, "Free", 2.0, 0.0, 1.0, 1.0, 4, 4, "Linear Elastic");
  addDisplacement(deck, "Clamped", "Held/left", "XY");
  addTraction(deck, "Load", "Held/right", 10.0, 0.0);
  quiet(deck, 1);
  return deck;
}

TEST(FetiErrors, FloatingBodyNamesSubdomainAndBody) {
  PL deck = twoBodyDeck();
  PartitionSpec p;
  p.method = "By Body";
  setPartition(deck, p);
  useFeti(deck, fetiParams(kTightBelos));
  try {
    ddc::Analysis a(worldComm(), deck);
    FAIL() << "a floating body in its own subdomain was accepted";
  } catch (const ddc::InputError& e) {
    // The body check runs before the corner rule and names the body.
    EXPECT_THAT(e.what(), testing::HasSubstr("body 'Free' is not supported"));
  }
}

/// The free body split by METIS into several subdomains: each of them has
/// interface nodes, so rule 3 makes some primal and every K_rr is regular,
/// but the body as a whole still floats (its coarse block is singular). With a
/// load on the free body the run must stop with an error naming the body.
/// (MUMPS factorises a singular coarse or global matrix without complaint, so
/// the analysis checks every body's supports before anything runs.)
TEST(FetiErrors, FloatingBodySplitByMetisIsDetected) {
  PL deck = twoBodyDeck();
  addTraction(deck, "Push free", "Free/right", 1.0, 0.0);
  PartitionSpec p;
  p.subdomains = 4;
  setPartition(deck, p);
  useFeti(deck, fetiParams(kTightBelos));
  deck.sublist("Load Stepping").set("Max Bisections", 0);
  std::string what = "no error";
  try {
    ddc::Analysis a(worldComm(), deck);
    a.run("");
  } catch (const std::exception& e) {
    what = e.what();
  }
  if (isRoot()) std::printf("[feti-errors] loaded free body split over subdomains: %s\n", what.c_str());
  EXPECT_THAT(what, testing::HasSubstr("'Free'"));
  EXPECT_THAT(what, testing::Not(testing::HasSubstr("Newton did not converge")));
}

}  // namespace
