// "MUMPS" back end of the local-solver factory: MUMPS 5 called through its C
// API (dmumps_c, or smumps_c with "Precision" = Single), because Debian's
// Amesos2 is built without MUMPS (doc/trilinos-notes.md).
//
// The matrix is handed to MUMPS in distributed assembled form (ICNTL(18)=3:
// every rank passes the rows it owns), the right-hand side is centralised
// on rank 0 of the matrix's communicator and the solution scattered back.
// One MUMPS instance per solver object; several may coexist (FETI-DP: one per
// subdomain on MPI_COMM_SELF plus a distributed coarse one).
#pragma once

#include <memory>

#include "DDC_DirectSolver.hpp"

namespace ddc {

/// Sparse direct solver backed by MUMPS (dmumps or smumps, C API).
///
/// Parameters (see getValidParameters()): "Symmetric", "Ordering",
/// "Memory Relaxation Percent", "Precision" (Double | Single: the factors in
/// float, right-hand sides and solutions converted; for solves inside a
/// preconditioner), "Verbose".
///
/// Lifecycle: symbolic(A) runs the MUMPS analysis (JOB=1) and caches the
/// index arrays; numeric() refreshes the values from A and factorises
/// (JOB=2) reusing the analysis, so a Newton loop with a fixed pattern calls
/// symbolic() once and numeric() per iteration; solve() runs JOB=3.
///
/// \pre A is fill-complete, its row, range and domain maps are the same,
///      one-to-one and contiguous with global indices 0..N-1 (the analysis
///      numbers DOFs so; otherwise std::invalid_argument).
/// \pre With "Symmetric" = true only the lower triangle (row >= col) of A is
///      read: A must be symmetric (it may be indefinite, e.g. a saddle-point
///      matrix [K B^T; B 0]; MUMPS then computes LDL^T with 2x2 pivots).
/// \note Every call, including the destructor (MUMPS JOB=-2), is collective
///       over A's communicator.
class MumpsSolver : public DirectSolver {
 public:
  /// \param params the back end's parameter list; validated against
  ///        getValidParameters() (path "MUMPS" in messages), defaults filled.
  explicit MumpsSolver(const Teuchos::ParameterList& params = Teuchos::ParameterList());
  ~MumpsSolver() override;
  MumpsSolver(const MumpsSolver&) = delete;
  MumpsSolver& operator=(const MumpsSolver&) = delete;

  /// Every parameter with its default and doc string.
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();

  void symbolic(const Teuchos::RCP<const CrsMatrix>& A) override;
  /// \throws SolverError (MUMPS, phase, INFOG(1), INFOG(2)) on failure, e.g.
  ///         INFOG(1) = -10 for a numerically singular matrix. Retries once
  ///         with doubled memory relaxation (at least 20 %) on INFOG(1) = -8 / -9;
  ///         the raised value stays in effect for later factorisations.
  void numeric() override;
  void solve(const MultiVector& b, MultiVector& x) override;
  std::string name() const override { return "MUMPS"; }

  /// Schur complement (ICNTL(19) = 3 on a 1 x 1 process grid: the whole S,
  /// column-major) and condensed solves (ICNTL(26) = 1, 2). Needs a matrix
  /// on one process (symbolic() throws std::invalid_argument otherwise).
  bool setSchurIndices(const std::vector<LO>& rows) override;
  void schurComplement(std::vector<double>& S) const override;
  void condense(const double* b, double* g) override;
  void expand(const double* xs, double* x) override;

  /// Number of MUMPS analyses (JOB=1) so far: stays 1 while only numeric()
  /// is called again (symbolic reuse).
  int numSymbolic() const;
  /// Number of successful MUMPS factorisations (JOB=2) so far.
  int numNumeric() const;
  /// INFOG(7): the ordering MUMPS actually used in the last analysis
  /// (0 AMD, 2 AMF, 4 PORD, 6 QAMD, ...); -1 before symbolic().
  int orderingUsed() const;
  /// ICNTL(14) currently in effect (the parameter, doubled after a retry).
  int memoryRelaxationPercent() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ddc
