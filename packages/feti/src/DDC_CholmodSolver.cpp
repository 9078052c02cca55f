#include "DDC_CholmodSolver.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "DDC_Error.hpp"
#include "DDC_LocalCsr.hpp"
#include "DDC_MumpsSolver.hpp"
#include "DDC_Parameters.hpp"

// The OpenMP runtime's entry points, declared weak: they resolve to the
// runtime CHOLMOD was linked with (Debian's libcholmod needs libgomp) and
// stay null if there is none, so DDContact itself needs no OpenMP flags.
extern "C" {
int omp_get_max_active_levels(void) __attribute__((weak));
void omp_set_max_active_levels(int) __attribute__((weak));
}

namespace ddc {

namespace {

using Long = SuiteSparse_long;

const std::vector<std::string>& orderingNames() {
  static const std::vector<std::string> names{"METIS", "AMD", "NESDIS", "Auto"};
  return names;
}

/// Set Common's ordering strategy for an "Ordering" name (Common->nmethods
/// and Common->method[], CHOLMOD user guide, cholmod_analyze).
void setOrdering(cholmod_common& cc, const std::string& o) {
  if (o == "Auto") {
    cc.nmethods = 0;  // AMD; METIS too if AMD's fill is high, keeping the better
    return;
  }
  cc.nmethods = 1;
  cc.method[0].ordering = o == "AMD" ? CHOLMOD_AMD : o == "NESDIS" ? CHOLMOD_NESDIS : CHOLMOD_METIS;
}

/// L->ordering as a name.
std::string orderingName(int code) {
  switch (code) {
    case CHOLMOD_NATURAL: return "natural";
    case CHOLMOD_GIVEN: return "given";
    case CHOLMOD_AMD: return "AMD";
    case CHOLMOD_METIS: return "METIS";
    case CHOLMOD_NESDIS: return "NESDIS";
    case CHOLMOD_COLAMD: return "COLAMD";
    case CHOLMOD_POSTORDERED: return "natural, postordered";
    default: return "unknown (" + std::to_string(code) + ")";
  }
}

/// Common->status in words.
std::string explainStatus(int status) {
  switch (status) {
    case CHOLMOD_NOT_INSTALLED: return "method not installed in this CHOLMOD";
    case CHOLMOD_OUT_OF_MEMORY: return "out of memory";
    case CHOLMOD_TOO_LARGE: return "integer overflow: problem too large";
    case CHOLMOD_INVALID: return "invalid input";
    case CHOLMOD_GPU_PROBLEM: return "GPU error";
    case CHOLMOD_NOT_POSDEF: return "matrix not positive definite";
    case CHOLMOD_DSMALL: return "tiny diagonal entry in L";
    default: return "see the CHOLMOD user guide, Common->status";
  }
}

/// Makes OpenMP parallel regions inactive for its lifetime (max-active-levels
/// 0), restoring the previous setting after: see the class documentation on
/// CHOLMOD's fixed team of 4 threads. A no-op without an OpenMP runtime.
class SerialOpenMp {
 public:
  SerialOpenMp() : active_(omp_get_max_active_levels != nullptr && omp_set_max_active_levels != nullptr) {
    if (!active_) return;
    saved_ = omp_get_max_active_levels();
    omp_set_max_active_levels(0);
  }
  ~SerialOpenMp() {
    if (active_) omp_set_max_active_levels(saved_);
  }
  SerialOpenMp(const SerialOpenMp&) = delete;
  SerialOpenMp& operator=(const SerialOpenMp&) = delete;

 private:
  bool active_;
  int saved_ = 0;
};

}  // namespace

struct CholmodSolver::Impl {
  // parameters
  std::string ordering = "METIS";
  bool allowFallback = true;

  cholmod_common cc{};

  // matrix and its pattern as cached by symbolic(): per row of A, its
  // entries' local column indices, and for each entry the slot in S->x it
  // goes to (-1: upper triangle, not read)
  Teuchos::RCP<const CrsMatrix> A;
  Teuchos::RCP<const Map> colMap;
  size_t n = 0;
  std::vector<size_t> rowPtr;
  std::vector<LO> cols;
  std::vector<Long> slot;
  std::vector<LO> colToRow;  // A's local column index -> local row index

  cholmod_sparse* S = nullptr;  // lower triangle of A, stored as CHOLMOD's upper (stype = +1)
  cholmod_factor* L = nullptr;

  /// Dense blocks and workspaces of one cholmod_solve2 width.
  struct Work {
    cholmod_common* cc = nullptr;
    cholmod_dense* B = nullptr;
    cholmod_dense* X = nullptr;
    cholmod_dense* Y = nullptr;
    cholmod_dense* E = nullptr;
    explicit Work(cholmod_common* c) : cc(c) {}
    ~Work() { release(); }
    Work(const Work&) = delete;
    Work& operator=(const Work&) = delete;
    void release() {
      for (cholmod_dense** d : {&B, &X, &Y, &E})
        if (*d) cholmod_l_free_dense(d, cc);
    }
  };
  Work one{&cc};    // single-column solves
  Work block{&cc};  // the last block of 2..kKeptBlockColumns columns

  // "Indefinite Fallback": MUMPS on A, or on a copy of A numbered 0..n-1
  // (what MUMPS needs) if A is numbered otherwise
  std::unique_ptr<MumpsSolver> mumps;
  Teuchos::RCP<CrsMatrix> renumbered;
  bool fallback = false;

  bool analysed = false;
  bool factored = false;
  int nSymbolic = 0;
  int nNumeric = 0;
  std::string orderingUsed;
  double lnz = 0.0;

  Impl() {
    cholmod_l_start(&cc);
    cc.print = 0;  // errors come back through Common->status, reported by us
    cc.error_handler = nullptr;
    cc.supernodal = CHOLMOD_SUPERNODAL;  // LL^T: stops at the first pivot <= 0
    cc.quick_return_if_not_posdef = 1;   // do not finish a factorisation that failed
    cc.useGPU = 0;
  }

  ~Impl() {
    one.release();
    block.release();
    freeFactorisation();
    cholmod_l_finish(&cc);
  }

  void freeFactorisation() {
    if (L) cholmod_l_free_factor(&L, &cc);
    if (S) cholmod_l_free_sparse(&S, &cc);
  }

  std::string label() const { return fallback ? "CHOLMOD (indefinite: MUMPS)" : "CHOLMOD"; }

  /// Copy A's values into S->x (and the renumbered copy, if any) after
  /// checking that A's pattern is the cached one. Returns false if the
  /// pattern changed; a non-finite value is described in `bad`.
  bool refresh(std::string& bad) {
    const auto cm = A->getColMap();
    if (cm.get() != colMap.get() && !cm->isSameAs(*colMap)) return false;
    if (A->getNodeNumEntries() != cols.size()) return false;
    double* x = S ? static_cast<double*>(S->x) : nullptr;
    {
      const LocalCsr a(*A);
      for (size_t lr = 0; lr < n; ++lr) {
        const size_t first = rowPtr[lr], len = a.ptr[lr + 1] - a.ptr[lr];
        if (len != rowPtr[lr + 1] - first) return false;
        for (size_t e = 0; e < len; ++e) {
          const size_t ae = a.ptr[lr] + e;
          if (a.col[ae] != cols[first + e]) return false;
          const Long s = slot[first + e];
          if (s < 0) continue;
          x[s] = a.val[ae];
          if (bad.empty() && !std::isfinite(a.val[ae])) {
            std::ostringstream os;
            os << "entry (" << A->getRowMap()->getGlobalElement(static_cast<LO>(lr)) << ", "
               << colMap->getGlobalElement(a.col[ae]) << ") is " << a.val[ae];
            bad = os.str();
          }
        }
      }
    }
    CrsMatrix::local_inds_host_view_type inds;
    CrsMatrix::values_host_view_type vals;
    if (fallback && !renumbered.is_null()) {
      renumbered->resumeFill();
      std::vector<GO> gc;
      for (size_t lr = 0; lr < n; ++lr) {
        A->getLocalRowView(static_cast<LO>(lr), inds, vals);
        gc.resize(inds.extent(0));
        for (size_t e = 0; e < gc.size(); ++e) gc[e] = colToRow[inds(e)];
        renumbered->replaceGlobalValues(static_cast<GO>(lr), static_cast<LO>(gc.size()), vals.data(), gc.data());
      }
      renumbered->fillComplete(renumbered->getRowMap(), renumbered->getRowMap());
    }
    return true;
  }

  /// A copy of A whose row i is A's local row i and whose global indices
  /// are the local ones (MUMPS wants rows numbered 0..n-1).
  Teuchos::RCP<CrsMatrix> renumberedCopy() const {
    auto map = Teuchos::rcp(new Map(static_cast<Tpetra::global_size_t>(n), 0, A->getComm()));
    std::vector<size_t> len(n);
    for (size_t i = 0; i < n; ++i) len[i] = rowPtr[i + 1] - rowPtr[i];
    auto C = Teuchos::rcp(new CrsMatrix(map, Teuchos::ArrayView<const size_t>(len)));
    CrsMatrix::local_inds_host_view_type inds;
    CrsMatrix::values_host_view_type vals;
    std::vector<GO> gc;
    for (size_t i = 0; i < n; ++i) {
      A->getLocalRowView(static_cast<LO>(i), inds, vals);
      gc.resize(inds.extent(0));
      for (size_t e = 0; e < gc.size(); ++e) gc[e] = colToRow[inds(e)];
      C->insertGlobalValues(static_cast<GO>(i), static_cast<LO>(gc.size()), vals.data(), gc.data());
    }
    C->fillComplete(map, map);
    return C;
  }

  /// Numeric factorisation by the MUMPS fallback; its failure becomes a
  /// SolverError starting with `context`.
  void mumpsNumeric(const std::string& context) {
    try {
      mumps->numeric();
    } catch (const SolverError& e) {
      DDC_THROW(SolverError, context << e.what());
    }
  }

  /// Switch to MUMPS for this matrix after CHOLMOD found it not positive
  /// definite (`why`), until the next symbolic().
  void startFallback(const std::string& why) {
    auto m = std::make_unique<MumpsSolver>();
    const auto rowMap = A->getRowMap();
    const bool zeroBased = rowMap->isContiguous() && rowMap->getMinGlobalIndex() == 0;
    Teuchos::RCP<CrsMatrix> copy = zeroBased ? Teuchos::null : renumberedCopy();
    try {
      m->symbolic(copy.is_null() ? A : Teuchos::RCP<const CrsMatrix>(copy));
    } catch (const std::exception& e) {
      DDC_THROW(SolverError, why << " and its MUMPS fallback ('Indefinite Fallback') failed as well: " << e.what());
    }
    mumps = std::move(m);
    renumbered = copy;
    fallback = true;
    if (L) cholmod_l_free_factor(&L, &cc);  // not used again until the next symbolic()
    mumpsNumeric(why + " and its MUMPS fallback ('Indefinite Fallback') failed as well: ");
  }
};

CholmodSolver::CholmodSolver(const Teuchos::ParameterList& params) : impl_(std::make_unique<Impl>()) {
  Teuchos::ParameterList p(params);
  validateLevel(p, *getValidParameters(), "CHOLMOD");
  impl_->ordering = p.get<std::string>("Ordering");
  impl_->allowFallback = p.get<bool>("Indefinite Fallback");
  setOrdering(impl_->cc, impl_->ordering);
}

CholmodSolver::~CholmodSolver() = default;

Teuchos::RCP<const Teuchos::ParameterList> CholmodSolver::getValidParameters() {
  static Teuchos::RCP<const Teuchos::ParameterList> valid = [] {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("CHOLMOD"));
    pl->set("Ordering", std::string("METIS"),
            "Fill-reducing ordering of the CHOLMOD analysis (once per sparsity pattern): METIS (nested dissection, "
            "METIS_NodeND), AMD, NESDIS (CHOLMOD's own nested dissection, also on METIS), Auto (CHOLMOD's default: "
            "AMD, and METIS as well when AMD's fill-in is high, keeping the sparser factor). On 3-D subdomain "
            "matrices METIS gives a sparser factor than AMD, so faster factorisations and solves, for a costlier "
            "analysis.",
            enumValidator(orderingNames(), "Ordering"));
    pl->set("Indefinite Fallback", true,
            "What to do with a matrix that is not positive definite (the Cholesky factorisation meets a pivot <= 0: "
            "a tangent past a limit point, a saddle-point matrix, a singular matrix). true: factorise it with MUMPS "
            "(symmetric LDL^T with pivoting, default MUMPS options; a singular matrix is an error there too) and "
            "keep using MUMPS until the next symbolic factorisation (a new sparsity pattern); false: a solver error "
            "naming the column.");
    return Teuchos::RCP<const Teuchos::ParameterList>(pl);
  }();
  return valid;
}

std::string CholmodSolver::name() const { return impl_->label(); }
int CholmodSolver::numSymbolic() const { return impl_->nSymbolic; }
int CholmodSolver::numNumeric() const { return impl_->nNumeric; }
bool CholmodSolver::usingFallback() const { return impl_->fallback; }
std::string CholmodSolver::orderingUsed() const { return impl_->orderingUsed; }
double CholmodSolver::factorNonzeros() const { return impl_->lnz; }

void CholmodSolver::symbolic(const Teuchos::RCP<const CrsMatrix>& A) {
  Impl& m = *impl_;
  if (A.is_null()) throw std::invalid_argument("CHOLMOD symbolic(): null matrix");
  if (!A->isFillComplete()) throw std::invalid_argument("CHOLMOD symbolic(): matrix is not fill-complete");
  const int procs = A->getComm()->getSize();
  if (procs != 1)
    throw std::invalid_argument(
        "CHOLMOD symbolic(): the matrix is distributed over " + std::to_string(procs) +
        " processes, but CHOLMOD is a serial solver for a matrix on one process (a FETI-DP subdomain on "
        "MPI_COMM_SELF). Use MUMPS for a distributed matrix (the monolithic 'Solver/Linear Solver' and the "
        "FETI-DP 'Coarse Solver'), and CHOLMOD as 'Solver/FETI-DP/Local Solver/Type'");
  const auto rowMap = A->getRowMap();
  if (!rowMap->isSameAs(*A->getRangeMap()) || !rowMap->isSameAs(*A->getDomainMap()))
    throw std::invalid_argument("CHOLMOD symbolic(): row, range and domain maps must be the same");

  m.analysed = m.factored = false;
  m.one.release();
  m.block.release();
  m.freeFactorisation();
  m.mumps.reset();
  m.renumbered = Teuchos::null;
  m.fallback = false;
  m.orderingUsed.clear();
  m.lnz = 0.0;

  m.A = A;
  m.colMap = A->getColMap();
  m.n = rowMap->getNodeNumElements();
  const size_t n = m.n;
  const auto& colMap = *m.colMap;
  m.colToRow.resize(colMap.getNodeNumElements());
  for (size_t c = 0; c < m.colToRow.size(); ++c) {
    const GO g = colMap.getGlobalElement(static_cast<LO>(c));
    m.colToRow[c] = rowMap->getLocalElement(g);
    if (m.colToRow[c] == Teuchos::OrdinalTraits<LO>::invalid())
      throw std::invalid_argument("CHOLMOD symbolic(): column " + std::to_string(g) +
                                  " is not a row of the matrix (it must be square on its row map)");
  }

  // The entries of local row i with local column j <= i become column i of
  // S, rows j sorted: CHOLMOD's upper triangle (stype = +1), its preferred
  // form when a fill-reducing ordering is used.
  CrsMatrix::local_inds_host_view_type inds;
  CrsMatrix::values_host_view_type vals;
  m.rowPtr.assign(n + 1, 0);
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i) {
    A->getLocalRowView(static_cast<LO>(i), inds, vals);
    m.rowPtr[i + 1] = m.rowPtr[i] + inds.extent(0);
    for (size_t e = 0; e < inds.extent(0); ++e)
      if (static_cast<size_t>(m.colToRow[inds(e)]) <= i) ++kept;
  }
  m.cols.resize(m.rowPtr[n]);
  m.slot.assign(m.rowPtr[n], -1);
  m.S = cholmod_l_allocate_sparse(n, n, std::max<size_t>(kept, 1), /*sorted=*/1, /*packed=*/1, /*stype=*/1,
                                  CHOLMOD_REAL, &m.cc);
  if (m.S == nullptr)
    DDC_THROW(SolverError, "CHOLMOD symbolic(): cholmod_allocate_sparse failed: Common->status = "
                               << m.cc.status << " (" << explainStatus(m.cc.status) << "), N = " << n);
  auto* Sp = static_cast<Long*>(m.S->p);
  auto* Si = static_cast<Long*>(m.S->i);
  auto* Sx = static_cast<double*>(m.S->x);
  std::vector<std::pair<LO, size_t>> row;  // (local column as a row index, entry)
  Long q = 0;
  Sp[0] = 0;
  for (size_t i = 0; i < n; ++i) {
    A->getLocalRowView(static_cast<LO>(i), inds, vals);
    row.clear();
    for (size_t e = 0; e < inds.extent(0); ++e) {
      const size_t k = m.rowPtr[i] + e;
      m.cols[k] = inds(e);
      const LO j = m.colToRow[inds(e)];
      if (static_cast<size_t>(j) <= i) row.emplace_back(j, e);
    }
    std::sort(row.begin(), row.end());
    for (const auto& [j, e] : row) {
      Si[q] = j;
      Sx[q] = vals(e);
      m.slot[m.rowPtr[i] + e] = q++;
    }
    Sp[i + 1] = q;
  }

  if (n > 0) {
    SerialOpenMp serial;
    m.L = cholmod_l_analyze(m.S, &m.cc);
  }
  if (n > 0 && (m.L == nullptr || m.cc.status < CHOLMOD_OK))
    DDC_THROW(SolverError, "CHOLMOD analysis (cholmod_analyze, ordering " << m.ordering
                               << ") failed: Common->status = " << m.cc.status << " ("
                               << explainStatus(m.cc.status) << "), N = " << n);
  if (m.L) {
    m.orderingUsed = orderingName(m.L->ordering);
    m.lnz = m.cc.lnz;
  }
  m.analysed = true;
  ++m.nSymbolic;
}

void CholmodSolver::numeric() {
  Impl& m = *impl_;
  if (!m.analysed) throw std::logic_error("CHOLMOD numeric() called before symbolic()");
  m.factored = false;
  std::string bad;
  if (!m.refresh(bad))
    throw std::logic_error(
        m.label() + " numeric(): the sparsity pattern of the matrix changed since symbolic(); call symbolic() again");
  if (!bad.empty()) DDC_THROW(SolverError, m.label() << " numeric(): " << bad << "; N = " << m.n);

  if (m.fallback) {
    m.mumpsNumeric(m.label() +
                   " numeric(): MUMPS, factorising since a matrix of this pattern was not positive definite "
                   "('Indefinite Fallback'), failed: ");
  } else if (m.n > 0) {
    {
      SerialOpenMp serial;
      cholmod_l_factorize(m.S, m.L, &m.cc);
    }
    if (m.cc.status < CHOLMOD_OK)
      DDC_THROW(SolverError, "CHOLMOD numeric factorisation (cholmod_factorize) failed: Common->status = "
                                 << m.cc.status << " (" << explainStatus(m.cc.status) << "), N = " << m.n);
    if (m.cc.status == CHOLMOD_NOT_POSDEF || m.L->minor < m.n) {
      // L->minor is the first column of the permuted matrix whose pivot is
      // not positive; Perm maps it back to a row of A.
      const size_t k = m.L->minor;
      const auto* perm = static_cast<const Long*>(m.L->Perm);
      const LO row = static_cast<LO>(perm && k < m.n ? perm[k] : static_cast<Long>(k));
      std::ostringstream why;
      why << "CHOLMOD numeric(): the matrix is not positive definite: the Cholesky factorisation broke down at "
          << "column " << m.A->getRowMap()->getGlobalElement(row) << " (pivot <= 0 after " << k << " of " << m.n
          << " eliminations)";
      if (!m.allowFallback)
        DDC_THROW(SolverError, why.str() << ", and 'Indefinite Fallback' is false. A symmetric indefinite matrix "
                                            "(a tangent past a limit point, a saddle point) needs LDL^T with "
                                            "pivoting: set 'Indefinite Fallback' = true, or use Type = MUMPS");
      m.startFallback(why.str());
    }
  }
  m.factored = true;
  ++m.nNumeric;
}

void CholmodSolver::solve(const MultiVector& b, MultiVector& x) {
  Impl& m = *impl_;
  if (!m.factored) throw std::logic_error("CHOLMOD solve() called without a successful numeric()");
  const size_t k = b.getNumVectors();
  if (x.getNumVectors() != k || b.getLocalLength() != m.n || x.getLocalLength() != m.n)
    throw std::invalid_argument(m.label() + " solve(): b and x must be distributed like the matrix rows (" +
                                std::to_string(m.n) + ") and have the same number of columns; got b " +
                                std::to_string(b.getLocalLength()) + " x " + std::to_string(k) + ", x " +
                                std::to_string(x.getLocalLength()) + " x " + std::to_string(x.getNumVectors()));
  if (k == 0 || m.n == 0) return;
  if (m.fallback) {
    m.mumps->solve(b, x);
    return;
  }
  Impl::Work wide(&m.cc);
  Impl::Work& w = k == 1 ? m.one : k <= kKeptBlockColumns ? m.block : wide;
  const size_t n = m.n;
  if (w.B == nullptr || w.B->ncol != k) {
    if (w.B) cholmod_l_free_dense(&w.B, &m.cc);
    w.B = cholmod_l_allocate_dense(n, k, n, CHOLMOD_REAL, &m.cc);
    if (w.B == nullptr)
      DDC_THROW(SolverError, "CHOLMOD solve(): cholmod_allocate_dense failed: Common->status = "
                                 << m.cc.status << " (" << explainStatus(m.cc.status) << "), " << n << " x " << k);
  }
  auto* B = static_cast<double*>(w.B->x);
  for (size_t j = 0; j < k; ++j) {
    auto bj = b.getData(j);
    std::copy(bj.begin(), bj.begin() + n, B + j * n);
  }
  int ok = 0;
  {
    SerialOpenMp serial;
    ok = cholmod_l_solve2(CHOLMOD_A, m.L, w.B, nullptr, &w.X, nullptr, &w.Y, &w.E, &m.cc);
  }
  if (!ok || w.X == nullptr)
    DDC_THROW(SolverError, "CHOLMOD solve (cholmod_solve2) failed: Common->status = "
                               << m.cc.status << " (" << explainStatus(m.cc.status) << "), N = " << n
                               << ", columns = " << k);
  const auto* X = static_cast<const double*>(w.X->x);
  for (size_t j = 0; j < k; ++j) {
    auto xj = x.getDataNonConst(j);
    std::copy(X + j * n, X + (j + 1) * n, xj.begin());
  }
}

}  // namespace ddc
