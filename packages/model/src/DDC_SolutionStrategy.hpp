// Solution strategies behind one interface: how a Newton iteration of the
// analysis assembles and solves for its correction (doc/user-guide.md,
// "Solution method"). The Newton driver (load stepping, bisection,
// convergence criteria, the contact active set, reporting) lives in
// ddc::Analysis and knows only this interface:
//
//  - Monolithic: the global tangent (a distributed Tpetra::CrsMatrix with the
//    contact multipliers appended) solved by a direct or iterative back end
//    of DirectSolverFactory;
//  - FETI-DP: the subdomain stiffness matrices solved by FetiDpSolver; the
//    strategy owns the contact rows of each step and the mapping of each
//    contact multiplier between the model's DOF vector and FETI-DP's
//    constraint rows, so a multiplier lives in one place for the driver: the
//    model's vector.
#pragma once

#include <Teuchos_Comm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "DDC_DirectSolver.hpp"
#include "DDC_FetiDpSolver.hpp"
#include "DDC_Model.hpp"
#include "DDC_Substructuring.hpp"

namespace ddc {

/// What one linear solve of a strategy cost.
struct StrategySolveInfo {
  int iterations = 0;         ///< Krylov / dual iterations (0 for a direct solve)
  /// Condition estimate of the preconditioned dual operator from the CG
  /// coefficients (FETI-DP with "Belos/Estimate Condition Number"); -1: none.
  double conditionEstimate = -1.0;
  double setupSeconds = 0.0;  ///< factorisation / preconditioner set-up
  double solveSeconds = 0.0;  ///< the solve itself
  /// FETI-DP breakdown: local, coarse, Dirichlet factorisation; local
  /// solves, coarse solves, preconditioner applications (zeros otherwise).
  std::array<double, 6> feti{{0, 0, 0, 0, 0, 0}};
};

/// One way of solving the Newton systems of a Model.
class SolutionStrategy {
 public:
  virtual ~SolutionStrategy() = default;
  /// "Monolithic" or "FETI-DP".
  virtual std::string name() const = 0;
  /// Collective, once: everything that depends on the model's DOFs and
  /// partition (the global matrix, or the primal choice and the subdomain
  /// problems). `progress` prints a line on rank 0 (e.g. the FETI-DP
  /// coarse-problem size).
  virtual void setUp(std::shared_ptr<Model> model, const std::function<void(const std::string&)>& progress) = 0;
  /// Before the Newton iterations of a (sub)step: the contact pairing and
  /// frozen geometry of the step are known.
  virtual void beginIncrement() {}
  /// Assemble at u (Model::assemble()): the residual r and what solve()
  /// needs (the global tangent, or the subdomain matrices).
  /// \throws InadmissibleDeformation as Model::assemble().
  virtual AssemblyResult assemble(const Vector& u, double lambda, Vector& r, const Vector* prescribedStep) = 0;
  /// Solve K du = b for the last assembled state (b = −r, model layout,
  /// multipliers included).
  /// \throws SolverError from the back end.
  virtual StrategySolveInfo solve(const Vector& b, Vector& du) = 0;
  /// The configured relative tolerance of an iterative linear solve (FETI-DP's
  /// dual Krylov solve, a Belos back end); 0 for a direct solve.
  virtual double linearTolerance() const = 0;
  /// The relative tolerance of the next solve()s, in [linearTolerance(), 1)
  /// (the inexact Newton forcing term of ddc::Analysis); ignored by a direct
  /// solve.
  virtual void setSolveTolerance(double tol) = 0;
  /// Rows of a coarse problem this rank owns after setUp() (FETI-DP's primal
  /// DOFs); 0 for a strategy without one. For the distribution line.
  virtual long long coarseRowsOnThisRank() const { return 0; }
  /// A line for the end-of-run timing report (empty: none), from the
  /// accumulated breakdown of solve() (max over ranks, collective).
  virtual std::string timingReport(const std::array<double, 6>& breakdown) const {
    (void)breakdown;
    return "";
  }
  /// Dynamics: the inertia term of every following assemble() (null: none).
  /// The pointee stays valid and is updated in place by the caller between
  /// assemblies; a change of its tangentFactor makes solve() factorise again.
  void setInertia(const Inertia* inertia) { inertia_ = inertia; }

 protected:
  /// The factor c of M in the tangent of the last assembly (0 without
  /// inertia): a factorisation made for another c is stale.
  double tangentMassFactor() const { return inertia_ ? inertia_->tangentFactor : 0.0; }
  const Inertia* inertia_ = nullptr;
};

/// The MUMPS ordering of the monolithic system when "Solver/Linear
/// Solver/MUMPS/Ordering" is not given: METIS' nested dissection, whose
/// factors of 3-D stiffness matrices are smaller and faster than those of
/// the orderings inside Debian's MUMPS (doc/performance.md). The MUMPS
/// back end's own default stays "Auto": on the FETI-DP coarse matrix PORD
/// is the faster.
inline const char* monolithicMumpsOrdering() { return "METIS"; }

/// Validate the "Solver" list (in place) against the contact formulation and
/// create the strategy with its solver back ends, before the model exists,
/// so that a wrong combination or a misspelt solver parameter stops before
/// any work. SolutionStrategy::setUp() binds it to the model.
/// \throws InputError naming the parameter paths.
std::unique_ptr<SolutionStrategy> makeSolutionStrategy(Teuchos::RCP<const Teuchos::Comm<int>> comm,
                                                       Teuchos::ParameterList& solverParams,
                                                       const ContactOptions& contact);

}  // namespace ddc
