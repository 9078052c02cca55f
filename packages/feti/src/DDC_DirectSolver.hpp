// Local-solver factory: direct solvers behind one interface, used for the
// monolithic global solve (distributed matrix) and, with FETI-DP, for the
// subdomain factorisations (matrices on MPI_COMM_SELF).
//
// Shape follows FROSch's Solver: symbolic / numeric / solve with state, a
// factory dispatching on "Type" with a {Type, ...} sublist.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_MultiVector.hpp>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "DDC_TpetraTypes.hpp"

namespace ddc {


/// A sparse direct solver for a square, fill-complete Tpetra::CrsMatrix whose
/// row, range and domain maps are the same map. The matrix may live on any
/// communicator (distributed, or MPI_COMM_SELF for a subdomain).
class DirectSolver {
 public:
  virtual ~DirectSolver() = default;
  /// Analyse the sparsity pattern of A (ordering, symbolic factorisation).
  /// Call again only when the pattern changes; the solver keeps A.
  virtual void symbolic(const Teuchos::RCP<const CrsMatrix>& A) = 0;
  /// Factorise the current values of the matrix given to symbolic().
  /// \throws SolverError if the matrix is singular (naming the back end).
  virtual void numeric() = 0;
  /// Solve A x = b (b, x distributed like A's row map; several columns ok).
  virtual void solve(const MultiVector& b, MultiVector& x) = 0;
  /// Back-end name for messages ("MUMPS", "Amesos2/KLU2", "CHOLMOD").
  virtual std::string name() const = 0;

  /// Optional hook: nodal coordinates, for back ends that build a near-null
  /// space from them (the iterative "Belos-MueLu" / "Belos-FROSch", see
  /// DDC_IterativeSolvers.hpp); direct solvers ignore it. Call before numeric().
  /// \param coords d columns (x, y[, z]) for spatial dimension d = 2 or 3, in
  ///        A's row map layout: row i holds the coordinates of the node that
  ///        DOF i belongs to. Their column count sets d (see setDofsPerNode()).
  virtual void setCoordinates(const Teuchos::RCP<const MultiVector>& /*coords*/) {}
  /// Optional hook: the DOFs per node, i.e. the spatial dimension d = 2 or 3
  /// of a displacement-only elasticity matrix (node-major, DOFs d k + c of
  /// node k). The iterative back ends need it for their near-null space and
  /// DOF layout check when no coordinates are given ("Null Space" =
  /// "Translations"); with coordinates it must agree with their column count.
  /// Default 2 (the 2-D analysis). Direct solvers ignore it. Call before
  /// numeric().
  virtual void setDofsPerNode(int /*dofsPerNode*/) {}
  /// Iterations of the last solve(): Belos iterations for iterative back
  /// ends, 0 for direct solvers (the "dual_iterations" of history.csv).
  virtual int lastIterations() const { return 0; }
  /// The configured relative tolerance of an iterative back end (its
  /// "Convergence Tolerance"); 0 for a direct solver, which solves to
  /// round-off and has no tolerance to relax.
  virtual double relativeTolerance() const { return 0.0; }
  /// Optional hook: the relative tolerance of the next solve()s, in
  /// [relativeTolerance(), 1) (an inexact Newton method's forcing term,
  /// doc/user-guide.md "Solution method"). Direct solvers ignore it.
  virtual void setSolveTolerance(double /*tol*/) {}

  /// \name Optional capability: Schur complement and condensed solves
  /// A partial factorisation that eliminates every row except the Schur rows
  /// s, so that A = [A_ii A_is; A_si A_ss] yields S = A_ss - A_si A_ii^{-1}
  /// A_is, and right-hand sides are condensed onto s and expanded back (MUMPS
  /// ICNTL(19) and ICNTL(26); FETI-DP's subdomain condensation on the primal
  /// DOFs, doc/feti-dp.md "Dual problem"). Only for matrices on one process.
  /// While Schur rows are set, solve() solves the interior problem A_ii x_i =
  /// b_i and returns x_s = 0.
  ///@{
  /// Set the Schur rows (local row indices, distinct), before symbolic();
  /// an empty list switches the capability off. Returns false, and changes
  /// nothing, if the back end cannot.
  virtual bool setSchurIndices(const std::vector<LO>& /*rows*/) { return false; }
  /// After numeric(): S, dense, column-major, |s| x |s|, rows and columns in
  /// the order of setSchurIndices(). \throws std::logic_error if unsupported.
  virtual void schurComplement(std::vector<double>& /*S*/) const {
    throw std::logic_error(name() + ": no Schur complement support");
  }
  /// Condensation: g = b_s - A_si A_ii^{-1} b_i for b with one value per row
  /// (g: |s| values). Keeps b for the next expand().
  virtual void condense(const double* /*b*/, double* /*g*/) {
    throw std::logic_error(name() + ": no Schur complement support");
  }
  /// Expansion after condense(b): x_i = A_ii^{-1} (b_i - A_is x_s) for the
  /// given x_s (|s| values); x gets one value per row, x_s included.
  virtual void expand(const double* /*xs*/, double* /*x*/) {
    throw std::logic_error(name() + ": no Schur complement support");
  }
  ///@}
};

/// Names -> direct-solver creators. Built-ins: "MUMPS", "Amesos2", "CHOLMOD"
/// (serial: matrices on one process only).
///
/// The {Type, ...} sublist has one sublist per back end, named like its Type:
/// {"Type": "MUMPS", "MUMPS": {...}, "Amesos2": {...}}; only the chosen back
/// end's sublist is used, but every one present is validated (see
/// validParameters()).
class DirectSolverFactory {
 public:
  /// Type used when the sublist has no "Type".
  static constexpr const char* kDefaultType = "MUMPS";

  using Creator = std::function<std::unique_ptr<DirectSolver>(const Teuchos::ParameterList&)>;
  struct Entry {
    Creator create;
    Teuchos::RCP<const Teuchos::ParameterList> validParameters;  ///< without "Type"
    std::string description;
    /// The back end factorises matrices on one process only (CHOLMOD): it
    /// may be a FETI-DP Local Solver, not a solver of a distributed matrix.
    bool oneProcess = false;
  };

  DirectSolverFactory() = default;
  static DirectSolverFactory withBuiltins();
  /// withBuiltins() plus the monolithic iterative types "Belos-MueLu" and
  /// "Belos-FROSch" (DDC_IterativeSolvers.hpp). Kept apart from the
  /// built-ins because FETI-DP's subdomain and coarse solves must be exact.
  static DirectSolverFactory withIterativeSolvers();

  /// Register a back end. \throws std::invalid_argument if `type` is empty,
  /// already registered, or `entry.create` is empty.
  void add(const std::string& type, Entry entry);
  std::vector<std::string> names() const;
  /// \throws InputError naming where/Type and the known types if unknown.
  const Entry& entry(const std::string& type, const std::string& where = "") const;
  /// `params` is the {Type, ...} sublist; validated, defaults filled in.
  /// \param where parameter path of `params` for messages (e.g. "Solver/Linear Solver").
  /// \throws InputError for an unknown Type (naming where/Type and listing the
  ///         known types) or a misspelt / mistyped parameter (naming its path).
  std::unique_ptr<DirectSolver> create(Teuchos::ParameterList& params, const std::string& where) const;
  /// \throws InputError naming where/Type when the chosen type factorises
  ///         matrices on one process only (Entry::oneProcess) and the
  ///         matrix it would solve is distributed over `processes` > 1.
  void requireDistributable(const Teuchos::ParameterList& params, const std::string& where, int processes) const;

  /// The documented valid {Type, <one sublist per registered type>} list of
  /// this factory (default Type "MUMPS" if registered, else the first name).
  Teuchos::RCP<const Teuchos::ParameterList> validParameters() const;
  /// validParameters() of withBuiltins(): every built-in option with default
  /// and doc string (for --print-parameters and for enclosing lists).
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();

 private:
  std::map<std::string, Entry> entries_;
};

}  // namespace ddc
