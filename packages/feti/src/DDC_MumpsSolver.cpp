#include "DDC_MpiRecords.hpp"
#include "DDC_MumpsSolver.hpp"

#include <dmumps_c.h>
#include <smumps_c.h>
#include <metis.h>
#include <mpi.h>

#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>
#include <algorithm>
#include <climits>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_Parameters.hpp"

namespace ddc {

namespace {

// MUMPS control arrays are 1-based in the user guide; these helpers keep the
// code readable against it ("ICNTL(18) = 3").
template <class Struc>
MUMPS_INT& icntl(Struc& id, int i) { return id.icntl[i - 1]; }
template <class Struc>
MUMPS_INT infog(const Struc& id, int i) { return id.infog[i - 1]; }

/// The two MUMPS arithmetics behind one code path ("Precision"): the
/// instance's structure, its real type and its entry point.
struct DoublePrecision {
  using Struc = DMUMPS_STRUC_C;
  using Real = double;
  static void call(Struc* id) { dmumps_c(id); }
};
struct SinglePrecision {
  using Struc = SMUMPS_STRUC_C;
  using Real = float;
  static void call(Struc* id) { smumps_c(id); }
};

/// ICNTL(7) = 1: the ordering is given in PERM_IN (METIS's, computed here).
constexpr int kUserOrdering = 1;

const std::vector<std::string>& orderingNames() {
  static const std::vector<std::string> names{"Auto", "AMD", "AMF", "QAMD", "PORD", "METIS"};
  return names;
}

/// ICNTL(7) value for an "Ordering" name (MUMPS user guide §6.1).
int orderingCode(const std::string& o) {
  if (o == "AMD") return 0;
  if (o == "METIS") return kUserOrdering;
  if (o == "AMF") return 2;
  if (o == "PORD") return 4;
  if (o == "QAMD") return 6;
  return 7;  // Auto
}

/// Short explanation of the most common INFOG(1) error codes.
std::string explainInfog1(int code) {
  switch (code) {
    case -5: case -7: case -13: return "memory allocation failed";
    case -6: return "matrix is structurally singular";
    case -8: case -9: case -14: case -15: case -17: case -20:
      return "internal work array too small (raise 'Memory Relaxation Percent')";
    case -10: return "matrix is numerically singular";
    case -16: return "N out of range";
    case -22: return "invalid pointer array";
    case -40: return "matrix declared symmetric positive definite is not";
    default: return "see the MUMPS user guide, INFOG(1)";
  }
}


}  // namespace

/// One MUMPS instance in the arithmetic P and what it keeps between calls.
template <class P>
struct MumpsCore {
  using Real = typename P::Real;
  // parameters
  bool symmetric = true;
  int ordering = 7;
  int relaxation = 30;
  bool verbose = false;

  // MUMPS instance, bound to a duplicate of the matrix's communicator
  typename P::Struc id{};
  bool initialized = false;
  MPI_Comm comm = MPI_COMM_NULL;  // our duplicate
  MPI_Comm userComm = MPI_COMM_NULL;  // what it duplicates (to detect a change)
  int rank = 0;
  int size = 1;

  // matrix and cached distributed assembled input (1-based global indices)
  Teuchos::RCP<const CrsMatrix> A;
  MUMPS_INT n = 0;
  LO nLocal = 0;
  std::vector<MUMPS_INT> irn, jcn;
  std::vector<Real> a;
  std::vector<int> rowCounts, rowFirst;  // per rank: owned rows, first GID (gather layout)
  std::vector<double> rhs;               // centralised RHS / solution on rank 0 (one column)
  std::vector<Real> rhsReal;             // the same in P's arithmetic (single precision only)
  std::vector<MUMPS_INT> permIn;         // "METIS": PERM_IN on rank 0 (1-based pivot position per variable)

  // Schur complement (setSchurIndices): 1-based rows, S (column-major), and
  // the RHS / reduced RHS kept from condense() for expand()
  std::vector<MUMPS_INT> schurRows;
  std::vector<Real> schur, condRhs, redRhs;
  bool condensed = false;

  bool analysed = false;
  bool factored = false;
  int nSymbolic = 0;
  int nNumeric = 0;

  ~MumpsCore() { destroy(); }
  void call() { P::call(&id); }

  void destroy() noexcept {
    if (!initialized) return;
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) {
      id.job = -2;
      P::call(&id);
      MPI_Comm_free(&comm);
    }
    initialized = false;
    analysed = factored = false;
    comm = userComm = MPI_COMM_NULL;
  }

  void init(MPI_Comm user) {
    destroy();
    userComm = user;
    MPI_Comm_dup(user, &comm);
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
    id = typename P::Struc{};
    id.job = -1;
    id.par = 1;  // the host takes part in the factorisation
    id.sym = symmetric ? 2 : 0;  // 2: general symmetric (LDL^T, indefinite ok)
    id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm));
    P::call(&id);
    initialized = true;
    check("initialisation (JOB=-1)");
    // Output: silent unless "Verbose" (ICNTL(1..4)).
    icntl(id, 1) = verbose ? 6 : -1;
    icntl(id, 2) = verbose ? 0 : -1;
    icntl(id, 3) = verbose ? 6 : -1;
    icntl(id, 4) = verbose ? 2 : 0;
    icntl(id, 5) = 0;   // assembled matrix
    icntl(id, 7) = ordering;
    icntl(id, 14) = relaxation;
    icntl(id, 18) = 3;  // distributed assembled input: each rank its owned rows
    icntl(id, 20) = 0;  // dense centralised right-hand side
    icntl(id, 21) = 0;  // centralised solution (overwrites rhs on the host)
    icntl(id, 28) = 1;  // sequential analysis: ICNTL(7) applies (no ParMETIS/PT-SCOTCH)
  }

  /// "METIS": a nested-dissection ordering of the matrix's graph by METIS
  /// (METIS_NodeND) on rank 0, handed to MUMPS as PERM_IN (ICNTL(7) = 1),
  /// because Debian's MUMPS has no METIS inside. The pattern is gathered to
  /// rank 0, as MUMPS' own sequential analysis (ICNTL(28) = 1) does; the
  /// Schur variables, if any, are ordered last. Collective.
  void orderByMetis() {
    const int mine = static_cast<int>(irn.size());
    std::vector<int> counts(static_cast<size_t>(size)), displs(static_cast<size_t>(size), 0);
    MPI_Gather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
    for (int r = 1; r < size; ++r) displs[size_t(r)] = displs[size_t(r) - 1] + counts[size_t(r) - 1];
    const size_t total = rank == 0 ? size_t(displs.back()) + size_t(counts.back()) : 0;
    std::vector<MUMPS_INT> rows(std::max<size_t>(total, 1)), cols(std::max<size_t>(total, 1));
    MPI_Gatherv(irn.data(), mine, MPI_INT, rows.data(), counts.data(), displs.data(), MPI_INT, 0, comm);
    MPI_Gatherv(jcn.data(), mine, MPI_INT, cols.data(), counts.data(), displs.data(), MPI_INT, 0, comm);
    permIn.clear();
    int status = rank == 0 ? metisOnRoot(total, rows, cols) : METIS_OK;
    // Every rank throws, or none: the analysis that follows is collective.
    MPI_Bcast(&status, 1, MPI_INT, 0, comm);
    if (status != METIS_OK) DDC_THROW(SolverError, "MUMPS: METIS_NodeND failed (status " << status << "), N = " << n);
  }

  /// orderByMetis() on rank 0: PERM_IN from the gathered pattern (1-based
  /// rows / cols of `total` entries). Returns METIS' status.
  int metisOnRoot(size_t total, std::vector<MUMPS_INT>& rows, std::vector<MUMPS_INT>& cols) {
    // The symmetric graph without the diagonal, in CSR (idx_t, 0-based).
    std::vector<idx_t> ptr(size_t(n) + 1, 0);
    for (size_t k = 0; k < total; ++k)
      if (rows[k] != cols[k]) ++ptr[size_t(rows[k])], ++ptr[size_t(cols[k])];
    for (size_t i = 0; i < size_t(n); ++i) ptr[i + 1] += ptr[i];
    std::vector<idx_t> adj(static_cast<size_t>(ptr[size_t(n)]));
    std::vector<idx_t> fill(ptr.begin(), ptr.end() - 1);
    for (size_t k = 0; k < total; ++k)
      if (rows[k] != cols[k]) {
        adj[size_t(fill[size_t(rows[k] - 1)]++)] = cols[k] - 1;
        adj[size_t(fill[size_t(cols[k] - 1)]++)] = rows[k] - 1;
      }
    std::vector<MUMPS_INT>().swap(rows), std::vector<MUMPS_INT>().swap(cols);
    // Each neighbour once (an unsymmetric pattern gives both (i, j) and (j, i)).
    idx_t out = 0;
    for (size_t i = 0; i < size_t(n); ++i) {
      const idx_t b = ptr[i], e = ptr[i + 1];
      std::sort(adj.begin() + b, adj.begin() + e);
      ptr[i] = out;
      for (idx_t k = b; k < e; ++k)
        if (k == b || adj[size_t(k)] != adj[size_t(k) - 1]) adj[size_t(out++)] = adj[size_t(k)];
    }
    ptr[size_t(n)] = out;
    idx_t nv = n;
    std::vector<idx_t> perm(static_cast<size_t>(n)), iperm(static_cast<size_t>(n));
    const int status = METIS_NodeND(&nv, ptr.data(), adj.data(), nullptr, nullptr, perm.data(), iperm.data());
    if (status != METIS_OK) return status;
    // PERM_IN(i) = the pivot position of variable i (perm[k]: the variable
    // METIS puts at position k, METIS manual 5.1 §5.8); the Schur rows last,
    // in their given order (MUMPS refuses another, INFOG(1) = -4).
    std::vector<char> schur(size_t(n), 0);
    for (MUMPS_INT r : schurRows) schur[size_t(r - 1)] = 1;
    permIn.resize(size_t(n));
    MUMPS_INT next = 1;
    for (size_t k = 0; k < size_t(n); ++k)
      if (!schur[size_t(perm[k])]) permIn[size_t(perm[k])] = next++;
    for (MUMPS_INT r : schurRows) permIn[size_t(r - 1)] = next++;
    return status;
  }

  /// INFOG(1) is the same on every rank, so every rank throws together.
  void check(const char* phase) const {
    const int c = infog(id, 1);
    if (c >= 0) return;
    DDC_THROW(SolverError, "MUMPS " << phase << " failed: INFOG(1) = " << c << ", INFOG(2) = "
                                    << infog(id, 2) << " (" << explainInfog1(c) << "), N = " << n);
  }

  void run(int job, const char* phase) {
    id.job = job;
    P::call(&id);
    check(phase);
  }

  /// Append the kept entries of local row `lrow` (lower triangle if
  /// symmetric) to irn/jcn/a (build) or compare with the cache and refresh a.
  /// Returns false if the pattern differs from the cache (refresh mode).
  bool collect(bool build) {
    const auto& rowMap = *A->getRowMap();
    const auto& colMap = *A->getColMap();
    if (build) {
      irn.clear();
      jcn.clear();
      a.clear();
      irn.reserve(A->getNodeNumEntries());
      jcn.reserve(A->getNodeNumEntries());
      a.reserve(A->getNodeNumEntries());
    }
    size_t k = 0;
    CrsMatrix::local_inds_host_view_type inds;
    CrsMatrix::values_host_view_type vals;
    for (LO lr = 0; lr < nLocal; ++lr) {
      const GO gr = rowMap.getGlobalElement(lr);
      A->getLocalRowView(lr, inds, vals);
      for (size_t e = 0; e < inds.extent(0); ++e) {
        const GO gc = colMap.getGlobalElement(inds(e));
        if (symmetric && gc > gr) continue;  // SYM=2 reads one triangle only
        if (build) {
          irn.push_back(static_cast<MUMPS_INT>(gr + 1));
          jcn.push_back(static_cast<MUMPS_INT>(gc + 1));
          a.push_back(vals(e));
        } else {
          if (k >= jcn.size() || jcn[k] != gc + 1 || irn[k] != gr + 1) return false;
          a[k] = vals(e);
        }
        ++k;
      }
    }
    return build || k == jcn.size();
  }
};

/// The instance of the chosen arithmetic; visit() calls f on it.
struct MumpsSolver::Impl {
  std::unique_ptr<MumpsCore<DoublePrecision>> d;
  std::unique_ptr<MumpsCore<SinglePrecision>> s;
  template <class F>
  auto visit(F f) {
    return s ? f(*s) : f(*d);
  }
  template <class F>
  auto visit(F f) const {
    return s ? f(static_cast<const MumpsCore<SinglePrecision>&>(*s))
             : f(static_cast<const MumpsCore<DoublePrecision>&>(*d));
  }
};

MumpsSolver::MumpsSolver(const Teuchos::ParameterList& params) : impl_(std::make_unique<Impl>()) {
  Teuchos::ParameterList p(params);
  validateLevel(p, *getValidParameters(), "MUMPS");
  if (p.get<std::string>("Precision") == "Single")
    impl_->s = std::make_unique<MumpsCore<SinglePrecision>>();
  else
    impl_->d = std::make_unique<MumpsCore<DoublePrecision>>();
  impl_->visit([&](auto& m) {
    m.symmetric = p.get<bool>("Symmetric");
    m.ordering = orderingCode(p.get<std::string>("Ordering"));
    m.relaxation = p.get<int>("Memory Relaxation Percent");
    m.verbose = p.get<bool>("Verbose");
  });
}

MumpsSolver::~MumpsSolver() = default;

Teuchos::RCP<const Teuchos::ParameterList> MumpsSolver::getValidParameters() {
  static Teuchos::RCP<const Teuchos::ParameterList> valid = [] {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("MUMPS"));
    pl->set("Symmetric", true,
            "Matrix is symmetric: factorise LDL^T (MUMPS SYM=2, symmetric indefinite, so saddle-point "
            "matrices with Lagrange multipliers work) reading only the lower triangle. false: LU of the "
            "full matrix (SYM=0).");
    pl->set("Ordering", std::string("Auto"),
            "Fill-reducing ordering, MUMPS ICNTL(7): Auto (7, MUMPS chooses), AMD (0), AMF (2), QAMD (6), "
            "PORD (4), or METIS: METIS_NodeND's nested dissection, computed on rank 0 and given to MUMPS "
            "(ICNTL(7) = 1), because Debian's MUMPS has no METIS/SCOTCH inside (Auto picks among the others).",
            enumValidator(orderingNames(), "Ordering"));
    pl->set("Memory Relaxation Percent", 30,
            "MUMPS ICNTL(14): percentage added to the estimated working space. On INFOG(1) = -8/-9 the "
            "factorisation is retried once with twice this value (at least 20), kept for later factorisations.",
            between(0, 100000));
    pl->set("Precision", std::string("Double"),
            "Arithmetic of the factors and solves: Double (dmumps), or Single (smumps: half the factor's bytes, "
            "about half the time to factorise and solve, relative accuracy about 1e-7 times the condition "
            "number). Single suits a solve inside a preconditioner, e.g. the coarse solve of BDDC "
            "(doc/feti-dp.md, 'BDDC'); the right-hand side and solution stay double.",
            enumValidator({"Double", "Single"}, "Precision"));
    pl->set("Verbose", false, "Let MUMPS print its diagnostics (ICNTL(1..4)); silent otherwise.");
    return Teuchos::RCP<const Teuchos::ParameterList>(pl);
  }();
  return valid;
}

void MumpsSolver::symbolic(const Teuchos::RCP<const CrsMatrix>& A) {
  return impl_->visit([&](auto& m) {
    if (A.is_null()) throw std::invalid_argument("MUMPS symbolic(): null matrix");
    if (!A->isFillComplete()) throw std::invalid_argument("MUMPS symbolic(): matrix is not fill-complete");
    const MPI_Comm user = rawComm(A->getComm());
    int same = MPI_UNEQUAL;
    if (m.initialized) MPI_Comm_compare(user, m.userComm, &same);
    if (!m.initialized || same != MPI_IDENT) m.init(user);

    const auto rowMap = A->getRowMap();
    const GO nGlobal = static_cast<GO>(rowMap->getGlobalNumElements());
    // The centralised RHS is laid out by global index, and MUMPS wants 1-based
    // global indices < 2^31: require a one-to-one contiguous 0..N-1 map.
    int local[3] = {rowMap->isContiguous() ? 1 : 0, static_cast<int>(rowMap->getNodeNumElements()), 0};
    GO first = rowMap->getNodeNumElements() > 0 ? rowMap->getMinGlobalIndex() : 0;
    const bool sameMaps = rowMap->isSameAs(*A->getRangeMap()) && rowMap->isSameAs(*A->getDomainMap());
    std::vector<int> all(3 * m.size);
    std::vector<GO> firsts(m.size);
    MPI_Allgather(local, 3, MPI_INT, all.data(), 3, MPI_INT, m.comm);
    MPI_Allgather(&first, 1, MPI_LONG_LONG, firsts.data(), 1, MPI_LONG_LONG, m.comm);
    bool ok = sameMaps && nGlobal <= INT_MAX && rowMap->getIndexBase() == 0;
    std::vector<std::pair<GO, int>> ranges;
    for (int r = 0; r < m.size; ++r) {
      ok = ok && all[3 * r] == 1;
      if (all[3 * r + 1] > 0) ranges.emplace_back(firsts[r], all[3 * r + 1]);
    }
    std::sort(ranges.begin(), ranges.end());
    GO next = 0;
    for (const auto& rg : ranges) {
      ok = ok && rg.first == next;
      next = rg.first + rg.second;
    }
    ok = ok && next == nGlobal;
    if (!ok)
      throw std::invalid_argument(
          "MUMPS symbolic(): the matrix's row map must equal its range and domain maps and be one-to-one and "
          "contiguous with global indices 0..N-1 (N < 2^31); got N = " +
          std::to_string(nGlobal));

    m.A = A;
    m.n = static_cast<MUMPS_INT>(nGlobal);
    m.nLocal = static_cast<LO>(rowMap->getNodeNumElements());
    m.rowCounts.resize(m.size);
    m.rowFirst.resize(m.size);
    for (int r = 0; r < m.size; ++r) {
      m.rowCounts[r] = all[3 * r + 1];
      m.rowFirst[r] = static_cast<int>(firsts[r]);
    }
    m.collect(true);

    auto& id = m.id;
    id.n = m.n;
    id.nnz_loc = static_cast<MUMPS_INT8>(m.irn.size());
    id.nz_loc = static_cast<MUMPS_INT>(m.irn.size());
    // MUMPS may dereference the arrays even when empty: never pass null.
    if (m.irn.empty()) {
      m.irn.reserve(1);
      m.jcn.reserve(1);
      m.a.reserve(1);
    }
    id.irn_loc = m.irn.data();
    id.jcn_loc = m.jcn.data();
    id.a_loc = m.a.data();
    if (!m.schurRows.empty()) {
      if (m.size != 1)
        throw std::invalid_argument("MUMPS symbolic(): a Schur complement needs a matrix on one process");
      for (MUMPS_INT r : m.schurRows)
        if (r < 1 || r > m.n)
          throw std::invalid_argument("MUMPS symbolic(): Schur row " + std::to_string(r - 1) + " outside 0.." +
                                      std::to_string(m.n - 1));
      const MUMPS_INT ns = static_cast<MUMPS_INT>(m.schurRows.size());
      icntl(id, 19) = 3;  // "distributed" Schur, whole matrix, on a 1 x 1 grid: plain column-major
      id.size_schur = ns;
      id.listvar_schur = m.schurRows.data();
      id.nprow = id.npcol = 1;
      id.mblock = id.nblock = 100;
      id.schur_lld = ns;
      m.schur.assign(size_t(ns) * size_t(ns), 0.0);
      id.schur = m.schur.data();
      m.condRhs.assign(size_t(m.n), 0.0);
      m.redRhs.assign(size_t(ns), 0.0);
    } else {
      icntl(id, 19) = 0;
      id.size_schur = 0;
      id.listvar_schur = nullptr;
      id.schur = nullptr;
    }
    icntl(id, 26) = 0;
    m.condensed = false;
    m.analysed = m.factored = false;
    if (m.ordering == kUserOrdering) {
      m.orderByMetis();
      id.perm_in = m.rank == 0 ? m.permIn.data() : nullptr;
    }
    m.run(1, "analysis (JOB=1)");
    m.analysed = true;
    ++m.nSymbolic;
  });
}

void MumpsSolver::numeric() {
  return impl_->visit([&](auto& m) {
    if (!m.analysed) throw std::logic_error("MUMPS numeric() called before symbolic()");
    m.factored = m.condensed = false;
    const bool changed = !m.collect(false);
    if (anyRank(m.comm, changed))
      throw std::logic_error(
          "MUMPS numeric(): the sparsity pattern of the matrix changed since symbolic(); call symbolic() again");
    auto& id = m.id;
    id.a_loc = m.a.data();
    id.job = 2;
    m.call();
    const int c = infog(id, 1);
    if (c == -8 || c == -9) {
      // The working space estimated in the analysis was too small (typically
      // delayed pivots in an indefinite matrix): one retry with twice the relaxation.
      icntl(id, 14) = std::max(2 * icntl(id, 14), 20);
      m.call();
    }
    m.check("numerical factorisation (JOB=2)");
    m.factored = true;
    ++m.nNumeric;
  });
}

void MumpsSolver::solve(const MultiVector& b, MultiVector& x) {
  return impl_->visit([&](auto& m) {
    if (!m.factored) throw std::logic_error("MUMPS solve() called without a successful numeric()");
    const size_t k = b.getNumVectors();
    const bool bad = x.getNumVectors() != k || b.getLocalLength() != static_cast<size_t>(m.nLocal) ||
                     x.getLocalLength() != static_cast<size_t>(m.nLocal);
    if (anyRank(m.comm, bad))
      throw std::invalid_argument("MUMPS solve(): b and x must be distributed like the matrix rows and have the "
                                  "same number of columns");
    if (k == 0) return;
    const size_t n = static_cast<size_t>(m.n);
    // One column is kept between calls; a block of columns (FETI-DP's Phi) is
    // a temporary, so that it does not stay allocated per subdomain.
    std::vector<double> block;
    std::vector<double>& buf = k == 1 ? m.rhs : block;
    if (m.rank == 0) buf.assign(n * k, 0.0);
    double* root = m.rank == 0 ? buf.data() : nullptr;
    for (size_t j = 0; j < k; ++j) {
      auto bj = b.getData(j);
      MPI_Gatherv(bj.getRawPtr(), m.nLocal, MPI_DOUBLE, root ? root + j * n : nullptr, m.rowCounts.data(),
                  m.rowFirst.data(), MPI_DOUBLE, 0, m.comm);
    }
    auto& id = m.id;
    if constexpr (std::is_same_v<typename std::decay_t<decltype(m)>::Real, double>) {
      id.rhs = root;
    } else {
      if (root) m.rhsReal.assign(buf.begin(), buf.end());
      id.rhs = root ? m.rhsReal.data() : nullptr;
    }
    id.nrhs = static_cast<MUMPS_INT>(k);
    id.lrhs = m.n;
    icntl(id, 26) = 0;  // with a Schur complement: the interior problem only
    m.condensed = false;
    m.run(3, "solve (JOB=3)");
    if constexpr (!std::is_same_v<typename std::decay_t<decltype(m)>::Real, double>) {
      if (root) std::copy(m.rhsReal.begin(), m.rhsReal.end(), buf.begin());
    }
    for (size_t j = 0; j < k; ++j) {
      auto xj = x.getDataNonConst(j);
      MPI_Scatterv(root ? root + j * n : nullptr, m.rowCounts.data(), m.rowFirst.data(), MPI_DOUBLE,
                   xj.getRawPtr(), m.nLocal, MPI_DOUBLE, 0, m.comm);
    }
  });
}

bool MumpsSolver::setSchurIndices(const std::vector<LO>& rows) {
  return impl_->visit([&](auto& m) {
    m.schurRows.clear();
    std::vector<LO> sorted(rows);
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      throw std::invalid_argument("MUMPS setSchurIndices(): repeated row");
    for (LO r : rows) m.schurRows.push_back(static_cast<MUMPS_INT>(r) + 1);
    m.analysed = m.factored = false;  // the analysis depends on them
    return true;
  });
}

void MumpsSolver::schurComplement(std::vector<double>& S) const {
  return impl_->visit([&](auto& m) {
    if (!m.factored || m.schurRows.empty())
      throw std::logic_error("MUMPS schurComplement(): needs setSchurIndices(), symbolic() and numeric()");
    S.assign(m.schur.begin(), m.schur.end());
  });
}

void MumpsSolver::condense(const double* b, double* g) {
  return impl_->visit([&](auto& m) {
    if (!m.factored || m.schurRows.empty())
      throw std::logic_error("MUMPS condense(): needs setSchurIndices(), symbolic() and numeric()");
    auto& id = m.id;
    std::copy(b, b + m.n, m.condRhs.begin());
    id.rhs = m.condRhs.data();
    id.nrhs = 1;
    id.lrhs = m.n;
    id.redrhs = m.redRhs.data();
    id.lredrhs = static_cast<MUMPS_INT>(m.schurRows.size());
    icntl(id, 26) = 1;  // condensation: forward elimination, reduced RHS in REDRHS
    m.condensed = false;
    m.run(3, "condensation (JOB=3, ICNTL(26)=1)");
    icntl(id, 26) = 0;
    m.condensed = true;
    std::copy(m.redRhs.begin(), m.redRhs.end(), g);
  });
}

void MumpsSolver::expand(const double* xs, double* x) {
  return impl_->visit([&](auto& m) {
    if (!m.condensed) throw std::logic_error("MUMPS expand(): call condense() first");
    auto& id = m.id;
    const size_t ns = m.schurRows.size();
    std::copy(xs, xs + ns, m.redRhs.begin());
    id.rhs = m.condRhs.data();  // as condense() left it
    id.nrhs = 1;
    id.lrhs = m.n;
    id.redrhs = m.redRhs.data();
    id.lredrhs = static_cast<MUMPS_INT>(ns);
    icntl(id, 26) = 2;  // expansion: backward substitution with x_s given
    m.condensed = false;
    m.run(3, "expansion (JOB=3, ICNTL(26)=2)");
    icntl(id, 26) = 0;
    std::copy(m.condRhs.begin(), m.condRhs.end(), x);
    for (size_t q = 0; q < ns; ++q) x[m.schurRows[q] - 1] = xs[q];
  });
}

int MumpsSolver::numSymbolic() const {
  return impl_->visit([](const auto& m) { return m.nSymbolic; });
}
int MumpsSolver::numNumeric() const {
  return impl_->visit([](const auto& m) { return m.nNumeric; });
}
int MumpsSolver::orderingUsed() const {
  return impl_->visit([](const auto& m) { return m.analysed ? infog(m.id, 7) : -1; });
}
int MumpsSolver::memoryRelaxationPercent() const {
  return impl_->visit([](const auto& m) { return m.initialized ? m.id.icntl[13] : m.relaxation; });
}

}  // namespace ddc
