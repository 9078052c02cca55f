// The loop over the steps of a run, quasi-static or dynamic:
//
//   propose   the step controller proposes the next (sub)step;
//   solve     Newton solves it (DDC_Newton.hpp) from the last accepted state;
//   judge     the converged step is measured (energy, contact summary, the
//             step-end pairing, the frozen-geometry error) and the
//             controller accepts it, repeats it or sends it back smaller;
//             a Newton failure sends it back smaller;
//   accept    the state moves on (displacements, internal force, reactions,
//             external work, the integrator), the step's record joins the
//             history, and the observers are told.
//
// Everything that reacts to a step — history, VTK, Exodus II, checkpoints,
// progress lines, stop requests, a host's monitoring — is a StepObserver
// (DDC_StepObserver.hpp). The loop's state (RunState) is one object: what
// the steps carry forward, and with the controller's state what a
// checkpoint holds.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "DDC_Dynamics.hpp"
#include "DDC_Error.hpp"
#include "DDC_InitialPenetration.hpp"
#include "DDC_Newton.hpp"
#include "DDC_RunTiming.hpp"
#include "DDC_SolutionStrategy.hpp"
#include "DDC_StepController.hpp"
#include "DDC_StepObserver.hpp"
#include "DDC_StepRecord.hpp"

namespace ddc {

/// What the steps carry forward (the state after the last accepted step).
struct RunState {
  Teuchos::RCP<Vector> u;         ///< displacements, contact multipliers appended (model's owned map)
  Teuchos::RCP<Vector> fint;      ///< internal force f_int(u), all DOFs
  /// The force the prescribed DOFs exert: f_int, and in dynamics also the
  /// inertia and damping of the prescribed nodes (M a + C v).
  Teuchos::RCP<Vector> reaction;
  double externalWork = 0.0;      ///< StepRecord::externalWork so far
  /// The contact slots at convergence of the last step, before its step-end
  /// re-pairing (what contact_nodes.csv shows).
  std::vector<ContactSlot> convergedSlots;
  std::vector<StepRecord> history;       ///< one record per accepted step
  std::vector<double> controllerState;   ///< StepController::saveState() after the last accepted step
  double wallOffset = 0.0;        ///< a restart's wall times go on from the checkpoint's
};

/// Test seams of the loop (fault injection); a production run has none.
class StepFaults {
 public:
  virtual ~StepFaults() = default;
  /// Before step `step` is attempted (e.g. raise a signal).
  virtual void beforeAttempt(int step) = 0;
  /// A failure the attempt of step `step` reports instead of being solved ("": solve it).
  virtual std::string injectedFailure(int step) = 0;
};

/// How the loop describes the run in its messages.
struct StepLoopSettings {
  std::string stepping = "Load Stepping";  ///< the parameter list of the steps (or "Dynamics")
  std::string factorName = "load factor";  ///< what the steps advance ("time" in dynamics)
  int numSteps = 0;                        ///< the planned steps (for "no converged step")
  double finalValue = 0.0;                 ///< where they end
  std::string estimatedMemory;             ///< "estimated 1.2 GiB per rank", for the activity of a step
  /// Appended to the message of a step Newton could not solve (a likely
  /// cause the caller knows of, e.g. a nearly incompressible body); "" for none.
  std::string failureNote;
};

/// The loop over the steps (see the top of this file).
class StepLoop {
 public:
  /// \param dynamics the dynamic part of the run (null: quasi-static)
  /// \param controller proposes and judges the steps
  StepLoop(std::shared_ptr<Model> model, SolutionStrategy& strategy, Dynamics* dynamics, NewtonSettings newton,
           std::unique_ptr<StepController> controller, StepLoopSettings settings);
  ~StepLoop();

  /// Tell `observer` of every event of run(), after those added before it.
  /// The loop does not own it; it must outlive run().
  void addObserver(StepObserver& observer) { observers_.push_back(&observer); }
  /// Test seams (null: none). Not owned.
  void setFaults(StepFaults* faults) { faults_ = faults; }

  /// Run every step from the current state (unloaded, or as restored) to
  /// the controller's end. Collective.
  /// \throws SolverError when a step fails for good (with the observers'
  ///         failed() text appended) or no step converged; what an observer
  ///         throws (OutputError, RunInterrupted)
  void run();

  /// The state; a restart sets it (and the controller's) before run(), then
  /// calls markRestarted().
  RunState& state() { return state_; }
  const RunState& state() const { return state_; }
  /// The state was restored from a checkpoint (observers continue their series).
  void markRestarted() { restarted_ = true; }
  bool restarted() const { return restarted_; }

  const std::vector<StepRecord>& history() const { return state_.history; }
  const Model& model() const { return *model_; }
  const SolutionStrategy& strategy() const { return strategy_; }
  const Dynamics* dynamics() const { return dynamics_; }
  Dynamics* dynamics() { return dynamics_; }
  StepController& controller() { return *controller_; }
  const StepController& controller() const { return *controller_; }
  const StepLoopSettings& settings() const { return settings_; }
  /// Which fields the records' outputs have (StepRecord.hpp).
  RunKind kind() const;
  /// Where the time went (maxima over ranks once run() returned).
  const RunTiming& timing() const { return timing_; }
  /// "step   3/10" (equal steps) or "step   3" (their number is not known).
  std::string stepLabel(int step) const;

 private:
  /// The attempts of the step being worked on (see attempt()).
  struct Attempts;
  struct Measured;
  void note(const std::string& line);
  /// The contact component's warnings (a pairing update's), as notes.
  void contactWarnings();
  /// Solve proposal `p`; true if Newton converged into trial_.
  bool attempt(const StepProposal& p, StepRecord& rec);
  /// Whether a step starts with every paired slave node active
  /// (Contact/Initial Contact State; ContactOptions::inContactOnlyWhenNoneActive).
  bool startsInContact() const;
  /// Newton failed on `p`: back to its start, a smaller step or give up.
  void newtonFailed(const StepProposal& p, const StepRecord& rec);
  /// The converged attempt's record and the contact state at convergence.
  Measured measure(const StepProposal& p, StepRecord& rec);
  /// The error control sent `p` back (verdict Repeat or Reduce).
  void sentBack(const StepProposal& p, const StepRecord& rec, StepVerdict verdict);
  /// Accept `p`: the state moves to trial_.
  void accept(const StepProposal& p, StepRecord& rec, Measured& m);
  /// External work of the step, trapezoidal in the load factor (collective).
  double externalWorkIncrement(const Vector& reaction0, const Vector& u0, double lambda0, const Vector& reaction1,
                               const Vector& u1, double lambda1) const;
  /// A failure of the run (called while the SolverError `e` is handled):
  /// back to the last accepted state, the observers' notes appended.
  [[noreturn]] void fail(const SolverError& e);
  /// Peak memory and the time maxima over ranks (collective).
  void reduceTiming();

  std::shared_ptr<Model> model_;
  SolutionStrategy& strategy_;
  Dynamics* dynamics_;
  std::unique_ptr<StepController> controller_;
  StepLoopSettings settings_;
  RunTiming timing_;
  Newton newton_;
  std::vector<StepObserver*> observers_;
  StepFaults* faults_ = nullptr;
  RunState state_;
  bool restarted_ = false;
  std::unique_ptr<Attempts> attempts_;
  Teuchos::RCP<Vector> trial_;  ///< the attempt's displacements
  double start_ = 0.0;          ///< run()'s start (steady clock, seconds)
  /// A dynamic run with contact that starts overlapped (warned after its
  /// first step too), and the total energy at its start.
  InitialPenetration penetration_;
  double initialEnergy_ = 0.0;
};

}  // namespace ddc
