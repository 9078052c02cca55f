// "CHOLMOD" back end of the local-solver factory: SuiteSparse's supernodal
// sparse Cholesky factorisation (Chen, Davis, Hager & Rajamanickam,
// "Algorithm 887: CHOLMOD, supernodal sparse Cholesky factorization and
// update/downdate", ACM TOMS 35(3), 2008), called through its C API
// (cholmod_l_*, Debian: libsuitesparse-dev).
//
// For FETI-DP's subdomain matrices (doc/feti-dp.md, "Dual iterations and
// local solvers"): small symmetric positive definite matrices on
// MPI_COMM_SELF that are solved thousands of times per analysis, where
// MUMPS's per-call overhead dominates. Serial only; the distributed
// monolithic and coarse solves stay with MUMPS.
#pragma once

#include <memory>
#include <string>

#include "DDC_DirectSolver.hpp"

namespace ddc {

/// Sparse direct solver backed by CHOLMOD (supernodal LL^T).
///
/// Parameters (see getValidParameters()): "Ordering", "Indefinite Fallback".
///
/// Lifecycle: symbolic(A) copies one triangle of A into a cholmod_sparse,
/// remembers where each entry of A goes, and runs cholmod_analyze
/// (fill-reducing ordering, supernodal symbolic factorisation); numeric()
/// refreshes the values from A in place and runs cholmod_factorize reusing
/// the analysis, so a Newton loop with a fixed pattern calls symbolic() once
/// and numeric() per iteration; solve() runs one cholmod_solve2 for all the
/// columns of b, reusing its workspaces and dense blocks between calls.
///
/// Not positive definite: the supernodal factorisation stops at the first
/// pivot that is not positive (zero, negative or NaN), e.g. for a tangent
/// past a limit point or a saddle-point matrix [K B^T; B 0]. With
/// "Indefinite Fallback" = true (default) that matrix is factorised by an
/// internal MumpsSolver (symmetric LDL^T with pivoting, default MUMPS
/// parameters), which then serves every numeric() and solve() until the next
/// symbolic() (name() says so, usingFallback() is true); with false,
/// numeric() throws SolverError.
///
/// \pre A is fill-complete on a communicator of one process (a FETI-DP
///      subdomain on MPI_COMM_SELF, or a monolithic run on one rank), with
///      row, range and domain maps the same. Any global numbering is accepted.
/// \pre Only the lower triangle (row >= col, as MUMPS with "Symmetric") of A
///      is read: A must be symmetric.
/// \note A matrix that is numerically singular yet has positive pivots
///       (round-off turning a zero pivot into a tiny positive one, e.g. a
///       subdomain with a rigid-body mode left) factorises without error and
///       solves to large, meaningless values. Detecting that is left to the
///       caller: FETI-DP estimates the condition of every K_rr and reports a
///       subdomain above "Local Singularity Threshold" (doc/feti-dp.md,
///       "Primal nodes").
/// \note Debian's CHOLMOD runs loops of its supernodal factorisation with a
///       fixed team of 4 OpenMP threads (CHOLMOD_OMP_NUM_THREADS, a
///       num_threads clause), regardless of OMP_NUM_THREADS. With one MPI rank per core that only
///       oversubscribes the cores and slows small factorisations down
///       several times, so every CHOLMOD call here runs with OpenMP parallel
///       regions made inactive (omp_set_max_active_levels(0), restored after
///       the call), like the rest of DDContact, which runs one thread per rank.
class CholmodSolver : public DirectSolver {
 public:
  /// \param params the back end's parameter list; validated against
  ///        getValidParameters() (path "CHOLMOD" in messages), defaults filled.
  explicit CholmodSolver(const Teuchos::ParameterList& params = Teuchos::ParameterList());
  ~CholmodSolver() override;
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  /// Every parameter with its default and doc string.
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();

  /// \throws std::invalid_argument for a null, not fill-complete or
  ///         non-square matrix, and for a matrix on more than one process
  ///         (naming MUMPS as the solver for those).
  /// \throws SolverError if cholmod_analyze fails (e.g. out of memory).
  void symbolic(const Teuchos::RCP<const CrsMatrix>& A) override;
  /// \throws std::logic_error before symbolic() or if the pattern of A
  ///         changed since symbolic().
  /// \throws SolverError naming CHOLMOD for a non-finite entry of A; for a
  ///         matrix that is not positive definite when "Indefinite Fallback"
  ///         is false (naming the column where the factorisation broke down
  ///         and the parameter) or when the MUMPS fallback fails too (e.g. a
  ///         singular matrix).
  void numeric() override;
  /// Any number of columns. Single-column solves, and blocks of up to
  /// kKeptBlockColumns columns, reuse the dense blocks and workspaces kept
  /// from the last call of the same width (no allocation); a wider block
  /// (FETI-DP's Phi = K_rr^{-1} K_rPi, once per factorisation) uses
  /// temporary ones, so that they do not stay allocated per subdomain.
  void solve(const MultiVector& b, MultiVector& x) override;
  /// "CHOLMOD", or "CHOLMOD (indefinite: MUMPS)" while the fallback serves.
  std::string name() const override;

  /// Widest block of columns whose solve workspaces are kept between calls.
  static constexpr size_t kKeptBlockColumns = 16;

  /// Number of CHOLMOD analyses (cholmod_analyze) so far: stays 1 while only
  /// numeric() is called again (symbolic reuse).
  int numSymbolic() const;
  /// Number of successful factorisations so far, CHOLMOD's and the MUMPS
  /// fallback's.
  int numNumeric() const;
  /// True once a matrix was found not positive definite and the MUMPS
  /// fallback took over (until the next symbolic()).
  bool usingFallback() const;
  /// The ordering CHOLMOD actually used in the last analysis ("AMD",
  /// "METIS", "NESDIS", "natural", ...); empty before symbolic().
  std::string orderingUsed() const;
  /// Nonzeros of the factor L from the last analysis (0 before symbolic()).
  double factorNonzeros() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ddc
