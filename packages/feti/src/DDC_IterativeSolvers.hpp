// Monolithic iterative alternatives behind the local-solver factory
// (doc/user-guide.md "Solution method"; measured in doc/performance.md):
//
//   "Belos-MueLu"  : Belos CG, preconditioned by one MueLu smoothed-
//                    aggregation V-cycle (SPD matrices: linear elasticity,
//                    tangents of stable equilibria without contact).
//   "Belos-FROSch" : Belos GMRES, preconditioned by FROSch's two-level
//                    overlapping Schwarz method with a GDSW coarse space
//                    (one subdomain per rank, algebraic overlap).
//
// They implement the DirectSolver interface so the monolithic strategy can
// switch between MUMPS and these by "Type" alone. "Direct" is a misnomer
// here: solve() stops at a relative residual ||b - A x|| / ||b|| <=
// "Convergence Tolerance" and throws SolverError if it does not get there.
//
// Spatial dimension d = 2 or 3 (default 2): the column count of the
// coordinates of setCoordinates(), or setDofsPerNode(d) when there are none;
// if both are given they must agree.
//
// Near-null space. Both need the rigid-body modes of d-D elasticity, built
// from nodal coordinates handed over with setCoordinates() before numeric():
// in 2-D the two translations and the in-plane rotation (3 modes), in 3-D
// three translations and three rotations (6 modes), the rotations
// u = omega x (X - Xc) about the centroid Xc of the nodes. Smoothed
// aggregation reproduces them on every level (Vanek, Mandel, Brezina,
// Computing 56, 1996); the GDSW coarse space of FROSch multiplies them by an
// interface partition of unity (Dohrmann, Klawonn, Widlund, SINUM 46, 2008;
// Heinlein, Klawonn, Rheinbach, SISC 38, 2016). DOF layout assumed (checked
// in numeric()): node-major, d DOFs per node with consecutive global indices
// d k + c (c = 0 .. d-1 for x, y[, z]) owned by the same rank, so every rank
// owns a multiple of d rows. Lagrange-multiplier rows (contact) do not fit
// this layout: these solvers are for problems without contact.
//
// Registration: addIterativeSolvers(factory), or
// DirectSolverFactory::withIterativeSolvers() (= withBuiltins() + these).
#pragma once

#include <Tpetra_Operator.hpp>
#include <memory>
#include <string>

#include "DDC_DirectSolver.hpp"

namespace ddc {

/// Common part of the Belos-based types: parameters, coordinates, the
/// near-null space, the Belos solve with its convergence check. Subclasses
/// build the preconditioner.
///
/// Lifecycle: setCoordinates() (any time before numeric()), symbolic(A)
/// once per sparsity pattern, numeric() per value change (rebuilds or
/// updates the preconditioner), solve() any number of times.
///
/// \pre A is square, fill-complete, row map == range map == domain map, and
///      symmetric positive definite for "Belos-MueLu" (CG). Dirichlet
///      conditions as identity rows (and, for CG, zeroed columns).
/// \note Every call is collective over A's communicator. Our own checks
///       reach the same verdict on every rank; a failure inside MueLu or
///       FROSch on some ranks only cannot be turned into an exception on the
///       others (they wait in a collective of the library).
class IterativeSolver : public DirectSolver {
 public:
  /// The preconditioner's type (also Belos's operator type).
  using Operator = Tpetra::Operator<Scalar, LO, GO, Node>;

  ~IterativeSolver() override;
  IterativeSolver(const IterativeSolver&) = delete;
  IterativeSolver& operator=(const IterativeSolver&) = delete;

  /// \param coords d = 2 or 3 columns (x, y[, z]), in A's row map layout
  ///        (same map): row i holds the coordinates of the node DOF i belongs
  ///        to (the row of the x-DOF d k is read). Sets the dimension d. Kept
  ///        by reference (RCP); read in numeric(). Null forgets them (d stays).
  /// \throws std::invalid_argument naming the count if there are not 2 or 3
  ///         columns, or if setDofsPerNode() set another dimension.
  void setCoordinates(const Teuchos::RCP<const MultiVector>& coords) override;
  /// The dimension d = DOFs per node without coordinates (e.g. for "Null
  /// Space" = "Translations"); 2 unless called.
  /// \throws std::invalid_argument if d is not 2 or 3, or if coordinates of
  ///         another column count were set.
  void setDofsPerNode(int d) override;
  /// The dimension d in use (2 or 3).
  int dofsPerNode() const;
  /// \throws std::invalid_argument if A is null, not fill-complete or its
  ///         row/range/domain maps differ.
  void symbolic(const Teuchos::RCP<const CrsMatrix>& A) override;
  /// Build (first call after symbolic()) or update the preconditioner for
  /// the current values of A.
  /// \throws InputError naming "<Type>/Null Space" if it is "Rigid Body
  ///         Modes" and setCoordinates() was not called; std::invalid_argument
  ///         if the coordinates or the DOF layout do not fit A (see the file
  ///         comment); SolverError if the preconditioner setup fails.
  void numeric() override;
  /// Solve A x = b from x = 0 (the content of x on entry is ignored).
  /// Converged means: Belos met "Convergence Tolerance" with its recursive
  /// residual (or GMRES reported a "loss of accuracy": recursive residual met,
  /// explicit one not quite) within "Maximum Iterations", and the explicit
  /// ||b - A x|| / ||b|| of every column is <= 10 x the tolerance (the factor
  /// absorbs round-off: the tolerance 1e-10 is near the attainable accuracy of
  /// stiff elasticity matrices, MUMPS itself reaches ~5e-11 on the test one).
  /// \throws SolverError otherwise (the message gives iterations, the
  ///         achieved residual and the parameters to change).
  void solve(const MultiVector& b, MultiVector& x) override;
  /// Belos iterations of the last solve().
  int lastIterations() const override;
  /// "Convergence Tolerance".
  double relativeTolerance() const override;
  /// Tolerance of the next solve()s (>= "Convergence Tolerance", < 1).
  /// \throws std::invalid_argument outside that range.
  void setSolveTolerance(double tol) override;
  /// max over columns of ||b - A x|| / ||b|| of the last solve(), computed
  /// explicitly with A (not Belos's recursive residual).
  double lastResidual() const;
  /// Number of numeric() calls that built or updated a preconditioner.
  int numNumeric() const;

  /// The rigid-body modes of d-D elasticity on `coords`' map, d = the
  /// column count (2 or 3), with Xc the mean of the node coordinates
  /// (centring keeps the columns well conditioned):
  ///  - 2-D, 3 columns: (1,0), (0,1), (-(y-yc), x-xc) per node;
  ///  - 3-D, 6 columns: the translations e_x, e_y, e_z, then the rotations
  ///    e_x x r = (0, -rz, ry), e_y x r = (rz, 0, -rx), e_z x r = (-ry, rx, 0)
  ///    with r = X - Xc.
  /// \pre the DOF layout of the file comment (checked: std::invalid_argument,
  ///      also for a column count other than 2 or 3).
  static Teuchos::RCP<MultiVector> rigidBodyModes(const MultiVector& coords);
  /// The d translations only (what "Null Space" = "Translations" uses).
  /// \pre the DOF layout of the file comment for d = `dofsPerNode` (2 or 3).
  static Teuchos::RCP<MultiVector> translations(const Teuchos::RCP<const Map>& map, int dofsPerNode);

 protected:
  /// Parameters every Belos-based type shares (Convergence Tolerance,
  /// Maximum Iterations, Verbosity, Null Space) with defaults and docs.
  static void addCommonParameters(Teuchos::ParameterList& pl, const std::string& solverDoc);
  /// \param params the type's validated sublist; \param type its Type name.
  IterativeSolver(const Teuchos::ParameterList& params, const std::string& type, const std::string& belosSolver);

  /// Build the preconditioner for A_ (first == true after symbolic()) or
  /// update it for A_'s new values. `nullSpace` is on A_'s row map;
  /// `nodeCoords` (d = dofsPerNode() columns, one row per owned node with
  /// global index k of DOFs d k .. d k + d-1) is null when the null space
  /// does not need coordinates.
  virtual Teuchos::RCP<Operator> buildPreconditioner(bool first, const Teuchos::RCP<MultiVector>& nullSpace,
                                                     const Teuchos::RCP<MultiVector>& nodeCoords) = 0;
  /// Whether the preconditioner goes on the left (CG) or right (GMRES:
  /// then Belos's residual is the true one).
  virtual bool rightPreconditioning() const = 0;

  Teuchos::RCP<const CrsMatrix> A_;
  std::string type_;
  int verbosity_ = 0;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// "Belos-MueLu": preconditioned CG, one MueLu smoothed-aggregation V-cycle
/// per iteration. Parameters: getValidParameters(); the "MueLu" sublist is
/// MueLu's own list: our defaults (shown there) overridden entry by entry by
/// the user's, validated by MueLu (its master list) when the solver is
/// created. The near-null space goes to MueLu as "user data/Nullspace" (and
/// node coordinates as "user data/Coordinates"), and "number of equations"
/// is the dimension d (dofsPerNode()), so never set those.
///
/// A user entry for a method ("smoother: type", "coarse: type",
/// "repartition: partitioner") drops our options sublist for it ("...:
/// params"), so options of the old method do not reach the new one.
///
/// Coarse solver: the default "coarse: type" is KLU2 (exact), with the
/// coarsest level first moved to one rank (repartitioning with Zoltan2 from
/// the node coordinates; a level of fewer than "repartition: min rows per
/// proc" rows goes to one rank, and "repartition: use subcommunicators" gives
/// it a one-rank communicator), because KLU2 on a matrix distributed over
/// several ranks is wrong in this Trilinos (doc/trilinos-notes.md; measured: with
/// "repartition: enable" = false CG breaks down at once on 2 ranks).
/// Without coordinates ("Null Space" = "Translations" and no
/// setCoordinates()), repartitioning is impossible: unless the user's list
/// sets "repartition: enable", it is switched off and, unless it sets
/// "coarse: type", the coarse solver becomes Chebyshev of degree 10
/// (inexact but symmetric; same iterations on 1 and 2 ranks).
///
/// numeric() rebuilds the hierarchy, or with "MueLu/reuse: type" other than
/// "none" updates the existing one (MueLu::ReuseTpetraPreconditioner).
class MueLuSolver : public IterativeSolver {
 public:
  static constexpr const char* kType = "Belos-MueLu";
  /// \throws InputError naming "Belos-MueLu/..." for an invalid parameter,
  ///         including one MueLu rejects in the "MueLu" sublist.
  explicit MueLuSolver(const Teuchos::ParameterList& params = Teuchos::ParameterList());
  ~MueLuSolver() override;
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  std::string name() const override { return "Belos-CG/MueLu"; }
  /// Levels of the last hierarchy (0 before numeric()).
  int numLevels() const;

 protected:
  Teuchos::RCP<Operator> buildPreconditioner(bool first, const Teuchos::RCP<MultiVector>& nullSpace,
                                             const Teuchos::RCP<MultiVector>& nodeCoords) override;
  bool rightPreconditioning() const override { return false; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// "Belos-FROSch": GMRES right-preconditioned by FROSch::TwoLevelPreconditioner
/// (additive: algebraic overlapping subdomains = each rank's rows plus
/// "Overlap" layers of the matrix graph, exact local solves by Amesos2 KLU2
/// on MPI_COMM_SELF; coarse space: GDSW interface partition of unity times
/// the near-null space, extended harmonically; the coarse matrix gathered to
/// one rank and solved there by KLU2).
///
/// FROSch is told the dimension d and d DOFs per node (dofsPerNode()), the
/// near-null space and the node coordinates (d columns). The "FROSch"
/// sublist goes to FROSch over our defaults (shown there), entry by entry.
/// FROSch reads its list with get(name, default) and never validates it, so
/// after the first numeric() every parameter the user set in it that FROSch
/// did not read is reported as an InputError (misspelt, or not used with the
/// chosen options).
///
/// "CoarseOperator Type" = "GDSWCoarseOperator" selects the classical GDSW
/// space (its sublist has defaults too). FROSch's "Zoltan2" coarse
/// "Distribution" is compiled out (see DDC_FroschSolver.cpp).
///
/// On one rank the only subdomain is the whole matrix, so the first level
/// is an exact KLU2 solve (GMRES converges in 1-2 iterations).
///
/// numeric(): the first call after symbolic() runs FROSch initialize()
/// (overlap, interface, coarse-space structure) and compute(); later calls
/// only compute() (new values; the FROSch "Reuse: ..." options decide what
/// else is kept).
class FroschSolver : public IterativeSolver {
 public:
  static constexpr const char* kType = "Belos-FROSch";
  explicit FroschSolver(const Teuchos::ParameterList& params = Teuchos::ParameterList());
  ~FroschSolver() override;
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  std::string name() const override { return "Belos-GMRES/FROSch"; }
  /// Dimension of the coarse space of the last numeric() (0 before).
  long long coarseDimension() const;

 protected:
  Teuchos::RCP<Operator> buildPreconditioner(bool first, const Teuchos::RCP<MultiVector>& nullSpace,
                                             const Teuchos::RCP<MultiVector>& nodeCoords) override;
  bool rightPreconditioning() const override { return true; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Register "Belos-MueLu" and "Belos-FROSch" in `factory`.
/// \throws std::invalid_argument if either name is already registered.
void addIterativeSolvers(DirectSolverFactory& factory);

}  // namespace ddc
