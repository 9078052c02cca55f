// "Amesos2" back end of the local-solver factory (KLU2 by default).
//
// Pitfall of this Trilinos build (doc/trilinos-notes.md): Amesos2/KLU2
// returns a wrong solution for a matrix distributed over several ranks, but is correct
// on MPI_COMM_SELF. So a matrix whose communicator has more than one rank is
// gathered to rank 0 into a CrsMatrix on MPI_COMM_SELF and factorised there;
// b is gathered and x scattered in solve(). A matrix on one rank (FETI-DP
// subdomains) goes to Amesos2 directly.
#pragma once

#include <memory>
#include <vector>

#include "DDC_DirectSolver.hpp"

namespace ddc {

/// Sparse direct solver through Amesos2 (parameter "Solver Name").
///
/// Lifecycle: symbolic(A) (Amesos2 symbolicFactorization; in the gathered
/// mode also gathers the pattern) once per pattern, numeric() per value
/// change (re-reads the values of A), solve() any number of times.
///
/// \pre A is fill-complete with row map == range map == domain map
///      (one-to-one). Any global numbering is accepted.
/// \note With more than one rank every call is collective over A's
///       communicator; errors on rank 0 are broadcast so all ranks throw.
class Amesos2Solver : public DirectSolver {
 public:
  /// \param params the back end's parameter list; validated against
  ///        getValidParameters() (path "Amesos2" in messages).
  /// \throws InputError if "Solver Name" is not available in this Amesos2
  ///         build (the message lists the available ones).
  explicit Amesos2Solver(const Teuchos::ParameterList& params = Teuchos::ParameterList());
  ~Amesos2Solver() override;
  Amesos2Solver(const Amesos2Solver&) = delete;
  Amesos2Solver& operator=(const Amesos2Solver&) = delete;

  /// Every parameter with its default and doc string.
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  /// Amesos2 solver names compiled into this Trilinos (Amesos2::query).
  static std::vector<std::string> availableSolvers();

  void symbolic(const Teuchos::RCP<const CrsMatrix>& A) override;
  /// \throws SolverError naming "Amesos2/<solver>" if the factorisation
  ///         fails (e.g. a singular matrix).
  void numeric() override;
  void solve(const MultiVector& b, MultiVector& x) override;
  std::string name() const override;

  /// True if the last symbolic() chose the gather-to-rank-0 mode.
  bool gathersToRoot() const;
  /// Number of symbolic factorisations so far.
  int numSymbolic() const;
  /// Number of successful numeric factorisations so far.
  int numNumeric() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ddc
