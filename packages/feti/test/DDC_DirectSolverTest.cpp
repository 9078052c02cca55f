// Local-solver factory: every back end solves a 2-D Laplacian and a
// symmetric indefinite saddle-point matrix [K B^T; B 0], distributed over
// the world communicator and on MPI_COMM_SELF, checked by the residual
// ||b - A x|| / ||b|| computed with Tpetra's apply (never against the solver
// itself: doc/trilinos-notes.md records a wrong KLU2 solution on 2 ranks). Also:
// refactorisation with the same pattern (symbolic reuse), singular matrices,
// several right-hand sides, coexisting instances, factory errors. The serial
// CHOLMOD back end has its own tests (SPD matrices on one process, compared
// with MUMPS; the MUMPS fallback for indefinite matrices).
#include <gtest/gtest.h>
#include <mpi.h>

#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_SerialDenseMatrix.hpp>
#include <Teuchos_SerialDenseSolver.hpp>
#include <Teuchos_SerialDenseVector.hpp>
#include <Tpetra_Core.hpp>
#include <algorithm>
#include <cstdio>
#include <functional>

#include "DDC_TestErrors.hpp"
#include "DDC_Amesos2Solver.hpp"
#include "DDC_CholmodSolver.hpp"
#include "DDC_DirectSolver.hpp"
#include "DDC_Error.hpp"
#include "DDC_MumpsSolver.hpp"
#include "DDC_TestTolerances.hpp"

namespace ddc::test {
/// Relative residual ||b - A x|| / ||b|| accepted from a direct solve. A
/// backward-stable factorisation gives ~ u * cond(A) * growth; the test
/// matrices have cond(A) <= 1e4, so 1e-16 * 1e4 = 1e-12, and 1e-10 leaves a
/// factor 100 for pivot growth. A wrong solve (the KLU2-on-2-ranks pitfall)
/// has a residual of O(1).
constexpr double kDirectSolveResidual = 1e-10;
/// Relative difference ||x_1 - x_2|| / ||x_2|| accepted between two direct
/// solvers (or between a block and a single-column solve) on the same SPD
/// matrix: each is backward stable, so they differ by ~ u * cond(A) * growth;
/// the SPD test matrices have cond(A) <= 1e4 (Cholesky has no pivot growth),
/// so 1e-16 * 1e4 = 1e-12 with a factor 100 to spare.
constexpr double kDirectSolverAgreement = 1e-10;
}  // namespace ddc::test

namespace {

using ddc::CrsMatrix;
using ddc::DirectSolver;
using ddc::DirectSolverFactory;
using ddc::GO;
using ddc::LO;
using ddc::Map;
using ddc::MultiVector;
using ddc::test::kDirectSolveResidual;
using ddc::test::kDirectSolverAgreement;
using Teuchos::RCP;
using Teuchos::rcp;
using Comm = Teuchos::Comm<int>;

RCP<const Comm> worldComm() { return Tpetra::getDefaultComm(); }
RCP<const Comm> selfComm() { return rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF)); }
int worldRank() { return worldComm()->getRank(); }

/// Print a measured number from rank 0 (kept in the ctest log).
void report(const std::string& what, double value) {
  if (worldRank() == 0) std::printf("[ residual ] %-55s %.3e\n", what.c_str(), value);
}

/// 5-point Laplacian on an nx x ny grid (Dirichlet: diagonal 4), optionally
/// with a convection term c (u_{i+1} - u_{i-1}) that makes it nonsymmetric.
/// Global indices start at `base`.
RCP<CrsMatrix> laplacian(const RCP<const Comm>& comm, int nx, int ny, double c = 0.0, GO base = 0) {
  const GO n = GO(nx) * ny;
  auto map = rcp(new Map(n, base, comm));
  auto A = rcp(new CrsMatrix(map, 5));
  for (LO lr = 0; lr < LO(map->getNodeNumElements()); ++lr) {
    const GO g = map->getGlobalElement(lr) - base;
    const int i = int(g % nx), j = int(g / nx);
    std::vector<GO> cols{g};
    std::vector<double> vals{4.0};
    if (i > 0) cols.push_back(g - 1), vals.push_back(-1.0 - c);
    if (i < nx - 1) cols.push_back(g + 1), vals.push_back(-1.0 + c);
    if (j > 0) cols.push_back(g - nx), vals.push_back(-1.0);
    if (j < ny - 1) cols.push_back(g + nx), vals.push_back(-1.0);
    for (auto& col : cols) col += base;
    A->insertGlobalValues(g + base, LO(cols.size()), vals.data(), cols.data());
  }
  A->fillComplete();
  return A;
}

/// Saddle-point matrix [K B^T; B 0]: K the Laplacian (n = nx*ny), B has m
/// rows tying DOF pairs, B(i, 2i) = 1, B(i, 2i+1) = -1 (like interface
/// compatibility constraints). Symmetric indefinite, zero (structurally
/// absent) diagonal in the multiplier rows.
RCP<CrsMatrix> saddlePoint(const RCP<const Comm>& comm, int nx, int ny, int m) {
  const GO n = GO(nx) * ny;
  auto map = rcp(new Map(n + m, 0, comm));
  auto A = rcp(new CrsMatrix(map, 6));
  for (LO lr = 0; lr < LO(map->getNodeNumElements()); ++lr) {
    const GO g = map->getGlobalElement(lr);
    std::vector<GO> cols;
    std::vector<double> vals;
    if (g < n) {
      const int i = int(g % nx), j = int(g / nx);
      cols.push_back(g), vals.push_back(4.0);
      if (i > 0) cols.push_back(g - 1), vals.push_back(-1.0);
      if (i < nx - 1) cols.push_back(g + 1), vals.push_back(-1.0);
      if (j > 0) cols.push_back(g - nx), vals.push_back(-1.0);
      if (j < ny - 1) cols.push_back(g + nx), vals.push_back(-1.0);
      if (g < 2 * m) cols.push_back(n + g / 2), vals.push_back(g % 2 == 0 ? 1.0 : -1.0);
    } else {
      const GO i = g - n;
      cols = {2 * i, 2 * i + 1};
      vals = {1.0, -1.0};
    }
    A->insertGlobalValues(g, LO(cols.size()), vals.data(), cols.data());
  }
  A->fillComplete();
  return A;
}

/// 3-D elasticity-like SPD matrix on an nx x ny x nz node grid, 3 DOFs per
/// node (node-major, DOF 3 a + c), 27-point coupling: (L + D) (x) M, with L
/// the graph Laplacian of the 27-point stencil, D = 1 on the nodes of the
/// bottom layer (z = 0, "supported") and M a 3 x 3 SPD coupling of the
/// components; a Kronecker product of SPD matrices is SPD. `shift` is added
/// to every diagonal entry (a negative one makes the matrix indefinite).
RCP<CrsMatrix> elasticity3d(const RCP<const Comm>& comm, int nx, int ny, int nz, double shift = 0.0) {
  const double M[3][3] = {{2.0, 0.5, 0.25}, {0.5, 2.0, 0.5}, {0.25, 0.5, 2.0}};
  const GO n = 3 * GO(nx) * ny * nz;
  auto map = rcp(new Map(n, 0, comm));
  auto A = rcp(new CrsMatrix(map, 81));
  for (LO lr = 0; lr < LO(map->getNodeNumElements()); ++lr) {
    const GO g = map->getGlobalElement(lr);
    const GO a = g / 3;
    const int c = int(g % 3), i = int(a % nx), j = int((a / nx) % ny), k = int(a / (GO(nx) * ny));
    std::vector<GO> cols;
    std::vector<double> vals;
    int degree = 0;
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int ii = i + di, jj = j + dj, kk = k + dk;
          if ((di == 0 && dj == 0 && dk == 0) || ii < 0 || jj < 0 || kk < 0 || ii >= nx || jj >= ny || kk >= nz)
            continue;
          ++degree;
          const GO b = (GO(kk) * ny + jj) * nx + ii;
          for (int d = 0; d < 3; ++d) cols.push_back(3 * b + d), vals.push_back(-M[c][d]);
        }
    const double lii = degree + (k == 0 ? 1.0 : 0.0);
    for (int d = 0; d < 3; ++d) cols.push_back(3 * a + d), vals.push_back(lii * M[c][d] + (d == c ? shift : 0.0));
    A->insertGlobalValues(g, LO(cols.size()), vals.data(), cols.data());
  }
  A->fillComplete();
  return A;
}

/// max over columns of ||x - y|| / ||y||.
double relDifference(const MultiVector& x, const MultiVector& y) {
  MultiVector d(y, Teuchos::Copy);
  d.update(1.0, x, -1.0);
  std::vector<double> dn(y.getNumVectors()), yn(y.getNumVectors());
  d.norm2(Teuchos::ArrayView<double>(dn));
  y.norm2(Teuchos::ArrayView<double>(yn));
  double worst = 0.0;
  for (size_t j = 0; j < dn.size(); ++j) worst = std::max(worst, dn[j] / yn[j]);
  return worst;
}

/// Replace every value a_ij by f(i, j, a_ij) keeping the pattern.
void modifyValues(CrsMatrix& A, const std::function<double(GO, GO, double)>& f) {
  A.resumeFill();
  const auto& rowMap = *A.getRowMap();
  const auto& colMap = *A.getColMap();
  for (LO lr = 0; lr < LO(rowMap.getNodeNumElements()); ++lr) {
    CrsMatrix::local_inds_host_view_type inds;
    CrsMatrix::values_host_view_type v;
    A.getLocalRowView(lr, inds, v);
    std::vector<LO> cols(inds.data(), inds.data() + inds.extent(0));
    std::vector<double> vals(inds.extent(0));
    for (size_t e = 0; e < cols.size(); ++e)
      vals[e] = f(rowMap.getGlobalElement(lr), colMap.getGlobalElement(cols[e]), v(e));
    A.replaceLocalValues(lr, LO(cols.size()), vals.data(), cols.data());
  }
  A.fillComplete();
}

/// max over columns of ||b - A x|| / ||b||, with A applied by Tpetra.
double relResidual(const CrsMatrix& A, const MultiVector& x, const MultiVector& b) {
  MultiVector r(A.getRangeMap(), b.getNumVectors());
  A.apply(x, r);
  r.update(1.0, b, -1.0);
  std::vector<double> rn(b.getNumVectors()), bn(b.getNumVectors());
  r.norm2(Teuchos::ArrayView<double>(rn));
  b.norm2(Teuchos::ArrayView<double>(bn));
  double worst = 0.0;
  for (size_t j = 0; j < rn.size(); ++j) worst = std::max(worst, rn[j] / bn[j]);
  return worst;
}

/// Factorise and solve A x = b for `k` random right-hand sides; returns the
/// worst relative residual.
double solveResidual(DirectSolver& s, const RCP<const CrsMatrix>& A, size_t k = 1) {
  MultiVector b(A->getRowMap(), k), x(A->getRowMap(), k);
  b.randomize();
  s.symbolic(A);
  s.numeric();
  s.solve(b, x);
  return relResidual(*A, x, b);
}

using ddc::test::expectThrowWith;

// ---- every back end --------------------------------------------------------

class DirectSolverTest : public ::testing::TestWithParam<std::string> {
 protected:
  /// A solver of the back end under test through the factory, `opts` going
  /// into its sublist.
  std::unique_ptr<DirectSolver> make(const Teuchos::ParameterList& opts = Teuchos::ParameterList()) const {
    Teuchos::ParameterList p;
    p.set("Type", GetParam());
    p.sublist(GetParam()).setParameters(opts);
    return DirectSolverFactory::withBuiltins().create(p, "Test/Direct Solver");
  }
  std::string tag(const std::string& what) const {
    return GetParam() + " " + what + " np=" + std::to_string(worldComm()->getSize());
  }
};

TEST_P(DirectSolverTest, LaplacianDistributed) {
  auto A = laplacian(worldComm(), 30, 20);
  auto s = make();
  const double res = solveResidual(*s, A);
  report(tag("Laplacian 600 world"), res);
  EXPECT_LT(res, kDirectSolveResidual);
}

TEST_P(DirectSolverTest, LaplacianOnCommSelf) {
  // A different matrix on every rank, as for FETI-DP subdomains.
  auto A = laplacian(selfComm(), 12 + worldRank(), 9);
  auto s = make();
  const double res = solveResidual(*s, A);
  EXPECT_LT(res, kDirectSolveResidual) << "rank " << worldRank();
  double worst = 0;
  MPI_Allreduce(&res, &worst, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  report(tag("Laplacian self (max over ranks)"), worst);
}

TEST_P(DirectSolverTest, SaddlePointDistributed) {
  auto A = saddlePoint(worldComm(), 20, 15, 40);
  auto s = make();
  const double res = solveResidual(*s, A);
  report(tag("saddle point 340 world"), res);
  EXPECT_LT(res, kDirectSolveResidual);
}

TEST_P(DirectSolverTest, SaddlePointOnCommSelf) {
  auto A = saddlePoint(selfComm(), 10 + worldRank(), 8, 12);
  auto s = make();
  const double res = solveResidual(*s, A);
  EXPECT_LT(res, kDirectSolveResidual) << "rank " << worldRank();
  double worst = 0;
  MPI_Allreduce(&res, &worst, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  report(tag("saddle point self (max over ranks)"), worst);
}

TEST_P(DirectSolverTest, NonsymmetricDistributed) {
  auto A = laplacian(worldComm(), 25, 16, 0.4);
  Teuchos::ParameterList opts;
  if (GetParam() == "MUMPS") opts.set("Symmetric", false);
  auto s = make(opts);
  const double res = solveResidual(*s, A);
  report(tag("convection-diffusion 400 world"), res);
  EXPECT_LT(res, kDirectSolveResidual);
}

TEST_P(DirectSolverTest, RankOwningNoRows) {
  // All rows on rank 0, none elsewhere (a coarse problem on few ranks).
  auto comm = worldComm();
  const int nx = 12, ny = 10;
  auto full = laplacian(selfComm(), nx, ny);
  const GO n = GO(nx) * ny;
  auto map = rcp(new Map(n, comm->getRank() == 0 ? size_t(n) : 0, 0, comm));
  auto A = rcp(new CrsMatrix(map, 5));
  for (LO lr = 0; lr < LO(map->getNodeNumElements()); ++lr) {
    CrsMatrix::local_inds_host_view_type inds;
    CrsMatrix::values_host_view_type v;
    full->getLocalRowView(lr, inds, v);
    for (size_t e = 0; e < inds.extent(0); ++e) {
      const GO c = full->getColMap()->getGlobalElement(inds(e));
      const double a = v(e);
      A->insertGlobalValues(map->getGlobalElement(lr), 1, &a, &c);
    }
  }
  A->fillComplete();
  auto s = make();
  const double res = solveResidual(*s, A, 2);
  report(tag("Laplacian 120, all rows on rank 0"), res);
  EXPECT_LT(res, kDirectSolveResidual);
}

TEST_P(DirectSolverTest, MultipleRightHandSides) {
  auto A = saddlePoint(worldComm(), 16, 16, 30);
  auto s = make();
  const double res = solveResidual(*s, A, 4);
  report(tag("saddle point, 4 right-hand sides"), res);
  EXPECT_LT(res, kDirectSolveResidual);
}

TEST_P(DirectSolverTest, RefactorisationReusesSymbolic) {
  for (const auto& comm : {worldComm(), selfComm()}) {
    auto A = saddlePoint(comm, 18, 12, 25);
    auto s = make();
    MultiVector b(A->getRowMap(), 2), x(A->getRowMap(), 2), xOld(A->getRowMap(), 2);
    b.randomize();
    s->symbolic(A);
    s->numeric();
    s->solve(b, xOld);
    EXPECT_LT(relResidual(*A, xOld, b), kDirectSolveResidual);

    // New values, same pattern (a Newton iteration): stiffen K, rescale B.
    const GO n = 18 * 12;
    modifyValues(*A, [n](GO i, GO j, double a) {
      if (i < n && j < n) return i == j ? 2.0 * a + 1.5 : 2.0 * a;
      return 3.0 * a;
    });
    s->numeric();  // no symbolic(): the analysis is reused
    s->solve(b, x);
    const double res = relResidual(*A, x, b);
    EXPECT_LT(res, kDirectSolveResidual);
    // The old solution is wrong for the new matrix: the new values were used.
    EXPECT_GT(relResidual(*A, xOld, b), 1e-2);
    if (comm == worldComm()) report(tag("refactorised saddle point world"), res);

    if (auto* m = dynamic_cast<ddc::MumpsSolver*>(s.get())) {
      EXPECT_EQ(m->numSymbolic(), 1);
      EXPECT_EQ(m->numNumeric(), 2);
    } else if (auto* a = dynamic_cast<ddc::Amesos2Solver*>(s.get())) {
      EXPECT_EQ(a->numSymbolic(), 1);
      EXPECT_EQ(a->numNumeric(), 2);
    }
  }
}

TEST_P(DirectSolverTest, SingularMatrixThrowsSolverError) {
  for (const auto& comm : {worldComm(), selfComm()}) {
    // Zero the row and column of one DOF (entries kept, values 0).
    auto A = laplacian(comm, 10, 10);
    const GO dead = 57;
    modifyValues(*A, [dead](GO i, GO j, double a) { return (i == dead || j == dead) ? 0.0 : a; });
    auto s = make();
    s->symbolic(A);
    const std::string backEnd = GetParam();
    expectThrowWith<ddc::SolverError>([&] { s->numeric(); }, {backEnd});
    if (GetParam() == "MUMPS") expectThrowWith<ddc::SolverError>([&] { s->numeric(); }, {"INFOG(1)"});
    // A solve after the failure is a usage error, not a silent wrong answer.
    MultiVector b(A->getRowMap(), 1), x(A->getRowMap(), 1);
    EXPECT_THROW(s->solve(b, x), std::logic_error);
  }
}

TEST_P(DirectSolverTest, CoexistingInstances) {
  // FETI-DP: one solver per subdomain on MPI_COMM_SELF plus a distributed
  // coarse one, alive together, used in interleaved order.
  auto Aself = saddlePoint(selfComm(), 9, 7 + worldRank(), 10);
  auto Aworld = laplacian(worldComm(), 20, 11);
  auto Aself2 = laplacian(selfComm(), 8, 8);
  auto s1 = make(), s2 = make(), s3 = make();
  s1->symbolic(Aself);
  s2->symbolic(Aworld);
  s3->symbolic(Aself2);
  s2->numeric();
  s1->numeric();
  s3->numeric();
  for (int round = 0; round < 2; ++round) {
    for (auto [s, A] : {std::make_pair(s3.get(), Aself2), std::make_pair(s2.get(), Aworld),
                        std::make_pair(s1.get(), Aself)}) {
      MultiVector b(A->getRowMap(), 1), x(A->getRowMap(), 1);
      b.randomize();
      s->solve(b, x);
      EXPECT_LT(relResidual(*A, x, b), kDirectSolveResidual);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BackEnds, DirectSolverTest, ::testing::Values("MUMPS", "Amesos2"),
                         [](const auto& info) { return info.param; });

// ---- back-end specifics ----------------------------------------------------

TEST(MumpsSolver, RejectsNonContiguousNumbering) {
  auto A = laplacian(worldComm(), 8, 8, 0.0, /*base=*/1);  // GIDs 1..N
  ddc::MumpsSolver s;
  EXPECT_THROW(s.symbolic(A), std::invalid_argument);
}

TEST(MumpsSolver, EveryOrderingSolves) {
  // INFOG(7) reports the ordering MUMPS used (user guide: 0 AMD, 1 given by the user, 2 AMF, 4 PORD,
  // 6 QAMD); METIS's is given (on 1 and 2 ranks: the pattern is gathered to rank 0).
  const std::vector<std::pair<std::string, int>> orderings{
      {"AMD", 0}, {"AMF", 2}, {"PORD", 4}, {"QAMD", 6}, {"METIS", 1}};
  auto A = saddlePoint(worldComm(), 14, 10, 20);
  for (const auto& [name, code] : orderings) {
    Teuchos::ParameterList p;
    p.set("Ordering", name);
    ddc::MumpsSolver s(p);
    EXPECT_LT(solveResidual(s, A), kDirectSolveResidual) << name;
    EXPECT_EQ(s.orderingUsed(), code) << name;
  }
  Teuchos::ParameterList p;
  p.set("Memory Relaxation Percent", 5);
  ddc::MumpsSolver s(p);
  EXPECT_LT(solveResidual(s, A), kDirectSolveResidual);
  EXPECT_GE(s.memoryRelaxationPercent(), 5);
}

/// Single precision (smumps) keeps about 7 digits: on the Laplacian (condition ~ 100) the residual lies
/// between float's round-off and what double precision reaches, so both bounds show the arithmetic used.
constexpr double kSingleSolveResidual = 1e-5;
constexpr double kDoubleRoundOffResidual = 1e-12;

TEST(MumpsSolver, SinglePrecisionSolvesToFloatAccuracy) {
  auto A = laplacian(worldComm(), 30, 20);
  for (const bool symmetric : {true, false}) {
    Teuchos::ParameterList p;
    p.set("Precision", std::string("Single"));
    p.set("Symmetric", symmetric);
    ddc::MumpsSolver s(p);
    const double res = solveResidual(s, A);
    report(std::string("MUMPS single precision, ") + (symmetric ? "LDL^T" : "LU"), res);
    EXPECT_LT(res, kSingleSolveResidual);
    EXPECT_GT(res, kDoubleRoundOffResidual) << "the solve was not in single precision";
    // A second factorisation reuses the analysis, as in double precision.
    s.numeric();
    MultiVector b(A->getRowMap(), 1), x(A->getRowMap(), 1);
    b.randomize();
    s.solve(b, x);
    EXPECT_LT(relResidual(*A, x, b), kSingleSolveResidual);
    EXPECT_EQ(s.numSymbolic(), 1);
    EXPECT_EQ(s.numNumeric(), 2);
  }
}

TEST(MumpsSolver, MemoryRelaxationRetry) {
  // With no relaxation this saddle point overflows MUMPS's estimate on 2
  // ranks (INFOG(1) = -9, delayed pivots); the retry with 20 % succeeds.
  auto A = saddlePoint(worldComm(), 40, 30, 300);
  Teuchos::ParameterList p;
  p.set("Memory Relaxation Percent", 0);
  ddc::MumpsSolver s(p);
  const double res = solveResidual(s, A);
  report("MUMPS saddle point 1500, relaxation 0 -> " + std::to_string(s.memoryRelaxationPercent()), res);
  EXPECT_LT(res, kDirectSolveResidual);
  EXPECT_TRUE(s.memoryRelaxationPercent() == 0 || s.memoryRelaxationPercent() == 20);
}

// The Schur capability, checked against A itself (Tpetra's apply), never
// against a second factorisation: with b = 0 and x_s = e_j, expand() gives
// x_i = -A_ii^{-1} A_is e_j, so (A x)_s is column j of S = A_ss - A_si
// A_ii^{-1} A_is and (A x)_i = 0; with b random, condense() / a dense solve
// with S / expand() solve A x = b. Interior rows (A x)_i = b_i, Schur rows
// agree with S up to round-off in the entries of S (|S_ij| <= 4).
TEST(MumpsSolver, SchurComplementAndCondensedSolves) {
  // METIS's ordering is given to MUMPS with the Schur rows last.
  for (const std::string ordering : {"Auto", "METIS"})
  for (const bool symmetric : {true, false}) {
    SCOPED_TRACE(ordering);
    auto A = laplacian(selfComm(), 7, 6, symmetric ? 0.0 : 0.3);
    const LO n = LO(A->getNodeNumRows());
    const std::vector<LO> rows{29, 3, 17, 10, 41};  // deliberately unsorted
    const size_t ns = rows.size();
    Teuchos::ParameterList p;
    p.set("Symmetric", symmetric);
    p.set("Ordering", ordering);
    ddc::MumpsSolver s(p);
    ASSERT_TRUE(s.setSchurIndices(rows));
    s.symbolic(A);
    s.numeric();
    std::vector<double> S;
    s.schurComplement(S);
    ASSERT_EQ(S.size(), ns * ns);
    MultiVector x(A->getRowMap(), 1), ax(A->getRowMap(), 1);
    const size_t nn = static_cast<size_t>(n);
    std::vector<double> zero(nn, 0.0), g(ns), xs(ns), xv(nn);
    for (size_t j = 0; j < ns; ++j) {
      s.condense(zero.data(), g.data());
      for (double v : g) EXPECT_EQ(v, 0.0);
      std::fill(xs.begin(), xs.end(), 0.0);
      xs[j] = 1.0;
      s.expand(xs.data(), xv.data());
      {
        auto xd = x.getDataNonConst(0);
        std::copy(xv.begin(), xv.end(), xd.begin());
      }
      A->apply(x, ax);
      auto a = ax.getData(0);
      for (size_t i = 0; i < ns; ++i)
        EXPECT_NEAR(a[rows[i]], S[i + j * ns], kDirectSolveResidual) << "S(" << i << ", " << j << ")";
      for (LO r = 0; r < n; ++r)
        if (std::find(rows.begin(), rows.end(), r) == rows.end()) EXPECT_NEAR(a[r], 0.0, kDirectSolveResidual);
    }
    // A full solve through the condensed system.
    MultiVector b(A->getRowMap(), 1);
    b.randomize();
    std::vector<double> bv(nn);
    {
      auto bd = b.getData(0);
      std::copy(bd.begin(), bd.end(), bv.begin());
    }
    s.condense(bv.data(), g.data());
    const int m = static_cast<int>(ns);
    Teuchos::SerialDenseMatrix<int, double> Sd(m, m);
    Teuchos::SerialDenseVector<int, double> gd(m), xd(m);
    for (size_t i = 0; i < ns; ++i) {
      gd(int(i)) = g[i];
      for (size_t j = 0; j < ns; ++j) Sd(int(i), int(j)) = S[i + j * ns];
    }
    Teuchos::SerialDenseSolver<int, double> dense;
    dense.setMatrix(Teuchos::rcpFromRef(Sd));
    dense.setVectors(Teuchos::rcpFromRef(xd), Teuchos::rcpFromRef(gd));
    ASSERT_EQ(dense.solve(), 0);
    for (size_t i = 0; i < ns; ++i) xs[i] = xd(int(i));
    s.expand(xs.data(), xv.data());
    {
      auto xdv = x.getDataNonConst(0);
      std::copy(xv.begin(), xv.end(), xdv.begin());
    }
    const double res = relResidual(*A, x, b);
    report(std::string("MUMPS condense / expand, ") + (symmetric ? "SYM=2" : "SYM=0"), res);
    EXPECT_LT(res, kDirectSolveResidual);
    // solve() with Schur rows: the interior problem, x_s = 0.
    s.solve(b, x);
    A->apply(x, ax);
    auto a = ax.getData(0);
    auto bd = b.getData(0);
    auto xd2 = x.getData(0);
    for (LO r = 0; r < n; ++r) {
      if (std::find(rows.begin(), rows.end(), r) == rows.end()) EXPECT_NEAR(a[r], bd[r], kDirectSolveResidual);
      else EXPECT_EQ(xd2[r], 0.0);
    }
    EXPECT_THROW(s.expand(xs.data(), xv.data()), std::logic_error);  // solve() ended the condensed pair
  }
}

TEST(Amesos2Solver, GathersOnlyWhenDistributed) {
  ddc::Amesos2Solver s;
  auto A = laplacian(worldComm(), 10, 10);
  EXPECT_LT(solveResidual(s, A), kDirectSolveResidual);
  EXPECT_EQ(s.gathersToRoot(), worldComm()->getSize() > 1);
  auto B = laplacian(selfComm(), 10, 10);
  EXPECT_LT(solveResidual(s, B), kDirectSolveResidual);
  EXPECT_FALSE(s.gathersToRoot());
  EXPECT_EQ(s.name(), "Amesos2/KLU2");
  EXPECT_FALSE(s.setSchurIndices({0}));  // no Schur capability: FETI-DP falls back to explicit Phi
  std::vector<double> S;
  EXPECT_THROW(s.schurComplement(S), std::logic_error);
}

TEST(Amesos2Solver, AcceptsAnyGlobalNumbering) {
  ddc::Amesos2Solver s;
  auto A = laplacian(worldComm(), 9, 11, 0.0, /*base=*/1);
  const double res = solveResidual(s, A);
  EXPECT_LT(res, kDirectSolveResidual);
}

// CHOLMOD: serial, SPD. Every matrix here lives on MPI_COMM_SELF (a
// different one per rank, as FETI-DP's subdomains) unless a test says so.

/// Solve with MUMPS for comparison.
MultiVector mumpsSolution(const RCP<const CrsMatrix>& A, const MultiVector& b) {
  ddc::MumpsSolver mumps;
  MultiVector x(A->getRowMap(), b.getNumVectors());
  mumps.symbolic(A);
  mumps.numeric();
  mumps.solve(b, x);
  return x;
}

TEST(CholmodSolver, SolvesSpdLikeMumps) {
  for (const auto& [nx, nz] : {std::make_pair(5, 4), std::make_pair(7, 6)}) {
    auto A = elasticity3d(selfComm(), nx, nx + worldRank(), nz);
    ddc::CholmodSolver s;
    EXPECT_FALSE(s.setSchurIndices({0}));  // no Schur capability: FETI-DP uses Phi
    MultiVector b(A->getRowMap(), 1), x(A->getRowMap(), 1);
    b.randomize();
    s.symbolic(A);
    s.numeric();
    s.solve(b, x);
    const double res = relResidual(*A, x, b), diff = relDifference(x, mumpsSolution(A, b));
    EXPECT_LT(res, kDirectSolveResidual);
    EXPECT_LT(diff, kDirectSolverAgreement);
    EXPECT_EQ(s.name(), "CHOLMOD");
    EXPECT_FALSE(s.usingFallback());
    EXPECT_EQ(s.orderingUsed(), "METIS");
    EXPECT_GT(s.factorNonzeros(), 0.0);
    const std::string n = std::to_string(A->getGlobalNumRows());
    report("CHOLMOD elasticity " + n + " residual", res);
    report("CHOLMOD elasticity " + n + " vs MUMPS", diff);
  }
}

TEST(CholmodSolver, EveryOrderingSolves) {
  auto A = elasticity3d(selfComm(), 6, 5, 5);
  for (const std::string ordering : {"METIS", "AMD", "NESDIS", "Auto"}) {
    Teuchos::ParameterList p;
    p.set("Ordering", ordering);
    ddc::CholmodSolver s(p);
    EXPECT_LT(solveResidual(s, A), kDirectSolveResidual) << ordering;
    if (ordering == "Auto") {
      EXPECT_TRUE(s.orderingUsed() == "AMD" || s.orderingUsed() == "METIS") << s.orderingUsed();
    } else {
      EXPECT_EQ(s.orderingUsed(), ordering);
    }
  }
}

TEST(CholmodSolver, SeveralColumnsInOneSolve) {
  // 1 column, kept blocks (3, 8, 3 again: the block workspaces are resized)
  // and a block wider than kKeptBlockColumns (temporary workspaces), each
  // column checked against a single-column solve.
  auto A = elasticity3d(selfComm(), 6, 6, 4);
  ddc::CholmodSolver s;
  s.symbolic(A);
  s.numeric();
  for (const size_t k : {size_t(1), size_t(3), size_t(8), size_t(3), ddc::CholmodSolver::kKeptBlockColumns + 9}) {
    MultiVector b(A->getRowMap(), k), x(A->getRowMap(), k), xj(A->getRowMap(), k);
    b.randomize();
    s.solve(b, x);
    EXPECT_LT(relResidual(*A, x, b), kDirectSolveResidual) << k << " columns";
    for (size_t j = 0; j < k; ++j) {
      auto bj = b.getVector(j);
      auto xjj = xj.getVectorNonConst(j);
      s.solve(*bj, *xjj);
    }
    EXPECT_LT(relDifference(x, xj), kDirectSolverAgreement) << k << " columns";
  }
  // x may be b itself.
  MultiVector b(A->getRowMap(), 2), x(A->getRowMap(), 2);
  b.randomize();
  s.solve(b, x);
  s.solve(b, b);
  EXPECT_LT(relDifference(b, x), kDirectSolverAgreement);
}

TEST(CholmodSolver, RefactorisationReusesSymbolic) {
  auto A = elasticity3d(selfComm(), 5, 6, 5);
  ddc::CholmodSolver s;
  MultiVector b(A->getRowMap(), 2), x(A->getRowMap(), 2), xOld(A->getRowMap(), 2);
  b.randomize();
  s.symbolic(A);
  s.numeric();
  s.solve(b, xOld);
  EXPECT_LT(relResidual(*A, xOld, b), kDirectSolveResidual);
  // New values, same pattern (a Newton iteration), still SPD: 2 A + 1.5 I.
  modifyValues(*A, [](GO i, GO j, double a) { return i == j ? 2.0 * a + 1.5 : 2.0 * a; });
  s.numeric();  // no symbolic(): the analysis is reused
  s.solve(b, x);
  EXPECT_LT(relResidual(*A, x, b), kDirectSolveResidual);
  EXPECT_GT(relResidual(*A, xOld, b), 1e-2);  // the new values were used
  EXPECT_LT(relDifference(x, mumpsSolution(A, b)), kDirectSolverAgreement);
  EXPECT_EQ(s.numSymbolic(), 1);
  EXPECT_EQ(s.numNumeric(), 2);
  // A new pattern: symbolic() again.
  auto A2 = laplacian(selfComm(), 11, 9);
  EXPECT_LT(solveResidual(s, A2), kDirectSolveResidual);
  EXPECT_EQ(s.numSymbolic(), 2);
  EXPECT_EQ(s.numNumeric(), 3);
}

TEST(CholmodSolver, PatternChangeIsLogicError) {
  // A copy of the Laplacian with room for one more entry per row (storage
  // not optimised by fillComplete), so that entries can be added later.
  const int nx = 8;
  auto L = laplacian(selfComm(), nx, 6);
  auto A = rcp(new CrsMatrix(L->getRowMap(), 6));
  for (LO lr = 0; lr < LO(L->getNodeNumRows()); ++lr) {
    CrsMatrix::local_inds_host_view_type inds;
    CrsMatrix::values_host_view_type v;
    L->getLocalRowView(lr, inds, v);
    for (size_t e = 0; e < inds.extent(0); ++e) {
      const GO c = L->getColMap()->getGlobalElement(inds(e));
      const double a = v(e);
      A->insertGlobalValues(L->getRowMap()->getGlobalElement(lr), 1, &a, &c);
    }
  }
  auto keepRoom = Teuchos::parameterList();
  keepRoom->set("Optimize Storage", false);
  A->fillComplete(keepRoom);
  ddc::CholmodSolver s;
  s.symbolic(A);
  s.numeric();
  // Couple the grid corners 0 and nx - 1, symmetrically.
  A->resumeFill();
  const auto& rows = *A->getRowMap();
  const auto& cols = *A->getColMap();
  const LO r0 = rows.getLocalElement(0), r1 = rows.getLocalElement(nx - 1);
  const LO c0 = cols.getLocalElement(0), c1 = cols.getLocalElement(nx - 1);
  const double v = -0.5;
  A->insertLocalValues(r0, 1, &v, &c1);
  A->insertLocalValues(r1, 1, &v, &c0);
  A->fillComplete(keepRoom);
  expectThrowWith<std::logic_error>([&] { s.numeric(); }, {"CHOLMOD", "pattern", "symbolic()"});
  MultiVector b(A->getRowMap(), 1), x(A->getRowMap(), 1);
  EXPECT_THROW(s.solve(b, x), std::logic_error);
  s.symbolic(A);  // the new pattern
  EXPECT_LT(solveResidual(s, A), kDirectSolveResidual);
}

TEST(CholmodSolver, IndefiniteFallsBackToMumps) {
  // A saddle-point matrix [K B^T; B 0] and a "tangent past a limit point"
  // (an SPD matrix shifted below its smallest eigenvalues): symmetric,
  // indefinite, nonsingular.
  std::vector<std::pair<std::string, RCP<CrsMatrix>>> cases{
      {"saddle point", saddlePoint(selfComm(), 10, 8 + worldRank(), 12)},
      {"shifted elasticity", elasticity3d(selfComm(), 5, 5, 4, -0.35)}};
  for (auto& [what, A] : cases) {
    ddc::CholmodSolver s;
    MultiVector b(A->getRowMap(), 3), x(A->getRowMap(), 3);
    b.randomize();
    s.symbolic(A);
    s.numeric();
    EXPECT_TRUE(s.usingFallback()) << what;
    EXPECT_EQ(s.name(), "CHOLMOD (indefinite: MUMPS)");
    s.solve(b, x);
    EXPECT_LT(relResidual(*A, x, b), kDirectSolveResidual) << what;
    // Refactorisation stays with MUMPS until the next symbolic().
    modifyValues(*A, [](GO, GO, double a) { return 1.5 * a; });
    s.numeric();
    s.solve(b, x);
    EXPECT_LT(relResidual(*A, x, b), kDirectSolveResidual) << what;
    EXPECT_TRUE(s.usingFallback());
    EXPECT_EQ(s.numNumeric(), 2);
    EXPECT_EQ(s.numSymbolic(), 1);
    auto spd = elasticity3d(selfComm(), 4, 4, 3);
    EXPECT_LT(solveResidual(s, spd), kDirectSolveResidual);
    EXPECT_FALSE(s.usingFallback()) << what;
    EXPECT_EQ(s.name(), "CHOLMOD");
  }
  // Rows numbered 1..N (not MUMPS' 0..N-1): the fallback factorises a
  // renumbered copy, refreshed by every numeric().
  auto A = laplacian(selfComm(), 9, 7, 0.0, /*base=*/1);
  modifyValues(*A, [](GO i, GO j, double a) { return i == j && i == 30 ? -a : a; });
  ddc::CholmodSolver s;
  EXPECT_LT(solveResidual(s, A), kDirectSolveResidual);
  EXPECT_TRUE(s.usingFallback());
  modifyValues(*A, [](GO i, GO j, double a) { return i == j ? a + 0.25 : a; });
  s.numeric();
  MultiVector b(A->getRowMap(), 1), x(A->getRowMap(), 1);
  b.randomize();
  s.solve(b, x);
  EXPECT_LT(relResidual(*A, x, b), kDirectSolveResidual);
}

TEST(CholmodSolver, IndefiniteWithoutFallbackThrows) {
  auto A = elasticity3d(selfComm(), 5, 5, 4, -0.35);
  Teuchos::ParameterList p;
  p.set("Indefinite Fallback", false);
  ddc::CholmodSolver s(p);
  s.symbolic(A);
  expectThrowWith<ddc::SolverError>([&] { s.numeric(); },
                                    {"CHOLMOD", "not positive definite", "column", "'Indefinite Fallback'"});
  EXPECT_FALSE(s.usingFallback());
  MultiVector b(A->getRowMap(), 1), x(A->getRowMap(), 1);
  EXPECT_THROW(s.solve(b, x), std::logic_error);
}

TEST(CholmodSolver, SingularAndNonFiniteMatricesThrowSolverError) {
  for (const bool fallback : {true, false}) {
    // Zero the row and column of one DOF (entries kept, values 0): a zero pivot.
    auto A = laplacian(selfComm(), 10, 10);
    const GO dead = 57;
    modifyValues(*A, [dead](GO i, GO j, double a) { return (i == dead || j == dead) ? 0.0 : a; });
    Teuchos::ParameterList p;
    p.set("Indefinite Fallback", fallback);
    ddc::CholmodSolver s(p);
    s.symbolic(A);
    if (fallback) {  // MUMPS finds it singular too
      expectThrowWith<ddc::SolverError>([&] { s.numeric(); }, {"CHOLMOD", "MUMPS", "INFOG(1) = -10"});
    } else {
      expectThrowWith<ddc::SolverError>([&] { s.numeric(); }, {"CHOLMOD", "column 57", "Indefinite Fallback"});
    }
    MultiVector b(A->getRowMap(), 1), x(A->getRowMap(), 1);
    EXPECT_THROW(s.solve(b, x), std::logic_error);
  }
  auto A = laplacian(selfComm(), 6, 6);
  modifyValues(*A, [](GO i, GO j, double a) { return i == 7 && j == 7 ? std::nan("") : a; });
  ddc::CholmodSolver s;
  s.symbolic(A);
  expectThrowWith<ddc::SolverError>([&] { s.numeric(); }, {"CHOLMOD", "entry (7, 7)", "nan"});
}

TEST(CholmodSolver, TinyMatrices) {
  // n = 0 (an empty block, e.g. a subdomain without interior DOFs), 1, 2.
  for (const int n : {0, 1, 2}) {
    auto A = laplacian(selfComm(), n, 1);
    ddc::CholmodSolver s;
    MultiVector b(A->getRowMap(), 2), x(A->getRowMap(), 2);
    b.randomize();
    s.symbolic(A);
    s.numeric();
    s.solve(b, x);
    if (n > 0) EXPECT_LT(relResidual(*A, x, b), kDirectSolveResidual) << "n = " << n;
    EXPECT_EQ(s.numNumeric(), 1);
    EXPECT_FALSE(s.usingFallback());
  }
}

TEST(CholmodSolver, DistributedMatrixIsInvalidArgument) {
  auto A = laplacian(worldComm(), 12, 10);
  ddc::CholmodSolver s;
  if (worldComm()->getSize() == 1) {
    // One rank: the world communicator is a serial one (a monolithic run on one rank).
    EXPECT_LT(solveResidual(s, A), kDirectSolveResidual);
  } else {
    expectThrowWith<std::invalid_argument>([&] { s.symbolic(A); },
                                           {"CHOLMOD", "serial", "MUMPS", "Solver/FETI-DP/Local Solver/Type"});
  }
}

TEST(CholmodSolver, CoexistingInstances) {
  // One solver per subdomain, used in interleaved order, with a MUMPS one.
  auto A1 = elasticity3d(selfComm(), 4, 5, 3 + worldRank());
  auto A2 = laplacian(selfComm(), 9, 8);
  auto A3 = saddlePoint(selfComm(), 7, 6, 8);
  ddc::CholmodSolver s1, s2, s3;
  ddc::MumpsSolver m;
  s1.symbolic(A1);
  s2.symbolic(A2);
  m.symbolic(A2);
  s3.symbolic(A3);
  s2.numeric();
  s3.numeric();
  m.numeric();
  s1.numeric();
  for (int round = 0; round < 2; ++round) {
    for (auto [s, A] : {std::make_pair<DirectSolver*>(&s3, A3), std::make_pair<DirectSolver*>(&s1, A1),
                        std::make_pair<DirectSolver*>(&m, A2), std::make_pair<DirectSolver*>(&s2, A2)}) {
      MultiVector b(A->getRowMap(), 1), x(A->getRowMap(), 1);
      b.randomize();
      s->solve(b, x);
      EXPECT_LT(relResidual(*A, x, b), kDirectSolveResidual) << s->name();
    }
  }
}

// ---- factory -----------------------------------------------------------------

TEST(DirectSolverFactory, DefaultsToMumpsAndFillsDefaults) {
  Teuchos::ParameterList p;
  auto s = DirectSolverFactory::withBuiltins().create(p, "Solver/Linear Solver");
  EXPECT_EQ(s->name(), "MUMPS");
  EXPECT_EQ(p.get<std::string>("Type"), "MUMPS");
  ASSERT_TRUE(p.isSublist("MUMPS"));
  EXPECT_EQ(p.sublist("MUMPS").get<std::string>("Ordering"), "Auto");
  EXPECT_EQ(p.sublist("MUMPS").get<int>("Memory Relaxation Percent"), 30);
  EXPECT_TRUE(p.sublist("MUMPS").get<bool>("Symmetric"));
}

TEST(DirectSolverFactory, CreatesCholmodAndFillsDefaults) {
  Teuchos::ParameterList p;
  p.set("Type", "CHOLMOD");
  auto s = DirectSolverFactory::withBuiltins().create(p, "Solver/FETI-DP/Local Solver");
  ASSERT_NE(dynamic_cast<ddc::CholmodSolver*>(s.get()), nullptr);
  EXPECT_EQ(s->name(), "CHOLMOD");
  ASSERT_TRUE(p.isSublist("CHOLMOD"));
  EXPECT_EQ(p.sublist("CHOLMOD").get<std::string>("Ordering"), "METIS");
  EXPECT_TRUE(p.sublist("CHOLMOD").get<bool>("Indefinite Fallback"));
  auto A = elasticity3d(selfComm(), 4, 4, 4);
  EXPECT_LT(solveResidual(*s, A), kDirectSolveResidual);
  // The options reach the solver: without the fallback an indefinite matrix is an error.
  Teuchos::ParameterList q;
  q.set("Type", "CHOLMOD");
  q.sublist("CHOLMOD").set("Indefinite Fallback", false);
  auto t = DirectSolverFactory::withBuiltins().create(q, "S");
  auto B = saddlePoint(selfComm(), 6, 5, 4);
  t->symbolic(B);
  EXPECT_THROW(t->numeric(), ddc::SolverError);
}

TEST(DirectSolverFactory, UnknownTypeNamesPathAndKnownTypes) {
  Teuchos::ParameterList p;
  p.set("Type", "Pardiso");
  expectThrowWith<ddc::InputError>(
      [&] { DirectSolverFactory::withBuiltins().create(p, "Solver/Linear Solver"); },
      {"Pardiso", "Solver/Linear Solver/Type", "'MUMPS'", "'Amesos2'", "'CHOLMOD'"});
}

TEST(DirectSolverFactory, MisspeltParametersNamePath) {
  const auto f = DirectSolverFactory::withBuiltins();
  {
    Teuchos::ParameterList p;
    p.set("Type", "MUMPS");
    p.sublist("MUMPS").set("Orderng", "PORD");
    expectThrowWith<ddc::InputError>([&] { f.create(p, "Solver/Linear Solver"); },
                                     {"Solver/Linear Solver/MUMPS/Orderng", "Ordering"});
  }
  {
    Teuchos::ParameterList p;
    p.set("Typ", "MUMPS");
    expectThrowWith<ddc::InputError>([&] { f.create(p, "Solver/Linear Solver"); },
                                     {"Solver/Linear Solver/Typ"});
  }
  {  // a misspelt option of the back end not chosen is still an error
    Teuchos::ParameterList p;
    p.set("Type", "MUMPS");
    p.sublist("Amesos2").set("SolverName", "KLU2");
    expectThrowWith<ddc::InputError>([&] { f.create(p, "S"); }, {"S/Amesos2/SolverName"});
  }
  {
    Teuchos::ParameterList p;
    p.set("Type", "MUMPS");
    p.sublist("MUMPS").set("Ordering", "SCOTCH");  // not inside Debian's MUMPS
    expectThrowWith<ddc::InputError>([&] { f.create(p, "S"); }, {"S/MUMPS/Ordering", "SCOTCH", "PORD", "METIS"});
  }
  {
    Teuchos::ParameterList p;
    p.set("Type", "MUMPS");
    p.sublist("MUMPS").set("Symmetric", "yes");
    expectThrowWith<ddc::InputError>([&] { f.create(p, "S"); }, {"S/MUMPS/Symmetric"});
  }
  {
    Teuchos::ParameterList p;
    p.set("Type", "MUMPS");
    p.sublist("CHOLMOD").set("Indefinite Fallbak", false);
    expectThrowWith<ddc::InputError>([&] { f.create(p, "Solver/FETI-DP/Local Solver"); },
                                     {"Solver/FETI-DP/Local Solver/CHOLMOD/Indefinite Fallbak", "Indefinite Fallback"});
  }
  {
    Teuchos::ParameterList p;
    p.set("Type", "CHOLMOD");
    p.sublist("CHOLMOD").set("Ordering", "COLAMD");
    expectThrowWith<ddc::InputError>([&] { f.create(p, "S"); }, {"S/CHOLMOD/Ordering", "COLAMD", "METIS", "AMD"});
  }
  {
    Teuchos::ParameterList p;
    p.set("Type", "Amesos2");
    p.sublist("Amesos2").set("Solver Name", "SuperLU");
    expectThrowWith<ddc::InputError>([&] { f.create(p, "S"); }, {"S/Amesos2/Solver Name", "SuperLU", "KLU2"});
  }
}

TEST(DirectSolverFactory, ValidParametersAreDocumented) {
  const auto valid = DirectSolverFactory::getValidParameters();
  ASSERT_TRUE(valid->isParameter("Type"));
  EXPECT_EQ(valid->get<std::string>("Type"), "MUMPS");
  for (const std::string back : {"MUMPS", "Amesos2", "CHOLMOD"}) {
    ASSERT_TRUE(valid->isSublist(back)) << back;
    const auto& sub = valid->sublist(back);
    EXPECT_GT(sub.numParams(), 0);
    for (auto it = sub.begin(); it != sub.end(); ++it)
      EXPECT_FALSE(sub.entry(it).docString().empty()) << back << "/" << sub.name(it);
  }
  EXPECT_FALSE(valid->getEntry("Type").docString().empty());
  const auto names = ddc::Amesos2Solver::availableSolvers();
  EXPECT_NE(std::find(names.begin(), names.end(), "KLU2"), names.end());
}

TEST(DirectSolverFactory, HostCodesRegisterTheirOwn) {
  auto f = DirectSolverFactory::withBuiltins();
  auto valid = rcp(new Teuchos::ParameterList("Mine"));
  valid->set("Tolerance", 1e-8, "a documented option");
  double seen = 0;
  f.add("Mine", {[&seen](const Teuchos::ParameterList& p) {
                   seen = p.get<double>("Tolerance");
                   return std::unique_ptr<DirectSolver>(new ddc::MumpsSolver());
                 },
                 valid, "test back end"});
  Teuchos::ParameterList p;
  p.set("Type", "Mine");
  auto s = f.create(p, "X");
  EXPECT_EQ(seen, 1e-8);
  EXPECT_EQ(f.names().size(), 4u);
  EXPECT_THROW(f.add("Mine", f.entry("MUMPS")), std::invalid_argument);
  DirectSolverFactory empty;
  Teuchos::ParameterList q;
  expectThrowWith<ddc::InputError>([&] { empty.create(q, "Y"); }, {"Y/Type", "MUMPS"});
}

}  // namespace
