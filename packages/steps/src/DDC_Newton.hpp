// Newton's method for one (sub)step of the step loop, merged with the
// contact active-set iteration (a primal-dual active set / semismooth
// Newton loop; doc/user-guide.md, "Solution method"; doc/contact.md, "Search,
// tracking and the active set"):
//
//   repeat: assemble r(u) and the tangent (the strategy's), solve K du = −r
//           (an inexact solve with the Eisenstat-Walker forcing term when
//           the solver is iterative), u += du, then update the contact
//           pairing (conventional element) and the active set on the
//           multipliers;
//   until:  ||r|| <= max(rtol ||r_0||, atol), |du.r| <= etol |du_0.r_0| and
//           the active set and pairing did not change.
//
// A cycling active set fails the step (the step controller then halves it);
// with Contact/Pairing Cycles = Freeze a cycling pairing is kept for the rest
// of the increment instead.
#pragma once

#include <Teuchos_ParameterList.hpp>
#include <functional>
#include <string>
#include <vector>

#include "DDC_Dynamics.hpp"
#include "DDC_RunTiming.hpp"
#include "DDC_SolutionStrategy.hpp"
#include "DDC_StepRecord.hpp"

namespace ddc {

/// The "Newton" parameters, resolved.
struct NewtonSettings {
  int maxIterations = 25;
  double residualTolerance = 1e-8;          ///< relative to the first residual of the step
  double absoluteResidualTolerance = 1e-10;  ///< force units
  double energyTolerance = 1e-16;            ///< |du.r| relative to the first iteration's
  bool printIterations = false;
  bool eisenstatWalker = true;      ///< Forcing Term = Eisenstat-Walker (else Constant)
  double maximumForcingTerm = 0.1;
  double forcingTermFloor = 0.1;
  /// Every valid parameter of the "Newton" list, with defaults and doc strings.
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  /// From a validated "Newton" list.
  /// \throws InputError when both residual tolerances or the energy
  ///         tolerance are 0 (round-off never meets them)
  static NewtonSettings fromParameters(const Teuchos::ParameterList& newton);
};

/// Newton's method on the model's residual (see the top of this file).
class Newton {
 public:
  /// Lines for the user (a failure, a frozen pairing): printed by the caller.
  using Note = std::function<void(const std::string&)>;
  /// \param dynamics the inertia of a dynamic run (null: quasi-static)
  /// \param timing accumulates the assembly and solve times
  Newton(Model& model, SolutionStrategy& strategy, NewtonSettings settings, Dynamics* dynamics, RunTiming& timing,
         Note note);
  /// Solve the (sub)step from load factor (time) `lambda0` to `lambda1`,
  /// starting from `u` (the last converged state, multipliers included).
  /// On convergence `u` holds the solution and true is returned; otherwise
  /// `u` is unchanged and `record.failure` says why. Fills the record's
  /// residualHistory, newtonIterations and dualIterations. Collective.
  /// \throws SolverError for a singular problem (a free rigid motion) and
  ///         from the solver back ends
  bool solve(double lambda0, double lambda1, Vector& u, StepRecord& record);

 private:
  struct Iteration;
  /// Assemble the residual `r` and the strategy's tangent at iterate `it`
  /// (`dp`: the prescribed increment of the first iteration). False, with
  /// the record's failure, on an inadmissible deformation.
  /// \throws SolverError for a free rigid motion (a singular tangent)
  bool assemble(int it, const Vector& u, double lambda0, double lambda1, Vector& r, const Vector* dp,
                StepRecord& record);
  /// Why Newton did not converge: the criterion not met, and whether the
  /// residual stagnated (for the failure message).
  std::string unmetCriterion(const std::vector<double>& residuals, double energy, double e0, double increment) const;
  /// The linear-solve tolerance of iteration `it` at residual `rnorm`
  /// (Eisenstat-Walker), set on the strategy.
  void setForcingTerm(int it, double rnorm, double r0);
  void printIteration(const Iteration& i) const;
  /// Follow the contact state to iterate `u`: the pairing (conventional
  /// element), the active set and the gross slip. False, with the record's
  /// failure, on a geometry the update cannot evaluate. Collective.
  bool updateContact(const Vector& u, bool conventional, Iteration& i, StepRecord& record);
  /// Set the record's failure to `why`, after the increment's gross slip
  /// if there was one (the cause behind most failures that follow it), and
  /// note it; returns false.
  bool fail(const std::string& why, StepRecord& record) const;
  /// Record the first gross slip of the increment (grossSlip_).
  void noteGrossSlip(int it);
  /// The contact checks after an update: true if the iteration may go on;
  /// false with `record.failure` set when the active set cycles.
  bool contactSettled(const Iteration& i, StepRecord& record);

  Model& model_;
  SolutionStrategy& strategy_;
  NewtonSettings settings_;
  Dynamics* dynamics_;
  RunTiming& timing_;
  Note note_;
  // State of the current solve().
  double eta_ = 0.0, solveTol_ = 0.0, mismatch_ = 1.0, rPrev_ = 0.0;  ///< forcing term
  bool forcing_ = false;
  std::vector<std::vector<int>> seen_;  ///< active sets after each change in this increment
  bool pairingFrozen_ = false;
  /// The first gross slip of this increment (a frictional pair whose every
  /// slave node in contact slips), for the failure messages; empty: none.
  std::string grossSlip_;
};

}  // namespace ddc
