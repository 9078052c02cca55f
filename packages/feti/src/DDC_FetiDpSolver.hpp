// FETI-DP dual-interface solver: the algebra only (doc/feti-dp.md; Farhat,
// Lesoinne, LeTallec, Pierson & Rixen 2001).
//
// It knows no mesh and no contact (doc/architecture.md): the caller hands
// it, per subdomain, the global ids of the subdomain's free DOFs, which of them are
// primal (assembled globally into the coarse problem) and the subdomain
// stiffness K^s on MPI_COMM_SELF. From that it builds the interface
// compatibility constraints B, the partially assembled operator
//
//     F = B K~^{-1} B^T ,   d = B K~^{-1} f~            (doc/feti-dp.md)
//
// (K~ = the stiffness assembled only at primal DOFs) and solves F lambda = d
// with Belos, preconditioned by the Dirichlet or lumped preconditioner.
//
// Typical use (one Newton iteration per numeric() + solve()):
//
//   ddc::FetiDpSolver feti(comm, params, "Solver/FETI-DP");
//   feti.setTopology(std::move(subdomains), ownedMap);   // once per pattern
//   for (...) {            // Newton
//     ... update the values of every subdomain's K (same pattern) ...
//     feti.numeric();      // only when the values changed: a linear
//                          // material is factorised once, contact rows or not
//     auto info = feti.solve(residual, du);
//   }
#pragma once

#include <Teuchos_Comm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Tpetra_Operator.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "DDC_DirectSolver.hpp"
#include "DDC_FetiEdgeFaceConstraints.hpp"

namespace ddc {

/// One subdomain as the caller describes it to FetiDpSolver::setTopology().
struct FetiSubdomain {
  /// Global subdomain id, unique across all ranks (orders the +1/-1 signs of
  /// the compatibility constraints and names the subdomain in messages).
  int id = -1;
  /// Global ids (in the owned DOF map given to setTopology()) of the
  /// subdomain's free DOFs, without duplicates. Prescribed DOFs are
  /// eliminated by the caller. Local DOF index = position in this vector.
  std::vector<GO> dofs;
  /// Per local DOF: 1 = primal (assembled globally, coarse space), 0 = not.
  /// A DOF must be primal in every subdomain that has it, or in none.
  std::vector<char> primal;
  /// Local stiffness on MPI_COMM_SELF: row, range and domain map = the
  /// contiguous map 0..n-1 (n = dofs.size()), fill-complete. The caller
  /// updates its values before each numeric(); the sparsity pattern must stay
  /// the one seen by setTopology().
  Teuchos::RCP<CrsMatrix> K;
  /// Optional (empty = none), per local DOF: 1 = rows from
  /// FetiDpSolver::setConstraintRows() may touch this DOF (e.g. the DOFs of
  /// contact surface nodes). Such DOFs count as dual interface DOFs in the
  /// Dirichlet preconditioner, so that it sees those rows; entries on other
  /// DOFs are exact in F but ignored by the preconditioner.
  std::vector<char> constrainable;
  /// Spatial dimension of the mesh, 2 or 3 (the same in every subdomain).
  /// Needed, with `component`, for edge and face averages ("Primal
  /// Constraints" other than "Vertices"): it decides what an edge is.
  int dim = 0;
  /// Per local DOF: the displacement component 0..dim-1 it belongs to
  /// (averages are taken per component). Needed like `dim`.
  std::vector<int> component;
  /// dim values per local DOF: the coordinates of its node, for the
  /// rotational edge / face constraints ("Rotational Constraints").
  std::vector<double> coordinates;
};

/// How one extra row enters the next solve() beyond its active flag
/// (FetiDpSolver::setConstraintCoupling(); doc/feti-dp.md "Coupled rows").
/// The dual problem's unknowns x live on the active rows; by default an
/// active row's multiplier is its unknown and its equation (B u)_row = c_row,
/// an inactive row's multiplier is zero. A coupled row replaces either:
///   multiplier:  λ_row = Σ_j a_j x_j  (j: active rows of this rank),
///   equation:    Σ_j g_j (B u)_j − compliance · x_row = c_row  (active rows).
/// Rows are LIDs of the caller's row map on this rank.
struct CoupledRow {
  LO row = 0;                                      ///< the row (LID in the row map)
  std::vector<std::pair<LO, double>> multiplier;   ///< (j, a_j); empty: the default
  std::vector<std::pair<LO, double>> equation;     ///< (j, g_j); empty: the default
  double compliance = 0.0;                         ///< >= 0, active rows only
};

/// One entry of an extra constraint row (FetiDpSolver::setConstraintRows()):
/// coefficient `coef` of local DOF `dof` of one subdomain in the row with
/// global id `row` (a GID of the caller's row map).
struct ConstraintEntry {
  GO row;       ///< the row's global id in the row map
  LO dof;       ///< local DOF index in the subdomain (FetiSubdomain::dofs order)
  double coef;  ///< the coefficient of that DOF in the row
};

/// FETI-DP solver for K u = b, K = sum_s R_s^T K^s R_s (the globally
/// assembled stiffness of the subdomains given to setTopology()).
///
/// Unknowns and constraints (doc/feti-dp.md):
///  - every subdomain keeps its own copy of its DOFs; the primal DOFs are
///    assembled globally (coarse space);
///  - one Lagrange multiplier (LM) per pair of subdomains sharing a
///    non-primal DOF ("fully redundant" compatibility constraints, row
///    u^s_j - u^t_j = 0 with +1 for the subdomain of smaller id). A DOF shared
///    by m subdomains gets m(m-1)/2 rows. In 2-D with all cross points primal
///    every non-primal interface DOF has m = 2, so this equals the
///    non-redundant choice;
///  - extra rows B_c u = c (e.g. contact; setConstraintRows()): general
///    lists of (subdomain, local DOF, coefficient) entries on remainder
///    and/or primal DOFs, with a right-hand side c and an active mask
///    (setConstraintState()). An inactive row's multiplier is restrained
///    to zero: F, d and the preconditioner are masked, F -> P F P,
///    d -> P (B K~^{-1} f~ - c), M^{-1} -> P M^{-1} P. This class does not
///    decide which rows are active (an inequality is the caller's active
///    set), nor what the rows mean (doc/architecture.md). With extra rows the
///    problem is the saddle point K u + B_c^T mu = b, B_c u = c (active
///    rows; mu = 0 on the others), mu from constraintMultipliers().
///
/// K~^{-1} f~ with precomputed Phi^s = K_rr^{-1} K_rPi (r = remainder = not
/// primal):  x_r = K_rr^{-1} f_r;  g_Pi = f_Pi - sum_s R_Pi^T K_Pir x_r;
/// u_Pi = S_PiPi^{-1} g_Pi (coarse solve, S_PiPi = sum_s R^T (K_PiPi - K_Pir
/// Phi) R assembled over the primal map);  u_r = x_r - Phi u_Pi^s.
///
/// Lifecycle: constructor (parameters) -> setTopology() (once per DOF
/// pattern) -> numeric() (after each change of the K values) -> solve()
/// (any number of right-hand sides). Every method except the accessors is
/// collective over the communicator; an error on one rank (e.g. a singular
/// subdomain) is raised on every rank with the same message.
///
/// Primal constraints ("Primal Constraints", doc/feti-dp.md "Primal
/// constraints: vertices, edges, faces"): the caller's primal DOFs
/// (vertices) and, unless "Vertices", the averages over the edges (and in
/// 3-D faces) of the interface, one per displacement component, found by
/// findEdgeFaceConstraints() from the DOF sharing alone, and (with coordinates)
/// the rigid rotations of each edge / face. Each such constraint value
/// becomes an explicit DOF by a change of basis (ChangeOfBasis, Klawonn &
/// Widlund 2006): K^s -> T^T K^s T; b, u and the extra rows are transformed
/// here, so the caller sees the original DOFs only.
///
/// Floating subdomains are not treated with a kernel: the caller must make
/// every K_rr^s nonsingular by choosing enough primal DOFs (doc/feti-dp.md,
/// "Primal nodes"; the analysis package does it in selectPrimalNodes()).
class FetiDpSolver {
 public:
  /// Statistics of one solve(). Times in seconds, maximum over the ranks.
  struct Info {
    int iterations = 0;             ///< Belos iterations (0 without interface or for d = 0)
    double relativeResidual = 0.0;  ///< Belos' achieved relative residual ||d - F lambda|| / ||d||
    /// CG broke down (F indefinite) and GMRES solved the system
    /// (Belos/GMRES on CG Breakdown); iterations count both.
    bool gmresAfterBreakdown = false;
    /// The coupled rows made the dual problem nonsymmetric and GMRES solved
    /// it in place of the configured symmetric solver (setConstraintCoupling()).
    bool gmresForCoupledRows = false;
    /// Lanczos estimate of the condition number of the preconditioned F from
    /// the CG coefficients (Belos "Estimate Condition Number" = true with
    /// Solver Type CG); -1 otherwise.
    double conditionEstimate = -1.0;
    double setupSeconds = 0.0;      ///< the last numeric() (local + coarse + Dirichlet factorisations)
    double solveSeconds = 0.0;      ///< this solve(), all of it
    // breakdown of setupSeconds
    double localFactorSeconds = 0.0;      ///< K_rr^s (or K^s with Schur rows) factorisations, Phi^s and S_PiPi^s (this rank's subdomains)
    double coarseFactorSeconds = 0.0;     ///< coarse assembly + factorisation
    double dirichletFactorSeconds = 0.0;  ///< K_II^s factorisations (Dirichlet preconditioner)
    // breakdown of solveSeconds
    double belosSeconds = 0.0;           ///< the Belos iterations (incl. F and M^{-1} applications)
    double localSolveSeconds = 0.0;      ///< K_rr^{-1} solves or condense / expand pairs (F applications and setup/recovery of solve())
    double coarseSolveSeconds = 0.0;     ///< coarse solves incl. their communication, whole solve()
    double preconditionerSeconds = 0.0;  ///< M^{-1} applications (includes the K_II^{-1} solves)
    int operatorApplications = 0;        ///< F applications by Belos
    int preconditionerApplications = 0;  ///< M^{-1} applications by Belos
    /// Factorisations of the subdomain matrices since setTopology(): the
    /// fewest and the most of any subdomain (all ranks). A linear material
    /// with contact rows is factorised once per analysis (1 and 1).
    int minLocalFactorizations = 0;
    int maxLocalFactorizations = 0;  ///< see minLocalFactorizations
  };

  /// Every parameter with its default and doc string:
  ///  - "Method": "Automatic" (default: FETI-DP unless the caller selects
  ///    BDDC by setAutomaticMethod()) | "FETI-DP" (iterate on the
  ///    multipliers) | "BDDC" (iterate on the interface displacements with
  ///    the same blocks; no extra rows, vertices only; DDC_FetiDpBddc.cpp);
  ///  - "Preconditioner": "Dirichlet" (default) | "Lumped" | "None";
  ///  - "Scaling": "Automatic" (default: multiplicity on compatibility
  ///    rows, stiffness weights on extra rows) | "Multiplicity" |
  ///    "Stiffness" (JumpOperator::computeWeights() in DDC_FetiDpScaling.cpp);
  ///  - "Primal Constraints": "Automatic" (default: "Vertices and
  ///    Edges") | "Vertices" | "Vertices and Edges" |
  ///    "Vertices, Edges and Faces" (in 2-D there are no faces, so it
  ///    equals "Vertices and Edges");
  ///  - "Rotational Constraints": bool (true): the rotations of each edge /
  ///    face too (needs FetiSubdomain::coordinates);
  ///  - "Local Singularity Threshold": double (1e13);
  ///  - "Local Schur Complement": bool (true): S_PiPi^s from a partial
  ///    factorisation of K^s and K~^{-1} by condensation / expansion, where
  ///    the local solver can (DirectSolver::setSchurIndices(), MUMPS);
  ///    otherwise K_rr^s and the dense Phi^s;
  ///  - "Belos": {"Solver Type": "CG" | "GMRES" | "MINRES", "Convergence
  ///    Tolerance" (1e-10), "Maximum Iterations" (500), "Verbosity" (0),
  ///    "Output Frequency" (-1)}, and any other parameter of the chosen
  ///    Belos solver (its getValidParameters(), same type), passed through;
  ///  - "Local Solver", "Coarse Solver": DirectSolverFactory {Type, ...}
  ///    sublists, Type "CHOLMOD" (local) and "MUMPS" (coarse) by default.
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();

  /// \param comm the communicator of the whole problem (the owned DOF map's).
  /// \param params validated against getValidParameters() (this level and
  ///        every sublist), defaults filled in.
  /// \param path parameter path of `params` for messages, e.g. "Solver/FETI-DP".
  /// \throws InputError naming the full parameter path for a misspelt or
  ///         mistyped parameter or an unknown enumeration value (e.g. an
  ///         unknown "Belos/Solver Type").
  FetiDpSolver(Teuchos::RCP<const Teuchos::Comm<int>> comm, Teuchos::ParameterList& params,
               const std::string& path);
  /// As above, with the back ends of "Local Solver" and "Coarse Solver"
  /// taken from `solvers` instead of DirectSolverFactory::withBuiltins(): a
  /// host adds its own sparse direct solver with DirectSolverFactory::add()
  /// (as Belos::SolverFactory::addFactory does for Krylov solvers) and names
  /// it in "Local Solver/Type" or "Coarse Solver/Type". Its sublist is
  /// validated against the factory's entry. The local solvers must be exact:
  /// FETI-DP's operator F is only as accurate as K_rr^{-1}.
  FetiDpSolver(Teuchos::RCP<const Teuchos::Comm<int>> comm, Teuchos::ParameterList& params,
               const std::string& path, DirectSolverFactory solvers);
  ~FetiDpSolver();
  FetiDpSolver(const FetiDpSolver&) = delete;
  FetiDpSolver& operator=(const FetiDpSolver&) = delete;

  /// Collective. Take the subdomains owned by this rank (zero, one or
  /// several) and build everything that depends only on the DOF pattern: DOF
  /// multiplicities, interface, compatibility constraints B (+1/-1 entries),
  /// the distributed LM map, the distributed primal map, the splits of each
  /// K^s into remainder / primal blocks and, for the Dirichlet
  /// preconditioner, into interior / dual-interface blocks, the patterns of
  /// the local and coarse matrices. The symbolic factorisations run in the
  /// next numeric() (some orderings look at values) and are reused by every
  /// later numeric().
  /// \param local the subdomains of this rank (see FetiSubdomain).
  /// \param ownedMap the one-to-one distributed map of all global DOFs of the
  ///        problem (the layout of b and u in solve()).
  /// \throws std::invalid_argument (on every rank) if a subdomain is
  ///         inconsistent: sizes, DOFs not in ownedMap, duplicate DOFs or
  ///         subdomain ids, a DOF primal in one subdomain but not in
  ///         another, K not fill-complete / not n x n, missing or
  ///         inconsistent dim / component / coordinates with edge or face
  ///         constraints.
  void setTopology(std::vector<FetiSubdomain> local, Teuchos::RCP<const Map> ownedMap);

  /// What "Primal Constraints" = Automatic stands for (Vertices and Edges
  /// unless set here): the caller, which chooses the primal vertices, knows
  /// the partition. An explicit choice is kept. Before setTopology().
  void setAutomaticPrimalConstraints(PrimalConstraints choice);
  /// The primal constraints in use ("Automatic" resolved).
  PrimalConstraints primalConstraints() const;

  /// What "Method" = Automatic stands for: FETI-DP unless the caller, which
  /// knows the partition and whether extra rows will come, selects BDDC
  /// here (the app does on many subdomains in 3-D without contact,
  /// doc/feti-dp.md "BDDC"). BDDC is taken only where the other options
  /// allow it (Preconditioner = Dirichlet, Scaling not Stiffness, Primal
  /// Constraints Automatic or Vertices); it then sets "Primal Constraints" =
  /// Automatic to Vertices and the MUMPS coarse solve to single precision
  /// unless the parameters say otherwise. An explicit "Method" is kept.
  /// Before setTopology(). \returns whether BDDC is now the method.
  bool setAutomaticMethod(bool bddc);
  /// True if the Krylov solver iterates on the interface displacements
  /// (BDDC), false for the multipliers (FETI-DP); "Automatic" resolved.
  bool usesBddc() const;

  /// Collective. After the caller updated the K values: factorise every
  /// K_rr^s, compute Phi^s = K_rr^{-1} K_rPi (one multi-RHS solve) and
  /// S_PiPi^s = K_PiPi - K_Pir Phi^s, assemble the coarse S_PiPi as a
  /// distributed CrsMatrix over the primal DOFs and factorise it (coarse
  /// solver), factorise K_II^s (Dirichlet preconditioner), compute the
  /// scaling weights.
  /// \throws SolverError naming the subdomain id if a K_rr^s is singular
  ///         ("the corner rule could not fix this subdomain's rigid modes"),
  ///         or if the coarse matrix cannot be factorised.
  void numeric();

  /// Collective. Solve K u = b.
  /// \param b right-hand side in the ownedMap layout. Nonzero entries on DOFs
  ///        that belong to no subdomain are an error (std::invalid_argument).
  /// \param u solution in the ownedMap layout (0 on DOFs in no subdomain);
  ///        the copies of a dual interface DOF are averaged.
  /// \pre numeric() has been called after the last change of the K values.
  /// \throws SolverError if Belos does not converge (message: iterations,
  ///         achieved residual, tolerance, the parameter paths to change).
  Info solve(const Vector& b, Vector& u);

  /// "Belos/Convergence Tolerance", the tightest relative residual a solve()
  /// is asked for.
  double convergenceTolerance() const;
  /// The relative tolerance ||d - F lambda|| / ||d|| of the next solve()s,
  /// in [convergenceTolerance(), 1): an inexact Newton method loosens it
  /// when the Newton residual does not need more (doc/user-guide.md
  /// "Newton"). Not collective, but every rank must set the same value.
  /// \throws std::invalid_argument outside that range.
  void setSolveTolerance(double tol);

  /// Collective. Replace the extra constraint rows (e.g. the contact rows of
  /// one load step). Call after setTopology(). The factorisations of the
  /// last numeric() stay valid (the rows do not change the subdomain
  /// matrices); the next solve() recomputes the rows' weights in the
  /// preconditioner. The LM map is rebuilt: compatibility rows, then this
  /// rank's extra rows.
  /// \param rowMap one-to-one distributed map of the rows (any GIDs); a row
  ///        is owned by the rank that sets its state and reads its
  ///        multiplier. The rows of this rank are rowMap's local elements.
  /// \param entries per local subdomain (same order as in setTopology()):
  ///        the entries of that subdomain's part of the rows. A row may have
  ///        entries in any subdomains on any ranks (a slave and a master
  ///        counterpart in different subdomains); a DOF shared by several
  ///        subdomains needs its entry in one of them only.
  /// \throws std::invalid_argument (every rank) for a row not in rowMap, a
  ///         local DOF out of range or a non-finite coefficient.
  void setConstraintRows(Teuchos::RCP<const Map> rowMap, const std::vector<std::vector<ConstraintEntry>>& entries);

  /// Collective. Active flags and right-hand sides c of this rank's extra
  /// rows (one per local element of the row map, in LID order) for the next
  /// solve()s. Inactive rows are restrained to zero. Default after
  /// setConstraintRows(): every row active with c = 0.
  /// \throws SolverError (every rank) if an active row has no entry on any
  ///         subdomain DOF (it cannot be enforced).
  void setConstraintState(const std::vector<char>& active, const std::vector<double>& rhs);

  /// Collective; optional, after setConstraintState() (which clears it).
  /// Couples this rank's extra rows for the next solve()s (CoupledRow):
  /// the multipliers λ = T x and the equations G B u − E x = c of the
  /// dual unknowns x, so that F -> G F T + E, d -> G B K~^{-1} f~ − c,
  /// M^{-1} -> D G M^{-1} Gᵀ D (D a diagonal scaling of the compliant rows by
  /// their preconditioner's diagonal). T = Gᵀ keeps the dual problem
  /// symmetric (CG); otherwise solve() uses GMRES (Info::gmresForCoupledRows).
  /// \throws std::invalid_argument (every rank) for a row or column out of
  ///         range, a listed row twice, a multiplier column or an equation on
  ///         an inactive row, a negative or non-finite value.
  void setConstraintCoupling(const std::vector<CoupledRow>& rows);

  /// Multipliers of the extra rows from the last solve() (on the row map;
  /// exactly 0 for inactive rows without a coupled multiplier); null
  /// without extra rows.
  Teuchos::RCP<const Vector> constraintMultipliers() const;

  /// Timings of the last numeric() (setup fields of Info only).
  const Info& setupInfo() const;

  // ---- accessors (for tests and diagnostics); valid after setTopology() ----

  /// Distributed map of the Lagrange multipliers (one per constraint row);
  /// each row is owned by the owner of its DOF in ownedMap.
  Teuchos::RCP<const Map> lmMap() const;
  /// Distributed map of the primal DOFs, GIDs = their global DOF ids, each
  /// owned by the DOF's owner in ownedMap.
  Teuchos::RCP<const Map> primalMap() const;
  /// Global number of dual DOFs: non-primal DOFs shared by >= 2 subdomains.
  GO numDualDofs() const;
  /// Global number of edge/face constraints (averages and rotations) among
  /// the primal DOFs (0 for "Vertices"); primalMap() holds vertex DOFs and
  /// these.
  GO numEdgeFaceConstraints() const;
  /// Apply B to a field given per subdomain copy: field[i] has one value per
  /// local DOF of the i-th subdomain passed to setTopology() on this rank.
  /// Returns (B field) on lmMap(). A continuous field (the same value in
  /// every copy of a DOF) gives 0. Collective.
  Teuchos::RCP<Vector> applyB(const std::vector<std::vector<double>>& field) const;
  /// The operator F = B K~^{-1} B^T on lmMap() (valid after numeric(); it
  /// refers to this solver and must not outlive it).
  Teuchos::RCP<const Tpetra::Operator<Scalar, LO, GO, Node>> fOperator() const;
  /// The preconditioner M^{-1} on lmMap() (null for "None"); same lifetime.
  Teuchos::RCP<const Tpetra::Operator<Scalar, LO, GO, Node>> preconditioner() const;

  /// Implementation detail (declared public only so that the operator
  /// classes in the .cpp can refer to it).
  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace ddc
