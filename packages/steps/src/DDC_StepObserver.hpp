// What reacts to the steps of a run: the history file, the VTK and Exodus II
// series, checkpoints, the progress lines, a stop on a signal, a host's own
// monitoring. The step loop (DDC_StepLoop.hpp) proposes, solves, judges and
// accepts steps; it tells each registered observer what happened, in the
// order they were registered, and knows nothing of what they do with it
// (doc/embedding.md, "Observing the steps").
#pragma once

#include <string>

#include "DDC_StepController.hpp"
#include "DDC_StepRecord.hpp"

namespace ddc {

class StepLoop;

/// An attempt the loop did not accept, and what it does next.
struct RejectedStep {
  enum class Reason {
    NewtonFailed,   ///< Newton did not converge: a smaller step follows
    Repeat,         ///< the error control repeats it with the geometry of its end
    Reduce,         ///< the error control tries it smaller
  };
  Reason reason;
  const StepProposal& attempt;  ///< the attempt
  const StepProposal& next;     ///< the controller's next proposal
  const StepRecord& record;     ///< its record so far (failure, geometry error)
};

/// Receives the events of a StepLoop (see the top of this file). Every
/// function is called on every rank (collectively); the defaults do nothing.
/// An exception thrown by an observer ends the run (RunInterrupted does so
/// on purpose: a stop request).
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  /// Before the first step: the loop's state is the unloaded one, or the
  /// one a restart restored (StepLoop::restarted(); history() not empty).
  virtual void started(const StepLoop& /*loop*/) {}
  /// A line for the user (a warning, a Newton diagnostic).
  virtual void note(const StepLoop& /*loop*/, const std::string& /*line*/) {}
  /// An attempt was not accepted (RejectedStep::Reason).
  virtual void rejected(const StepLoop& /*loop*/, const RejectedStep& /*step*/) {}
  /// A step was accepted: `record` is its row, now the last of
  /// StepLoop::history(), and the loop's state is the state after it;
  /// `last` is true for the run's last step.
  virtual void accepted(const StepLoop& /*loop*/, const StepRecord& /*record*/, bool /*last*/) {}
  /// The run fails with `error` (a step no smaller attempt could save, a
  /// singular problem); the loop's state is that of the last accepted step.
  /// Returns text to append to the error (e.g. where its checkpoint is), or "".
  virtual std::string failed(const StepLoop& /*loop*/, const std::string& /*error*/) { return ""; }
  /// Every step was done (after the last accepted()).
  virtual void finished(const StepLoop& /*loop*/) {}
};

}  // namespace ddc
