#include "DDC_MpiRecords.hpp"
#include "DDC_Amesos2Solver.hpp"

#include <mpi.h>

#include <Amesos2.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

static_assert(std::is_same<GO, long long>::value, "gather code sends global indices as MPI_LONG_LONG");

std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> d(counts.size(), 0);
  for (size_t r = 1; r < counts.size(); ++r) d[r] = d[r - 1] + counts[r - 1];
  return d;
}

}  // namespace

struct Amesos2Solver::Impl {
  using Solver = Amesos2::Solver<CrsMatrix, MultiVector>;

  std::string solverName = "KLU2";
  Teuchos::RCP<const CrsMatrix> A;
  Teuchos::RCP<Solver> solver;  // on the matrix itself, or (gather mode) on rank 0's copy
  bool gather = false;
  MPI_Comm comm = MPI_COMM_SELF;
  int rank = 0;
  int size = 1;
  bool analysed = false;
  bool factored = false;
  int nSymbolic = 0;
  int nNumeric = 0;

  // local pattern of A as cached by symbolic() (both modes: pattern check)
  LO nLocal = 0;
  size_t nnzLocal = 0;
  std::vector<int> rowLen;      // entries per local row
  std::vector<GO> colGids;      // global column of every local entry, row by row
  std::vector<double> vals;     // values in the same order

  // gather mode, rank 0 only
  std::vector<int> rowCounts, rowDispls, nnzCounts, nnzDispls;
  std::vector<int> allRowLen;   // entries per gathered row
  std::vector<LO> allLocalCols; // column of every gathered entry, local to rootA's column map
  std::vector<double> allVals;
  std::vector<double> buf;      // gathered RHS / solution, column-major N x k
  Teuchos::RCP<const Map> rootMap;
  Teuchos::RCP<CrsMatrix> rootA;

  std::string label() const { return "Amesos2/" + solverName; }

  /// Run `f` on rank 0 only; if it throws there, every rank throws a
  /// SolverError with the message (an error on one rank reaches all ranks).
  template <class F>
  void onRoot(const char* phase, F&& f) {
    std::string msg;
    int failed = 0;
    if (rank == 0) {
      try {
        f();
      } catch (const std::exception& e) {
        msg = lastLineOf(e);
        failed = 1;
      }
    }
    MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
    if (!failed) return;
    int len = static_cast<int>(msg.size());
    MPI_Bcast(&len, 1, MPI_INT, 0, comm);
    msg.resize(len);
    MPI_Bcast(&msg[0], len, MPI_CHAR, 0, comm);
    DDC_THROW(SolverError, label() << " " << phase << " failed (on rank 0 after gathering the matrix): " << msg);
  }

  /// Read A's local rows: build the pattern cache, or refresh the values
  /// and return false if the pattern differs from the cache.
  bool collect(bool build) {
    const auto& colMap = *A->getColMap();
    CrsMatrix::local_inds_host_view_type inds;
    CrsMatrix::values_host_view_type v;
    if (build) {
      rowLen.assign(nLocal, 0);
      colGids.clear();
      colGids.reserve(A->getNodeNumEntries());
    }
    vals.resize(build ? A->getNodeNumEntries() : nnzLocal);
    size_t k = 0;
    for (LO lr = 0; lr < nLocal; ++lr) {
      A->getLocalRowView(lr, inds, v);
      const int len = static_cast<int>(inds.extent(0));
      if (build) {
        rowLen[lr] = len;
      } else if (rowLen[lr] != len || k + len > nnzLocal) {
        return false;
      }
      for (int e = 0; e < len; ++e, ++k) {
        const GO gc = colMap.getGlobalElement(inds(e));
        if (build) {
          colGids.push_back(gc);
        } else if (colGids[k] != gc) {
          return false;
        }
        vals[k] = v(e);
      }
    }
    if (build) nnzLocal = k;
    return k == nnzLocal;
  }

  void symbolicGather() {
    const auto rowMap = A->getRowMap();
    std::vector<GO> gids(nLocal);
    for (LO i = 0; i < nLocal; ++i) gids[i] = rowMap->getGlobalElement(i);
    int nl = static_cast<int>(nLocal), nnz = static_cast<int>(nnzLocal);
    if (rank == 0) {
      rowCounts.assign(size, 0);
      nnzCounts.assign(size, 0);
    }
    MPI_Gather(&nl, 1, MPI_INT, rowCounts.data(), 1, MPI_INT, 0, comm);
    MPI_Gather(&nnz, 1, MPI_INT, nnzCounts.data(), 1, MPI_INT, 0, comm);
    std::vector<GO> allGids, allColGids;
    if (rank == 0) {
      rowDispls = displacements(rowCounts);
      nnzDispls = displacements(nnzCounts);
      const size_t n = static_cast<size_t>(rowDispls.back() + rowCounts.back());
      const size_t nz = static_cast<size_t>(nnzDispls.back() + nnzCounts.back());
      allGids.resize(n);
      allRowLen.resize(n);
      allColGids.resize(nz);
      allVals.resize(nz);
    }
    MPI_Gatherv(gids.data(), nl, MPI_LONG_LONG, allGids.data(), rowCounts.data(), rowDispls.data(),
                MPI_LONG_LONG, 0, comm);
    MPI_Gatherv(rowLen.data(), nl, MPI_INT, allRowLen.data(), rowCounts.data(), rowDispls.data(), MPI_INT, 0,
                comm);
    MPI_Gatherv(colGids.data(), nnz, MPI_LONG_LONG, allColGids.data(), nnzCounts.data(), nnzDispls.data(),
                MPI_LONG_LONG, 0, comm);
    onRoot("symbolic factorisation", [&] {
      // Rank 0's copy lives on MPI_COMM_SELF, rows in gathered order (rank
      // by rank), so gathered vectors map to its local indices directly.
      auto self = Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
      const auto n = static_cast<Tpetra::global_size_t>(allGids.size());
      rootMap = Teuchos::rcp(new Map(n, Teuchos::ArrayView<const GO>(allGids), rowMap->getIndexBase(), self));
      std::vector<size_t> len(allRowLen.begin(), allRowLen.end());
      auto graph = Teuchos::rcp(new CrsGraph(rootMap, Teuchos::ArrayView<const size_t>(len)));
      size_t off = 0;
      for (size_t i = 0; i < len.size(); ++i) {
        graph->insertGlobalIndices(allGids[i], static_cast<LO>(len[i]), allColGids.data() + off);
        off += len[i];
      }
      graph->fillComplete(rootMap, rootMap);
      const auto& colMap = *graph->getColMap();
      allLocalCols.resize(allColGids.size());
      for (size_t k = 0; k < allColGids.size(); ++k) allLocalCols[k] = colMap.getLocalElement(allColGids[k]);
      rootA = Teuchos::rcp(new CrsMatrix(graph));
      rootA->fillComplete(rootMap, rootMap);
      solver = Amesos2::create<CrsMatrix, MultiVector>(solverName, rootA);
      solver->symbolicFactorization();
    });
  }

  void numericGather() {
    MPI_Gatherv(vals.data(), static_cast<int>(nnzLocal), MPI_DOUBLE, allVals.data(), nnzCounts.data(),
                nnzDispls.data(), MPI_DOUBLE, 0, comm);
    onRoot("numeric factorisation", [&] {
      rootA->resumeFill();
      size_t off = 0;
      for (size_t i = 0; i < allRowLen.size(); ++i) {
        const LO len = allRowLen[i];
        const LO done = rootA->replaceLocalValues(static_cast<LO>(i), len, allVals.data() + off,
                                                  allLocalCols.data() + off);
        if (done != len) throw std::logic_error("internal: gathered entry not in rank 0's pattern");
        off += len;
      }
      rootA->fillComplete(rootMap, rootMap);
      solver->numericFactorization();
    });
  }

  void solveGather(const MultiVector& b, MultiVector& x) {
    const size_t k = b.getNumVectors();
    const size_t n = rank == 0 ? static_cast<size_t>(rootMap->getNodeNumElements()) : 0;
    if (rank == 0) buf.assign(n * k, 0.0);
    for (size_t j = 0; j < k; ++j) {
      auto bj = b.getData(j);
      MPI_Gatherv(bj.getRawPtr(), static_cast<int>(nLocal), MPI_DOUBLE, rank == 0 ? buf.data() + j * n : nullptr,
                  rowCounts.data(), rowDispls.data(), MPI_DOUBLE, 0, comm);
    }
    onRoot("solve", [&] {
      MultiVector B(rootMap, Teuchos::ArrayView<const double>(buf), n, k);
      MultiVector X(rootMap, k);
      solver->solve(Teuchos::ptrFromRef(X), Teuchos::ptrFromRef(static_cast<const MultiVector&>(B)));
      X.get1dCopy(Teuchos::ArrayView<double>(buf), n);
    });
    for (size_t j = 0; j < k; ++j) {
      auto xj = x.getDataNonConst(j);
      MPI_Scatterv(rank == 0 ? buf.data() + j * n : nullptr, rowCounts.data(), rowDispls.data(), MPI_DOUBLE,
                   xj.getRawPtr(), static_cast<int>(nLocal), MPI_DOUBLE, 0, comm);
    }
  }
};

std::vector<std::string> Amesos2Solver::availableSolvers() {
  static const std::vector<std::string> available = [] {
    // Canonical spellings of the solvers Amesos2 13.2 knows (Amesos2_Factory.hpp).
    // Tacho is left out on purpose: Amesos2::query reports it, but it
    // segfaults in numericFactorization in Debian's Trilinos 13.2
    // (doc/trilinos-notes.md), and a crash is no way to tell a user about it.
    const std::vector<std::string> candidates{"KLU2",      "Basker", "ShyLUBasker", "SuperLU",  "SuperLU_MT",
                                              "SuperLU_Dist", "Umfpack", "Pardiso_MKL", "LAPACK",
                                              "MUMPS",     "STRUMPACK", "Cholmod",  "cuSOLVER"};
    std::vector<std::string> out;
    for (const auto& c : candidates)
      if (Amesos2::query(c)) out.push_back(c);
    return out;
  }();
  return available;
}

Teuchos::RCP<const Teuchos::ParameterList> Amesos2Solver::getValidParameters() {
  static Teuchos::RCP<const Teuchos::ParameterList> valid = [] {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Amesos2"));
    auto names = availableSolvers();
    if (names.empty()) names.push_back("KLU2");  // keeps the default valid; create() reports it missing
    pl->set("Solver Name", std::string("KLU2"),
            "Amesos2 solver (those compiled into this Trilinos). A matrix on more than one rank is gathered to "
            "rank 0 and factorised on MPI_COMM_SELF, since KLU2 is wrong on distributed matrices in this "
            "build. Tacho is not offered: it crashes in numericFactorization in Debian's Trilinos 13.2.",
            enumValidator(names, "Solver Name"));
    return Teuchos::RCP<const Teuchos::ParameterList>(pl);
  }();
  return valid;
}

Amesos2Solver::Amesos2Solver(const Teuchos::ParameterList& params) : impl_(std::make_unique<Impl>()) {
  Teuchos::ParameterList p(params);
  validateLevel(p, *getValidParameters(), "Amesos2");
  impl_->solverName = p.get<std::string>("Solver Name");
  DDC_INPUT_REQUIRE(impl_->solverName != "Tacho",
                    "parameter 'Amesos2/Solver Name': Tacho is disabled because it crashes in Debian's Trilinos 13.2; "
                    "use KLU2 or the MUMPS back end");
  DDC_INPUT_REQUIRE(Amesos2::query(impl_->solverName),
                    "parameter 'Amesos2/Solver Name': '" << impl_->solverName
                                                         << "' is not available in this Amesos2 build; available: "
                                                         << quotedNames(availableSolvers()));
}

Amesos2Solver::~Amesos2Solver() = default;

std::string Amesos2Solver::name() const { return impl_->label(); }
bool Amesos2Solver::gathersToRoot() const { return impl_->gather; }
int Amesos2Solver::numSymbolic() const { return impl_->nSymbolic; }
int Amesos2Solver::numNumeric() const { return impl_->nNumeric; }

void Amesos2Solver::symbolic(const Teuchos::RCP<const CrsMatrix>& A) {
  Impl& m = *impl_;
  if (A.is_null()) throw std::invalid_argument(m.label() + " symbolic(): null matrix");
  if (!A->isFillComplete()) throw std::invalid_argument(m.label() + " symbolic(): matrix is not fill-complete");
  const auto rowMap = A->getRowMap();
  if (!rowMap->isSameAs(*A->getRangeMap()) || !rowMap->isSameAs(*A->getDomainMap()))
    throw std::invalid_argument(m.label() + " symbolic(): row, range and domain maps must be the same");
  m.analysed = m.factored = false;
  m.solver = Teuchos::null;
  m.rootA = Teuchos::null;
  m.rootMap = Teuchos::null;
  m.A = A;
  m.comm = rawComm(A->getComm());
  m.rank = A->getComm()->getRank();
  m.size = A->getComm()->getSize();
  m.gather = m.size > 1;
  m.nLocal = static_cast<LO>(rowMap->getNodeNumElements());
  m.collect(true);
  if (m.gather) {
    m.symbolicGather();
  } else {
    try {
      m.solver = Amesos2::create<CrsMatrix, MultiVector>(m.solverName, A);
      m.solver->symbolicFactorization();
    } catch (const std::exception& e) {
      DDC_THROW(SolverError, m.label() << " symbolic factorisation failed: " << lastLineOf(e));
    }
  }
  m.analysed = true;
  ++m.nSymbolic;
}

void Amesos2Solver::numeric() {
  Impl& m = *impl_;
  if (!m.analysed) throw std::logic_error(m.label() + " numeric() called before symbolic()");
  m.factored = false;
  if (anyRank(m.comm, !m.collect(false)))
    throw std::logic_error(m.label() +
                           " numeric(): the sparsity pattern of the matrix changed since symbolic(); call "
                           "symbolic() again");
  if (m.gather) {
    m.numericGather();
  } else {
    try {
      m.solver->numericFactorization();
    } catch (const std::exception& e) {
      DDC_THROW(SolverError, m.label() << " numeric factorisation failed (singular matrix?): " << lastLineOf(e));
    }
  }
  m.factored = true;
  ++m.nNumeric;
}

void Amesos2Solver::solve(const MultiVector& b, MultiVector& x) {
  Impl& m = *impl_;
  if (!m.factored) throw std::logic_error(m.label() + " solve() called without a successful numeric()");
  const bool bad = x.getNumVectors() != b.getNumVectors() || b.getLocalLength() != static_cast<size_t>(m.nLocal) ||
                   x.getLocalLength() != static_cast<size_t>(m.nLocal);
  if (anyRank(m.comm, bad))
    throw std::invalid_argument(m.label() + " solve(): b and x must be distributed like the matrix rows and "
                                            "have the same number of columns");
  if (b.getNumVectors() == 0) return;
  if (m.gather) {
    m.solveGather(b, x);
  } else {
    try {
      m.solver->solve(Teuchos::ptrFromRef(x), Teuchos::ptrFromRef(b));
    } catch (const std::exception& e) {
      DDC_THROW(SolverError, m.label() << " solve failed: " << lastLineOf(e));
    }
  }
}

}  // namespace ddc
